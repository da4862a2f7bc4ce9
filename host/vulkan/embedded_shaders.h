#pragma once
#include <cstddef>
#include <cstdint>

namespace mixtrace {

// One compute shader's SPIR-V, embedded at build time (see CMakeLists.txt).
struct EmbeddedShader {
  const char* name;        // file name without extension, e.g. "intersect"
  const uint32_t* code;
  size_t sizeBytes;
};

// nullptr when no shader of that name was built.
const EmbeddedShader* findEmbeddedShader(const char* name);

}  // namespace mixtrace
