#version 460
#extension GL_GOOGLE_include_directive : require
// Test kernel: every texel row's element i through its accessor, written back whole
// (tests/texel_rows_interface.h).
#include "tests/texel_rows_interface.h"
#define PASS_BUFFERS TEXEL_ROWS_BUFFERS
#define PASS_CONSTANTS TexelRowsConstants
#include "gpu/buffers.glsl"
#include "shared/constants.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  bvhNodesOut[i] = BVH_NODE(i);
  triangleShadingOut[i] = TRIANGLE_SHADING(i);
  materialsOut[i] = MATERIAL(i);
  emittersOut[i] = EMITTER(i);
  lightBvhOut[i] = LIGHT_BVH_FROM_TEXELS(i);
  trianglesOut[i] = TRIANGLE(i);
  lightsOut[i] = LIGHT(i);
}
