#version 460
#extension GL_GOOGLE_include_directive : require
// Controlled mixture sampling, at the start of every training iteration: the pixel estimate the
// relative weights of the statistics divide by (shared/pixel_estimate.h), from the film so far.
// One invocation per pixel.
#include "cms/pixel_estimate_interface.h"
#define PASS_BUFFERS PIXEL_ESTIMATE_BUFFERS
#define PASS_CONSTANTS PixelEstimateConstants
#include "gpu/cms_buffers.glsl"
#include "gpu/buffers.glsl"

#define FILM_MEAN(i) film[2u * (i)]
#include "shared/pixel_estimate.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.pixelCount) return;
  int width = int(camera.width);
  pixelEstimate[i] = pixelEstimateAt(int(i) % width, int(i) / width, width, int(camera.height));
}
