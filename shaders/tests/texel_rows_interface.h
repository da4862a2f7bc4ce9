// Test kernel tests/texel_rows.comp: reads element i of every row read as texels (access TEXELS,
// shared/buffer_table.h) through its GLSL accessor (gpu/buffers.glsl) and writes it to a storage
// buffer of the same struct, so tests/gpu/texel_rows_test.cpp can compare the bits with the
// host's.
#ifndef MIXTRACE_TESTS_TEXEL_ROWS_INTERFACE_H
#define MIXTRACE_TESTS_TEXEL_ROWS_INTERFACE_H
#include "shared/cms_pair_state.h"
#include "shared/cms_state.h"
#include "shared/method_buffers.h"
#include "shared/scene_buffers.h"

#define BUFFER_BVH_NODES_OUT(X) X(BVH_NODES_OUT, bvhNodesOut, 51, READ_WRITE, BvhNode, UPLOADED, "BVH nodes read back")
#define BUFFER_TRIANGLE_SHADING_OUT(X) \
  X(TRIANGLE_SHADING_OUT, triangleShadingOut, 52, READ_WRITE, TriangleShading, UPLOADED, "shading read back")
#define BUFFER_MATERIALS_OUT(X) X(MATERIALS_OUT, materialsOut, 53, READ_WRITE, MaterialGpu, UPLOADED, "materials read back")
#define BUFFER_EMITTERS_OUT(X) X(EMITTERS_OUT, emittersOut, 54, READ_WRITE, EmitterGpu, UPLOADED, "emitters read back")
#define BUFFER_LIGHT_BVH_OUT(X) X(LIGHT_BVH_OUT, lightBvhOut, 55, READ_WRITE, LightBvhNodeGpu, UPLOADED, "light BVH read back")
#define BUFFER_TRIANGLES_OUT(X) X(TRIANGLES_OUT, trianglesOut, 56, READ_WRITE, TriangleGeom, UPLOADED, "triangles read back")
#define BUFFER_LIGHTS_OUT(X) X(LIGHTS_OUT, lightsOut, 57, READ_WRITE, LightGpu, UPLOADED, "lights read back")
#define BUFFER_LIGHT_SELECTION_OUT(X) \
  X(LIGHT_SELECTION_OUT, lightSelectionOut, 60, READ_WRITE, LightSelectionGpu, UPLOADED, "light selection read back")
#define BUFFER_CLUSTERS_OUT(X) X(CLUSTERS_OUT, clustersOut, 61, READ_WRITE, ClusterGpu, UPLOADED, "clusters read back")
// The word views (CMS_STATE_VIEWS, CMS_PAIR_VIEWS): word i of each, through CELL_SOLUTION(i),
// PAIR_ALPHA(i) and CLUSTER_DEFAULT(i).
#define BUFFER_CELL_SOLUTION_OUT(X) \
  X(CELL_SOLUTION_OUT, cellSolutionOut, 62, READ_WRITE, uint, UPLOADED, "cell solution words read back")
#define BUFFER_PAIR_ALPHA_OUT(X) X(PAIR_ALPHA_OUT, pairAlphaOut, 63, READ_WRITE, uint, UPLOADED, "pair alpha words read back")
#define BUFFER_CLUSTER_DEFAULTS_OUT(X) \
  X(CLUSTER_DEFAULTS_OUT, clusterDefaultsOut, 65, READ_WRITE, uint, UPLOADED, "cluster default words read back")
// The scene's texture table (TEXTURE(i), as its uvec4), texels (TEXEL(i)) and environment words
// (ENV_DATA(i)).
#define BUFFER_TEXTURES_OUT(X) X(TEXTURES_OUT, texturesOut, 66, READ_WRITE, uvec4, UPLOADED, "texture table read back")
#define BUFFER_TEXELS_OUT(X) X(TEXELS_OUT, texelsOut, 67, READ_WRITE, uint, UPLOADED, "texels read back")
#define BUFFER_ENVIRONMENT_OUT(X) X(ENVIRONMENT_OUT, environmentOut, 68, READ_WRITE, uint, UPLOADED, "environment words read back")
#define TEXEL_ROWS_OUT_BUFFERS(X)                                                                         \
  BUFFER_BVH_NODES_OUT(X) BUFFER_TRIANGLE_SHADING_OUT(X) BUFFER_MATERIALS_OUT(X) BUFFER_EMITTERS_OUT(X) \
  BUFFER_LIGHT_BVH_OUT(X) BUFFER_TRIANGLES_OUT(X) BUFFER_LIGHTS_OUT(X) BUFFER_LIGHT_SELECTION_OUT(X)    \
  BUFFER_CLUSTERS_OUT(X) BUFFER_CELL_SOLUTION_OUT(X) BUFFER_PAIR_ALPHA_OUT(X) BUFFER_CLUSTER_DEFAULTS_OUT(X) \
  BUFFER_TEXTURES_OUT(X) BUFFER_TEXELS_OUT(X) BUFFER_ENVIRONMENT_OUT(X)
#define TEXEL_ROWS_BUFFERS(X)                                                                                \
  BUFFER_BVH_NODES(X) BUFFER_TRIANGLE_SHADING(X) BUFFER_MATERIALS(X) BUFFER_EMITTERS(X) BUFFER_LIGHT_BVH(X) \
  BUFFER_TRIANGLES(X) BUFFER_LIGHTS(X) BUFFER_LIGHT_SELECTION(X) BUFFER_CLUSTERS(X) BUFFER_CELL_SOLUTION_TEXELS(X) \
  BUFFER_PAIR_ALPHA_TEXELS(X) BUFFER_CLUSTER_DEFAULTS_TEXELS(X) BUFFER_TEXTURES(X) BUFFER_TEXELS(X)        \
  BUFFER_ENVIRONMENT(X) TEXEL_ROWS_OUT_BUFFERS(X)

SHARED_BEGIN
TEXEL_ROWS_OUT_BUFFERS(BUFFER_BINDING_CONSTANT)
struct TexelRowsConstants {
  uint count;  // elements in every row
};
SHARED_END
#endif
