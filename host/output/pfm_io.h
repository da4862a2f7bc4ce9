#pragma once
// Portable float map (PFM) output: the simplest float image format (a text header and raw
// little-endian floats, rows bottom to top), which numpy reads in a few lines. The benchmark
// suite plots error maps from it.
#include <string>
#include <vector>

namespace mixtrace {

// One channel; `values` in row-major order, top row first. Throws Error when it cannot write.
void writePfmGray(const std::string& path, int width, int height, const std::vector<float>& values);

}  // namespace mixtrace
