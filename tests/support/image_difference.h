#pragma once
// How many channels of two renders of the same paths differ by more than float rounding: for
// tests whose claim is "the same image" (backends, schedules, specialised and general pipelines),
// not "the same expectation" (those use the statistical comparison, compare/image_compare.h).
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "output/image.h"

namespace mixtrace::testing {

// Channels of `a` that differ from `b` by more than relTolerance x max(floor, |b|); every channel
// of `a` counts as differing where the sizes differ.
inline size_t differingChannels(const Image& a, const Image& b, float relTolerance, float floor = 1.0f) {
  if (a.rgb.size() != b.rgb.size()) return a.rgb.size() + b.rgb.size();
  size_t n = 0;
  for (size_t i = 0; i < a.rgb.size(); ++i)
    n += std::abs(a.rgb[i] - b.rgb[i]) > relTolerance * std::max(floor, std::abs(b.rgb[i]));
  return n;
}

}  // namespace mixtrace::testing
