#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 5: folds each path's radiance into its pixel's running mean and sqrt of the sum of
// squared deviations (Welford's update: unlike a float sum of squares it does not cancel, so the
// variance of bright, nearly constant pixels stays meaningful; kept as sqrt(M2) so that it has the
// image's range, shared/film.h). A NaN or Inf sample is counted and enters as 0: it never reaches
// the image.
#include "wavefront/accumulate_interface.h"
#define PASS_BUFFERS ACCUMULATE_BUFFERS
#define PASS_CONSTANTS AccumulateConstants
#include "gpu/buffers.glsl"
#include "shared/film.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint path = gl_GlobalInvocationID.x;
  if (path >= pc.pathCount) return;
  vec3 l = radiance[path];
  if (any(isnan(l)) || any(isinf(l))) {
    atomicAdd(queues.nonFinite, 1u);
    l = vec3(0.0);
  }
  uint pixel = pc.pixelOffset + path;
  float n = float(pc.sampleIndex + 1u);   // every pixel gets one sample per sample pass
  vec3 mean = film[2u * pixel];
  vec3 delta = l - mean;
  mean += delta / n;
  film[2u * pixel] = mean;
  film[2u * pixel + 1u] = filmRootM2Update(film[2u * pixel + 1u], delta, l - mean);
}
