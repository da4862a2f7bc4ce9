#pragma once
// Portable float map (PFM) output: the simplest float image format (a text header and raw
// little-endian floats, rows bottom to top), which numpy reads in a few lines. The benchmark
// suite plots error maps from it.
#include <string>
#include <vector>

#include "output/image.h"

namespace mixtrace {

// One channel; `values` in row-major order, top row first. Throws Error when it cannot write.
void writePfmGray(const std::string& path, int width, int height, const std::vector<float>& values);

// Reads a colour ("PF") or grey ("Pf", copied to R, G, B) PFM of either byte order, at most
// maxPixels pixels. Throws Error naming what is wrong (not a PFM, a bad header, a short file).
Image readPfm(const std::string& path, size_t maxPixels);

}  // namespace mixtrace
