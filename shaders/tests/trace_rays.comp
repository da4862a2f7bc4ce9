#version 460
#extension GL_GOOGLE_include_directive : require
// Test kernel: the wavefront's BVH traversal on a batch of rays given by the host, so tests can
// compare the GPU's closest and any hits with brute force (tests/trace_rays_interface.h).
#include "tests/trace_rays_interface.h"
#define PASS_BUFFERS TRACE_RAYS_BUFFERS
#define PASS_CONSTANTS TraceRaysConstants
#include "gpu/buffers.glsl"
#include "shared/bvh_traverse.h"
#include "shared/constants.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.rayCount) return;
  if (pc.mode == 0u) hits[i] = traceClosest(rayOrigin[i], rayDirection[i], kFloatMax);
  else misPdf[i] = traceAny(rayOrigin[i], rayDirection[i], misPdf[i]) ? 1.0 : 0.0;
}
