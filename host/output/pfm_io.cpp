#include "output/pfm_io.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "output/atomic_file.h"
#include "util/error.h"

namespace mixtrace {

void writePfmGray(const std::string& path, int width, int height, const std::vector<float>& values) {
  if (values.size() != size_t(width) * size_t(height)) throw Error("internal: PFM size mismatch");
  std::ostringstream out;
  // A negative scale marks little-endian data (every machine this runs on).
  out << "Pf\n" << width << " " << height << "\n-1.0\n";
  for (int y = height - 1; y >= 0; --y)
    out.write(reinterpret_cast<const char*>(values.data() + size_t(y) * width), std::streamsize(sizeof(float)) * width);
  writeFileAtomically(path, out.str());
}

Image readPfm(const std::string& path, size_t maxPixels) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open");
  auto bad = [&](const std::string& what) { return Error(path + ": not a readable PFM file (" + what + ")"); };
  std::string magic;
  long long width = 0, height = 0;
  double scale = 0.0;
  if (!(in >> magic) || (magic != "PF" && magic != "Pf")) throw bad("it does not start with PF or Pf");
  if (!(in >> width >> height) || width < 1 || height < 1) throw bad("no positive width and height");
  if (!(in >> scale) || !(scale != 0.0) || !std::isfinite(scale)) throw bad("no non-zero scale");
  in.get();  // the single whitespace character that ends the header
  if (size_t(width) > maxPixels || size_t(height) > maxPixels || size_t(width) * size_t(height) > maxPixels)
    throw bad(std::to_string(width) + "x" + std::to_string(height) + " is more than " + std::to_string(maxPixels) +
              " pixels");
  const int channels = magic == "PF" ? 3 : 1;
  const size_t count = size_t(width) * size_t(height) * size_t(channels);
  std::vector<float> raw(count);
  in.read(reinterpret_cast<char*>(raw.data()), std::streamsize(count * sizeof(float)));
  if (size_t(in.gcount()) != count * sizeof(float)) throw bad("the file ends before its pixels do");
  const bool bigEndian = scale > 0.0;   // the machines here are little-endian
  if (bigEndian)
    for (float& f : raw) {
      uint32_t b;
      std::memcpy(&b, &f, 4);
      b = __builtin_bswap32(b);
      std::memcpy(&f, &b, 4);
    }
  Image image{int(width), int(height)};
  for (long long y = 0; y < height; ++y)   // PFM rows run bottom to top
    for (long long x = 0; x < width; ++x) {
      const float* src = &raw[(size_t(height - 1 - y) * size_t(width) + size_t(x)) * size_t(channels)];
      float* dst = image.pixel(int(x), int(y));
      for (int c = 0; c < 3; ++c) dst[c] = src[channels == 3 ? c : 0];
    }
  return image;
}

}  // namespace mixtrace
