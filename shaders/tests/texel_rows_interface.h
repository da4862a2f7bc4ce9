// Test kernel tests/texel_rows.comp: reads element i of every row read as texels (access TEXELS,
// shared/buffer_table.h) through its GLSL accessor (gpu/buffers.glsl) and writes it to a storage
// buffer of the same struct, so tests/gpu/texel_rows_test.cpp can compare the bits with the
// host's.
#ifndef MIXTRACE_TESTS_TEXEL_ROWS_INTERFACE_H
#define MIXTRACE_TESTS_TEXEL_ROWS_INTERFACE_H
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
#define TEXEL_ROWS_OUT_BUFFERS(X)                                                                         \
  BUFFER_BVH_NODES_OUT(X) BUFFER_TRIANGLE_SHADING_OUT(X) BUFFER_MATERIALS_OUT(X) BUFFER_EMITTERS_OUT(X) \
  BUFFER_LIGHT_BVH_OUT(X) BUFFER_TRIANGLES_OUT(X) BUFFER_LIGHTS_OUT(X)
#define TEXEL_ROWS_BUFFERS(X)                                                                                \
  BUFFER_BVH_NODES(X) BUFFER_TRIANGLE_SHADING(X) BUFFER_MATERIALS(X) BUFFER_EMITTERS(X) BUFFER_LIGHT_BVH(X) \
  BUFFER_TRIANGLES(X) BUFFER_LIGHTS(X) TEXEL_ROWS_OUT_BUFFERS(X)

SHARED_BEGIN
TEXEL_ROWS_OUT_BUFFERS(BUFFER_BINDING_CONSTANT)
struct TexelRowsConstants {
  uint count;  // elements in every row
};
SHARED_END
#endif
