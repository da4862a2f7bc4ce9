#pragma once
#include <cstddef>
#include <vector>

namespace mixtrace {

// A linear (scene-referred) RGB image: rows top to bottom, pixels left to right, three floats per
// pixel, so pixel (x, y) starts at rgb[3 * (y * width + x)].
struct Image {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<size_t>(w) * static_cast<size_t>(h) * 3, 0.0f) {}

  size_t pixelCount() const { return static_cast<size_t>(width) * static_cast<size_t>(height); }
  float* pixel(int x, int y) { return &rgb[3 * (static_cast<size_t>(y) * width + x)]; }
  const float* pixel(int x, int y) const { return &rgb[3 * (static_cast<size_t>(y) * width + x)]; }
};

}  // namespace mixtrace
