#version 460
#extension GL_GOOGLE_include_directive : require
// The viewer's display pass: for each window pixel of the columns [xBegin, xEnd), the film pixel
// under it (the film is letterboxed into the window, nearest pixel) shown as the chosen view,
// packed as 8-bit sRGB into the display buffer the host copies to the swapchain image.
#include "viewer/display_interface.h"
#define PASS_BUFFERS DISPLAY_BUFFERS
#define PASS_UNREAD_BUFFERS DISPLAY_UNREAD_BUFFERS
#define PASS_CONSTANTS DisplayConstants
#include "gpu/cms_buffers.glsl"
#include "gpu/buffers.glsl"
// The display reads only the cells' cluster selection, never a triangle's pmf.
#define EMITTERS_UNIFORM false
#include "shared/cms_sampling.h"
#include "shared/film.h"

layout(local_size_x = 8, local_size_y = 8) in;

vec3 encode(vec3 linear) {
  vec3 v = clamp(linear * pc.exposure, vec3(0.0), vec3(1.0));
  if (any(isnan(v))) return vec3(1.0, 0.0, 1.0);
  return vec3(srgbEncode(v.x), srgbEncode(v.y), srgbEncode(v.z));
}

vec3 cellView(uint pixel) {
  uint cell = firstCell[pixel];
  uint L = pc.clusterCount;
  if (!CMS_SELECTION || cell == kNoCell) return vec3(0.12);   // no cell: a miss, or no learning method
  if (pc.view == kViewCells) return hashColour(cell);
  if (pc.view == kViewCellSamples)   // log scale up to the cap, where a cell stops gathering
    return heatColour(log2(1.0 + float(cellSamples[cell])) / log2(1.0 + float(kCellSampleCap)));
  if (!cellSolutionValid(cell, L)) return vec3(0.25, 0.0, 0.25);   // not (yet) solved
  if (pc.view == kViewAlphaSum) return encode(cellAlphaSum(cell, L));
  uint best = 0u;   // kViewLikelyLight
  for (uint k = 1u; k < L; ++k)
    if (clusterSelectPmf(cell, L, k) > clusterSelectPmf(cell, L, best)) best = k;
  return hashColour(best + 7919u) * (0.4 + 0.6 * clusterSelectPmf(cell, L, best));
}

vec3 viewColour(uint pixel) {
  vec3 mean = film[2u * pixel];
  if (pc.view == kViewImage) return encode(mean);
  if (pc.view == kViewVariance) {
    // Relative standard deviation of the mean, log scale from 0.1 % to 100 %.
    float standardError = standardErrorOfMean(luminance(film[2u * pixel + 1u]), float(pc.spp));
    float relative = standardError / (luminance(mean) + 1e-3);
    return heatColour((log(max(relative, 1e-3)) / log(10.0) + 3.0) / 3.0);
  }
  return cellView(pixel);
}

void main() {
  uint x = pc.xBegin + gl_GlobalInvocationID.x;
  uint y = gl_GlobalInvocationID.y;
  if (x >= pc.xEnd || y >= pc.windowHeight) return;
  float scale = letterboxScale(pc.windowWidth, pc.windowHeight, pc.filmWidth, pc.filmHeight);
  vec2 offset = 0.5 * (vec2(pc.windowWidth, pc.windowHeight) - scale * vec2(pc.filmWidth, pc.filmHeight));
  vec2 f = (vec2(x, y) + 0.5 - offset) / scale;
  vec3 colour = vec3(0.05);   // letterbox
  if (f.x >= 0.0 && f.y >= 0.0 && f.x < float(pc.filmWidth) && f.y < float(pc.filmHeight))
    colour = viewColour(uint(f.y) * pc.filmWidth + uint(f.x));
  if (pc.divider != 0u && x == pc.xBegin) colour = vec3(1.0);
  uvec3 c = uvec3(clamp(colour, 0.0, 1.0) * 255.0 + 0.5);
  if (pc.redFirst == 0u) c = c.zyx;
  window[y * pc.windowWidth + x] = c.x | (c.y << 8u) | (c.z << 16u) | (255u << 24u);
}
