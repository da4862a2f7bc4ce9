#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 2: closest hit of every queued extension ray against the BVH; queues the rays the shade
// pass has work for (IntersectConstants.queueForShade).
#include "wavefront/intersect_interface.h"
#define PASS_BUFFERS INTERSECT_BUFFERS
#define PASS_CONSTANTS IntersectConstants
#include "gpu/buffers.glsl"
#include "shared/alpha.h"
#define BVH_ALPHA_PASSES(i, u, v, origin, direction) alphaPassesThrough(i, u, v, origin, direction)
#include "shared/bvh_traverse.h"
#include "shared/constants.h"
#include "gpu/queue_append.glsl"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= queues.rayCount[pc.queueIn]) return;
  uint path = rayQueue[pc.queueIn * pc.pathCount + i];
  HitRecord hit = traceClosest(rayOrigin[path], rayDirection[path], kFloatMax);
  hits[path] = hit;
  // The rays the shade pass has work for, compacted (where the renderer asks for it): lavapipe runs
  // the whole shade pass for a SIMD group with any lane in it, so a ray that escaped into no light
  // cost its group as much as a hit.
  if (pc.queueForShade != 0u && hit.triangle != kNoHit) {
    uint slot;
    QUEUE_APPEND(queues.shadeCount, slot);
    rayQueue[kShadeQueue * pc.pathCount + slot] = path;
  }
}
