#pragma once
// OpenEXR output and input of linear RGB images (FLOAT channels R, G, B; optionally each
// pixel's uncertainty as the standard error of its mean, standardError.R/G/B) with typed header
// attributes for provenance. The standard error, not the variance: it has the image's own range,
// where a float variance overflows above pixel values of ~1e19 and underflows below ~1e-19.
#include <map>
#include <string>
#include <vector>

#include "output/image.h"

namespace mixtrace {

// Extra header attributes. Names must not collide with the standard EXR attributes
// (channels, compression, dataWindow, ...); those are rejected by writeExr.
struct ExrMetadata {
  std::map<std::string, std::string> strings;
  std::map<std::string, int> ints;
  std::map<std::string, float> floats;
};

// More channels from another image of the same size: channel k of `names` holds component k of
// `image` (at most 3; e.g. the AOVs "albedo.R/G/B", "normal.X/Y/Z", "depth.Z").
struct ExrLayer {
  std::vector<std::string> names;
  const Image* image = nullptr;
};

// Writes `image` (and `standardError`, which must have the same size, when given, and `layers`)
// as 32-bit float channels. Throws mixtrace::Error when the file cannot be written.
void writeExr(const std::string& path, const Image& image, const ExrMetadata& meta,
              const Image* standardError = nullptr, const std::vector<ExrLayer>& layers = {});

// Reads channels `names` (1 to 3, all required) into components 0.. of an RGB image (the rest 0).
// Throws mixtrace::Error as readExr does, or when a channel is missing.
Image readExrChannels(const std::string& path, const std::vector<std::string>& names);

// Reads R, G, B (all three are required) and, into `standardError` when given, standardError.R/G/B,
// or the square root of variance.R/G/B from files of earlier versions (left empty — width 0 — when
// the file has neither). String/int/float attributes that are not standard EXR attributes go into
// `meta`. Throws mixtrace::Error (not an EXR file, missing channels, ...).
Image readExr(const std::string& path, ExrMetadata* meta = nullptr, Image* standardError = nullptr);

}  // namespace mixtrace
