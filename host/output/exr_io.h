#pragma once
// OpenEXR output and input of linear RGB images (FLOAT channels R, G, B; optionally
// variance.R, variance.G, variance.B) with typed header attributes for provenance.
#include <map>
#include <string>

#include "output/image.h"

namespace mixtrace {

// Extra header attributes. Names must not collide with the standard EXR attributes
// (channels, compression, dataWindow, ...); those are rejected by writeExr.
struct ExrMetadata {
  std::map<std::string, std::string> strings;
  std::map<std::string, int> ints;
  std::map<std::string, float> floats;
};

// Writes `image` (and `variance`, which must have the same size, when given) as 32-bit float
// channels. Throws mixtrace::Error when the file cannot be written.
void writeExr(const std::string& path, const Image& image, const ExrMetadata& meta, const Image* variance = nullptr);

// Reads R, G, B (all three are required) and, into `variance` when given, variance.R/G/B
// (left empty — width 0 — when the file has none). String/int/float attributes that are not
// standard EXR attributes go into `meta`. Throws mixtrace::Error (not an EXR file, missing
// channels, ...).
Image readExr(const std::string& path, ExrMetadata* meta = nullptr, Image* variance = nullptr);

}  // namespace mixtrace
