// The prepared scene's buffers, uploaded once (host/wavefront/gpu_scene.cpp). Rows in the format of
// shared/buffer_table.h.
#ifndef MIXTRACE_SHARED_SCENE_BUFFERS_H
#define MIXTRACE_SHARED_SCENE_BUFFERS_H
#include "shared/buffer_table.h"
#include "shared/layouts.h"

#define BUFFER_CAMERA(X) X(CAMERA, camera, 0, READ_ONLY, CameraGpu, ONE, "camera")
// The rows read per lane at divergent indices are TEXELS (shared/buffer_table.h): lavapipe gathers
// texels, where it loads storage buffers one lane at a time.
#define BUFFER_BVH_NODES(X) X(BVH_NODES, bvhNodes, 1, TEXELS, BvhNode, UPLOADED, "BVH nodes")
#define BUFFER_TRIANGLES(X) X(TRIANGLES, triangles, 2, TEXELS, TriangleGeom, UPLOADED, "triangles")
#define BUFFER_TRIANGLE_SHADING(X) \
  X(TRIANGLE_SHADING, triangleShading, 3, TEXELS, TriangleShading, UPLOADED, "triangle shading data")
#define BUFFER_MATERIALS(X) X(MATERIALS, materials, 4, TEXELS, MaterialGpu, UPLOADED, "materials")
// The texture table holds TextureGpu records as uvec4s, one texel each (textureFromWords); the
// texels (RGBA8 words) are read through a word view, four to a texel (a buffer's size is whole
// texels, host/vulkan/buffer.cpp): a bilinear lookup's four reads are gathers, not four lane loops.
#define BUFFER_TEXTURES(X) X(TEXTURES, textures, 5, TEXELS, uvec4, UPLOADED, "texture table")
#define BUFFER_TEXELS(X) X(TEXELS, texels, 6, TEXELS, uint, UPLOADED, "texels")
#define BUFFER_LIGHTS(X) X(LIGHTS, lights, 7, TEXELS, LightGpu, UPLOADED, "lights")
#define BUFFER_EMITTERS(X) X(EMITTERS, emitters, 8, TEXELS, EmitterGpu, UPLOADED, "emitters")
// The environment light's map and distribution (shared/environment_layout.h); a header saying
// "none" where the scene has none. A word view like the texels (its lookups and the distribution's
// searches read at divergent indices).
#define BUFFER_ENVIRONMENT(X) X(ENVIRONMENT, environment, 48, TEXELS, float, UPLOADED, "environment map")
// Second texture coordinates per triangle (layouts.h TriangleUvs); one unused entry where no
// material reads them.
#define BUFFER_TRIANGLE_UV2(X) X(TRIANGLE_UV2, triangleUv2, 50, READ_ONLY, TriangleUvs, UPLOADED, "second texture coordinates")

#define SCENE_BUFFERS(X)                                                                             \
  BUFFER_CAMERA(X) BUFFER_BVH_NODES(X) BUFFER_TRIANGLES(X) BUFFER_TRIANGLE_SHADING(X) BUFFER_MATERIALS(X) \
  BUFFER_TEXTURES(X) BUFFER_TEXELS(X) BUFFER_LIGHTS(X) BUFFER_EMITTERS(X) BUFFER_ENVIRONMENT(X) BUFFER_TRIANGLE_UV2(X)
// (binding 31: the method's light selection, shared/method_buffers.h.)

SHARED_BEGIN
SCENE_BUFFERS(BUFFER_BINDING_CONSTANT)
SHARED_END
#endif
