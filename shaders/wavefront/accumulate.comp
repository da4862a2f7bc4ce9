#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 5: adds each path's radiance to its pixel (sum and sum of squares, for the variance of
// the mean). A NaN or Inf sample is counted and dropped: it never reaches the image.
#include "gpu/buffers.glsl"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint path = gl_GlobalInvocationID.x;
  if (path >= pc.pathCount) return;
  vec3 l = radiance[path];
  if (any(isnan(l)) || any(isinf(l))) {
    atomicAdd(queues.nonFinite, 1u);
    return;
  }
  uint pixel = pc.pixelOffset + path;
  film[2u * pixel] += l;
  film[2u * pixel + 1u] += l * l;
}
