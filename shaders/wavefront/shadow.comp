#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 4: any-hit test of every queued shadow ray; an unoccluded one adds its contribution.
// Each path queues at most one shadow ray per depth, so the add needs no atomics.
#include "gpu/buffers.glsl"
#include "shared/bvh_traverse.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= queues.shadowCount) return;
  ShadowRay s = shadowQueue[i];
  if (!traceAny(s.origin, s.direction, s.tMax)) radiance[s.path] += s.contribution;
}
