#version 460
#extension GL_GOOGLE_include_directive : require
// Test kernel: the wavefront's BVH traversal on a batch of rays given by the host, so tests can
// compare the GPU's closest and any hits with brute force. Mode 0: closest hit into hits[];
// mode 1: any hit in (0, misPdf[i]) into misPdf[i] (1 blocked, 0 free).
#include "gpu/buffers.glsl"
#include "shared/bvh_traverse.h"
#include "shared/constants.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.pathCount) return;
  if (pc.mode == 0u) hits[i] = traceClosest(rayOrigin[i], rayDirection[i], kFloatMax);
  else misPdf[i] = traceAny(rayOrigin[i], rayDirection[i], misPdf[i]) ? 1.0 : 0.0;
}
