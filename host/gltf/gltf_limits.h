#pragma once
// What the glTF loader accepts from a file before it allocates or recurses: one place for every
// limit, so that a small hostile file can cost neither unbounded memory, time nor stack. Each is
// far above anything a real scene for this renderer needs.
#include <cstddef>
#include <cstdint>

namespace mixtrace {
namespace gltf {

// The scene file, and each external buffer or image file it names. tinygltf keeps a whole file
// in memory (twice, briefly), so this bounds the memory a file can claim by its size.
constexpr uint64_t kMaxFileBytes = uint64_t(1) << 30;  // 1 GiB

// [ and { nested deeper than this are refused before the JSON parser (which recurses per level)
// sees them. Real glTF needs about 8 levels; extras may add a few more.
constexpr int kMaxJsonNesting = 128;

// Decoded texels of one image (RGBA8: 4 bytes each, 16-bit PNGs twice that while decoding).
// 8192 x 8192 = 256 MiB of texels; the header is read before anything is decoded.
constexpr uint64_t kMaxImageTexels = uint64_t(8192) * 8192;

// An accessor without a bufferView is all zeros by the spec: it costs the file nothing, so its
// count is bounded here (accessors with data are bounded by their buffer, itself by kMaxFileBytes).
constexpr uint64_t kMaxDatalessAccessorElements = uint64_t(1) << 20;

}  // namespace gltf
}  // namespace mixtrace
