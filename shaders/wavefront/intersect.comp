#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 2: closest hit of every queued extension ray against the BVH.
#include "wavefront/intersect_interface.h"
#define PASS_BUFFERS INTERSECT_BUFFERS
#define PASS_CONSTANTS IntersectConstants
#include "gpu/buffers.glsl"
#include "shared/alpha.h"
#define BVH_ALPHA_PASSES(i, u, v, origin, direction) alphaPassesThrough(i, u, v, origin, direction)
#include "shared/bvh_traverse.h"
#include "shared/constants.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= queues.rayCount[pc.queueIn]) return;
  uint path = rayQueue[pc.queueIn * pc.pathCount + i];
  hits[path] = traceClosest(rayOrigin[path], rayDirection[path], kFloatMax);
}
