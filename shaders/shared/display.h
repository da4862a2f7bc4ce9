// The viewer's display pass (shaders/viewer/display.comp): what it shows and where. One pass per
// renderer writes the window columns [xBegin, xEnd) of a packed 8-bit display buffer, which the
// host copies into the swapchain image; the split view runs it twice, one half per method.
#ifndef MIXTRACE_SHARED_DISPLAY_H
#define MIXTRACE_SHARED_DISPLAY_H
#include "shared/dialect.h"
SHARED_BEGIN

// What a pixel shows.
const uint kViewImage = 0u;        // the film, exposed and sRGB-encoded (as the PNG preview)
const uint kViewVariance = 1u;     // relative standard deviation of the pixel's mean, false colour
const uint kViewCells = 2u;        // the cell of the pixel's first hit, hashed colours
const uint kViewAlphaSum = 3u;     // that cell's sum of alpha: the control variate's integral
const uint kViewLikelyLight = 4u;  // that cell's most likely light cluster, hashed colours
const uint kViewCellSamples = 5u;  // vertices behind that cell's statistics, log scale
const uint kViewCount = 6u;

struct DisplayConstants {
  uint windowWidth;   // the display buffer's extent
  uint windowHeight;
  uint filmWidth;
  uint filmHeight;
  uint xBegin;        // window columns this pass writes
  uint xEnd;
  uint view;          // kView*
  uint clusterCount;  // L (cell views)
  float exposure;     // linear scale before the sRGB curve
  uint spp;           // samples in the film (variance view)
  uint divider;       // 1: a white line at xBegin (the split)
  uint redFirst;      // 1: the swapchain is R8G8B8A8, else B8G8R8A8
};

// Window pixels per film pixel: the film is letterboxed into the window, as large as fits. The
// display pass maps window pixels to film pixels with it, and the viewer's pan uses it so that the
// picture follows the mouse (host/viewer/camera_controller.h).
SHARED_FN float letterboxScale(uint windowWidth, uint windowHeight, uint filmWidth, uint filmHeight) {
  return min(float(windowWidth) / float(filmWidth), float(windowHeight) / float(filmHeight));
}

// IEC 61966-2-1 sRGB encoding: linear segment below 0.0031308, power 1/2.4 above. The PNG
// previews and the viewer encode with it.
SHARED_FN float srgbEncode(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * pow(linear, 1.0f / 2.4f) - 0.055f;
}

// Colours for identifiers (cells, clusters): well spread, never black.
SHARED_FN vec3 hashColour(uint id) {
  uint h = id * 0x9E3779B1u;
  h ^= h >> 15u;
  h *= 0x85EBCA77u;
  h ^= h >> 13u;
  vec3 c;
  c.x = float(h & 255u) / 255.0f;
  c.y = float((h >> 8u) & 255u) / 255.0f;
  c.z = float((h >> 16u) & 255u) / 255.0f;
  return c * 0.8f + vec3(0.2f);
}

// A heat ramp for t in [0, 1]: black, red, yellow, white.
SHARED_FN vec3 heatColour(float t) {
  t = clamp(t, 0.0f, 1.0f);
  vec3 c;
  c.x = clamp(3.0f * t, 0.0f, 1.0f);
  c.y = clamp(3.0f * t - 1.0f, 0.0f, 1.0f);
  c.z = clamp(3.0f * t - 2.0f, 0.0f, 1.0f);
  return c;
}

SHARED_END
#endif
