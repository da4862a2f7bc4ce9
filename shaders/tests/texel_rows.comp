#version 460
#extension GL_GOOGLE_include_directive : require
// The interface names the pair table's rows (shared/cms_pair_state.h), whose keys are 64-bit.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Test kernel: every texel row's element i through its accessor, written back whole
// (tests/texel_rows_interface.h).
#include "tests/texel_rows_interface.h"
#define PASS_BUFFERS TEXEL_ROWS_BUFFERS
#define PASS_CONSTANTS TexelRowsConstants
#define PASS_READS_SOLUTION_VIEWS
#include "gpu/cms_buffers.glsl"
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
  LightSelectionGpu s;
  s.pmf = LIGHT_SELECT_PMF(i);
  s.cdf = LIGHT_SELECT_CDF(i);
  s.cluster = LIGHT_CLUSTER(i);
  s.clusterPmf = LIGHT_CLUSTER_PMF(i);
  lightSelectionOut[i] = s;
  clustersOut[i] = CLUSTER(i);
  cellSolutionOut[i] = floatBitsToUint(CELL_SOLUTION(i));
  pairAlphaOut[i] = floatBitsToUint(PAIR_ALPHA(i));
  clusterDefaultsOut[i] = floatBitsToUint(CLUSTER_DEFAULT(i));
  TextureGpu t = TEXTURE(i);
  texturesOut[i] = uvec4(t.offset, t.width, t.height, t.sampling);
  texelsOut[i] = TEXEL(i);
  environmentOut[i] = floatBitsToUint(ENV_DATA(i));
}
