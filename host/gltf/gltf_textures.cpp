// glTF textures -> Texture: sampler wrap modes and magnification filter, image decoding, RGBA8 packing, average colour.
#include <array>
#include <cmath>
#include <climits>

#include <stb/stb_image.h>  // declarations only: stb_image is compiled into libstb

#include "gltf/gltf_internal.h"
#include "gltf/gltf_limits.h"

namespace mixtrace {
namespace gltf {
namespace {

uint32_t wrapMode(const LoadContext& ctx, int glWrap, int samplerIndex) {
  switch (glWrap) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return shared::kWrapRepeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return shared::kWrapClamp;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return shared::kWrapMirror;
    default:
      ctx.warning("sampler " + std::to_string(samplerIndex) + " has unknown wrap mode " + std::to_string(glWrap) +
                  "; using REPEAT");
      return shared::kWrapRepeat;
  }
}

// Whether the sampler's magFilter asks for the nearest texel (bilinear otherwise, and when absent:
// the spec leaves an undefined filter to the implementation).
bool nearestFilter(const LoadContext& ctx, int glFilter, int samplerIndex) {
  switch (glFilter) {
    case -1: return false;
    case TINYGLTF_TEXTURE_FILTER_NEAREST: return true;
    case TINYGLTF_TEXTURE_FILTER_LINEAR: return false;
    default:
      ctx.warning("sampler " + std::to_string(samplerIndex) + " has unknown magFilter " + std::to_string(glFilter) +
                  "; using LINEAR");
      return false;
  }
}

// sRGB transfer function decoded, for each 8-bit code.
const std::array<double, 256>& srgbToLinearTable() {
  static const std::array<double, 256> table = [] {
    std::array<double, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double c = i / 255.0;
      t[size_t(i)] = c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    }
    return t;
  }();
  return table;
}

uint32_t packRgba(uint32_t r, uint32_t g, uint32_t b, uint32_t a) { return r | (g << 8) | (b << 16) | (a << 24); }

}  // namespace

bool MaterialTable::convertTexture(int textureIndex, Texture& out) {
  const tinygltf::Model& model = ctx_.model;
  const tinygltf::Texture& texture = model.textures[size_t(textureIndex)];
  if (texture.source < 0 || size_t(texture.source) >= model.images.size()) {
    // e.g. a texture whose only image comes through an unsupported extension (EXT_texture_webp).
    ctx_.warning("texture " + std::to_string(textureIndex) + " has no usable image source; ignoring the texture");
    return false;
  }
  if (texture.sampler >= 0) {
    if (size_t(texture.sampler) >= model.samplers.size()) {
      ctx_.fail("texture " + std::to_string(textureIndex) + " refers to sampler " + std::to_string(texture.sampler) +
                ", which does not exist");
    }
    const tinygltf::Sampler& sampler = model.samplers[size_t(texture.sampler)];
    out.wrapS = wrapMode(ctx_, sampler.wrapS, texture.sampler);
    out.wrapT = wrapMode(ctx_, sampler.wrapT, texture.sampler);
    out.nearest = nearestFilter(ctx_, sampler.magFilter, texture.sampler);
  } else {
    out.wrapS = shared::kWrapRepeat;  // spec: no sampler means repeat wrapping
    out.wrapT = shared::kWrapRepeat;
  }
  decodeImage(ctx_, texture.source, out);
  return true;
}

void decodeImage(const LoadContext& ctx, int imageIndex, Texture& texture) {
  const tinygltf::Image& image = ctx.model.images[size_t(imageIndex)];
  const bool namedFile = !image.uri.empty() && image.uri.rfind("data:", 0) != 0;
  const std::string name = "image " + std::to_string(imageIndex) + (namedFile ? " (" + image.uri + ")" : "");
  const unsigned char* bytes = nullptr;
  size_t size = 0;
  if (image.bufferView >= 0) {
    bytes = bufferViewBytes(ctx, image.bufferView, size, name);
  } else {
    bytes = image.image.data();
    size = image.image.size();
  }
  if (size == 0) ctx.fail(name + " could not be read");
  if (size > size_t(INT_MAX)) ctx.fail(name + " is larger than 2 GiB");

  // The header says how much decoding will allocate: a few hundred compressed bytes can claim
  // gigabytes of texels, so the size is checked before anything is decoded.
  int headerWidth = 0, headerHeight = 0, headerComponents = 0;
  if (!stbi_info_from_memory(bytes, int(size), &headerWidth, &headerHeight, &headerComponents)) {
    const char* reason = stbi_failure_reason();
    ctx.fail(name + " could not be decoded: " + condenseMessage(reason ? reason : "unknown image format"));
  }
  if (headerWidth <= 0 || headerHeight <= 0 || uint64_t(headerWidth) * uint64_t(headerHeight) > kMaxImageTexels) {
    ctx.fail(name + " is " + std::to_string(headerWidth) + "x" + std::to_string(headerHeight) + ", more than the " +
             std::to_string(kMaxImageTexels) + "-texel limit");
  }

  // tinygltf::LoadImageData is stb_image inside libtinygltf; without options it expands to RGBA
  // and keeps 16 bits per channel for 16-bit PNGs.
  tinygltf::Image decoded;
  std::string err;
  std::string warnings;
  if (!tinygltf::LoadImageData(&decoded, imageIndex, &err, &warnings, 0, 0, bytes, int(size), nullptr)) {
    ctx.fail(name + " could not be decoded: " + condenseMessage(err));
  }
  const int components = decoded.component;
  const int bytesPerChannel = decoded.bits / 8;
  const size_t texelCount = size_t(decoded.width) * size_t(decoded.height);
  if (decoded.width <= 0 || decoded.height <= 0 || components < 1 || components > 4 ||
      (bytesPerChannel != 1 && bytesPerChannel != 2) ||
      decoded.image.size() != texelCount * size_t(components) * size_t(bytesPerChannel)) {
    ctx.fail(name + " decoded to an unsupported pixel format");
  }

  // Channel c of texel i as 8 bits (16-bit data rounded to the nearest 8-bit code).
  auto channel = [&](size_t i, int c) -> uint32_t {
    const size_t at = (i * size_t(components) + size_t(c)) * size_t(bytesPerChannel);
    if (bytesPerChannel == 1) return decoded.image[at];
    const uint32_t v = uint32_t(decoded.image[at]) | (uint32_t(decoded.image[at + 1]) << 8);  // stb: native (LE)
    return (v * 255u + 32767u) / 65535u;
  };
  texture.width = uint32_t(decoded.width);
  texture.height = uint32_t(decoded.height);
  texture.texels.resize(texelCount);
  const std::array<double, 256>& toLinear = srgbToLinearTable();
  glm::dvec3 sum(0.0);
  for (size_t i = 0; i < texelCount; ++i) {
    uint32_t r, g, b, a;
    if (components <= 2) {  // grey, grey + alpha
      r = g = b = channel(i, 0);
      a = components == 2 ? channel(i, 1) : 255u;
    } else {
      r = channel(i, 0);
      g = channel(i, 1);
      b = channel(i, 2);
      a = components == 4 ? channel(i, 3) : 255u;
    }
    texture.texels[i] = packRgba(r, g, b, a);
    sum += glm::dvec3(toLinear[r], toLinear[g], toLinear[b]);
  }
  texture.averageLinear = glm::vec3(sum / double(texelCount));
}

}  // namespace gltf
}  // namespace mixtrace
