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

// nullptr when no shader of that name was built: searches the product's table, then every
// registered one.
const EmbeddedShader* findEmbeddedShader(const char* name);

// Adds a table, ended by an entry with a null name, for findEmbeddedShader to search: the test
// kernels' (shaders/tests), which only tests link, register theirs at static initialisation.
void registerEmbeddedShaders(const EmbeddedShader* table);

}  // namespace mixtrace
