// exr_pixels_equal A.exr B.exr: whether two EXRs written by mixtrace hold the same pixels, bit for
// bit (R, G, B and, where either file has them, standardError.R/G/B). The header is not compared:
// renderSeconds and the other provenance attributes differ from run to run by design.
// Exit status: 0 identical, 1 different (the first differing value and the count are printed),
// 2 an error (unreadable file, different sizes, standard error in one file only).
//
// exr_pixels_equal --hash A.exr: prints a 64-bit FNV-1a hash of the same pixel data (size, then
// every value's bit pattern), so a record of renders can be compared by eye across machines.
// Used by scripts/bit_identity.sh, the check that a refactor leaves every image unchanged.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "output/exr_io.h"

namespace {

uint32_t bitsOf(float v) {
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  return bits;
}

// Compares two images value by value as bit patterns (so -0 differs from +0, and two NaNs with
// the same payload are equal). Returns the number of differing values; prints the first one.
size_t countDifferences(const mixtrace::Image& a, const mixtrace::Image& b, const std::string& planes) {
  static const char* const kChannel[3] = {"R", "G", "B"};
  size_t differing = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i) {
    if (bitsOf(a.rgb[i]) == bitsOf(b.rgb[i])) continue;
    if (differing++ == 0) {
      const size_t pixel = i / 3;
      std::printf("first difference: pixel (%zu, %zu) %s%s: %.9g (0x%08x) vs %.9g (0x%08x)\n",
                  pixel % size_t(a.width), pixel / size_t(a.width), planes.c_str(), kChannel[i % 3],
                  double(a.rgb[i]), bitsOf(a.rgb[i]), double(b.rgb[i]), bitsOf(b.rgb[i]));
    }
  }
  return differing;
}

uint64_t hashPixels(const mixtrace::Image& image, const mixtrace::Image& standardError) {
  uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bits
  auto add = [&hash](uint32_t word) {
    for (int byte = 0; byte < 4; ++byte) hash = (hash ^ ((word >> (8 * byte)) & 0xffu)) * 1099511628211ull;
  };
  add(uint32_t(image.width));
  add(uint32_t(image.height));
  for (float v : image.rgb) add(bitsOf(v));
  for (float v : standardError.rgb) add(bitsOf(v));
  return hash;
}

}  // namespace

int main(int argc, char** argv) {
  const bool hashOnly = argc == 3 && std::strcmp(argv[1], "--hash") == 0;
  if (argc != 3) {
    std::fprintf(stderr, "usage: exr_pixels_equal A.exr B.exr | exr_pixels_equal --hash A.exr\n");
    return 2;
  }
  try {
    mixtrace::Image errorA, errorB;
    if (hashOnly) {
      const mixtrace::Image a = mixtrace::readExr(argv[2], nullptr, &errorA);
      std::printf("%016llx\n", static_cast<unsigned long long>(hashPixels(a, errorA)));
      return 0;
    }
    const mixtrace::Image a = mixtrace::readExr(argv[1], nullptr, &errorA);
    const mixtrace::Image b = mixtrace::readExr(argv[2], nullptr, &errorB);
    if (a.width != b.width || a.height != b.height) {
      std::fprintf(stderr, "different sizes: %dx%d vs %dx%d\n", a.width, a.height, b.width, b.height);
      return 2;
    }
    if ((errorA.width == 0) != (errorB.width == 0)) {
      std::fprintf(stderr, "only one of the files has standard-error channels\n");
      return 2;
    }
    const size_t differing = countDifferences(a, b, "") + countDifferences(errorA, errorB, "standardError.");
    if (differing == 0) return 0;
    std::printf("%zu of %zu values differ\n", differing, a.rgb.size() + errorA.rgb.size());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}
