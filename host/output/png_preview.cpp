#include "output/png_preview.h"

#include <cmath>
#include <filesystem>
#include <vector>

#include "output/atomic_file.h"
#include "shared/display.h"
#include "util/error.h"

// libtinygltf imports the stb writer from libstb.so rather than exporting it, and the output layer
// does not link libstb, so the writer is compiled here — static, so it cannot clash with the
// copy in libstb.so that tinygltf loads.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace mixtrace {

unsigned char linearToSrgb8(float linear, float exposure) {
  if (!std::isfinite(linear)) return 0;
  float value = linear * exposure;
  if (!(value > 0.0f)) return 0;  // also catches NaN from a non-finite exposure
  if (value > 1.0f) value = 1.0f;
  return static_cast<unsigned char>(std::lround(shared::srgbEncode(value) * 255.0f));
}

namespace {

// stb's writers call this with pieces of the encoded file; collected so that the file is written
// in one go, atomically.
void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

std::vector<unsigned char> tonemapped(const std::string& path, const Image& image, float exposure) {
  if (image.width <= 0 || image.height <= 0 || image.rgb.size() != image.pixelCount() * 3)
    throw Error("cannot write '" + path + "': image is empty or its size does not match its pixels");
  std::vector<unsigned char> bytes(image.rgb.size());
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = linearToSrgb8(image.rgb[i], exposure);
  return bytes;
}

}  // namespace

void writePngPreview(const std::string& path, const Image& image, float exposure) {
  writePng8(path, image.width, image.height, tonemapped(path, image, exposure));
}

void writeJpegPreview(const std::string& path, const Image& image, float exposure) {
  const std::vector<unsigned char> rgb = tonemapped(path, image, exposure);
  std::string encoded;
  if (!stbi_write_jpg_to_func(appendBytes, &encoded, image.width, image.height, 3, rgb.data(), kJpegQuality))
    throw Error("cannot encode JPEG '" + path + "'");
  writeFileAtomically(path, encoded);
}

void writePng8(const std::string& path, int width, int height, const std::vector<unsigned char>& rgb) {
  if (width <= 0 || height <= 0 || rgb.size() != size_t(width) * size_t(height) * 3)
    throw Error("cannot write PNG '" + path + "': its size does not match its pixels");
  std::string encoded;
  if (!stbi_write_png_to_func(appendBytes, &encoded, width, height, 3, rgb.data(), width * 3))
    throw Error("cannot encode PNG '" + path + "'");
  writeFileAtomically(path, encoded);
}

std::string defaultPreviewPath(const std::string& exrPath) {
  return std::filesystem::path(exrPath).replace_extension(".png").string();
}

}  // namespace mixtrace
