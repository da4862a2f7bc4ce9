// The fused pass (wavefront/fused.comp): the Vulkan renderer's schedule for CPU devices. One
// dispatch per sample pass traces every path of the chunk whole (shared/path_tracer.h, and
// shared/cms_path_tracer.h for the methods with controlled mixture sampling), keeping its state in
// registers, where the wavefront schedule runs some twenty dispatches, each ended by
// a barrier that waits for the slowest worker thread. Writes each path's radiance for the
// accumulate pass. Declared once for the shader and the host (host/wavefront/passes/fused_pass.cpp).
#ifndef MIXTRACE_WAVEFRONT_FUSED_INTERFACE_H
#define MIXTRACE_WAVEFRONT_FUSED_INTERFACE_H
#include "shared/cms_pair_state.h"
#include "shared/cms_state.h"
#include "shared/method_buffers.h"
#include "shared/path_state.h"
#include "shared/scene_buffers.h"

#define FUSED_BUFFERS(X)                                                                                  \
  BUFFER_CAMERA(X) BUFFER_BVH_NODES(X) BUFFER_TRIANGLES(X) BUFFER_TRIANGLE_SHADING(X) BUFFER_MATERIALS(X) \
  BUFFER_TEXTURES(X) BUFFER_TEXELS(X) BUFFER_TRIANGLE_UV2(X) BUFFER_LIGHTS(X) BUFFER_EMITTERS(X)          \
  BUFFER_ENVIRONMENT(X) BUFFER_LIGHT_SELECTION(X) BUFFER_LIGHT_BVH(X) BUFFER_RADIANCE(X) BUFFER_QUEUE_STATE(X)    \
  BUFFER_CELL_STATS(X) BUFFER_CELL_SAMPLES(X) BUFFER_CELL_SOLUTION_TEXELS(X) BUFFER_CLUSTER_DEFAULTS_TEXELS(X)                 \
  BUFFER_CELL_KEYS(X) BUFFER_CLUSTERS(X) BUFFER_CLUSTER_LIGHTS(X) BUFFER_PIXEL_ESTIMATE(X) BUFFER_FIRST_CELL(X)  \
  CMS_PAIR_SETTLE_BUFFERS(X)

SHARED_BEGIN
struct FusedConstants {
  uint pathCount;       // paths in this chunk
  uint pixelOffset;     // first pixel of the chunk
  uint sampleIndex;     // sample pass (spp index)
  uint seed;
  uint maxDepth;        // Mitsuba convention: 1 = emitters seen directly
  uint lightCount;
  // The methods with controlled mixture sampling (the shade pass's VertexConstants members of the
  // same names; gpu/cms_statistics.glsl reads them): unread by the others.
  uint clusterCount;      // L
  uint cellTableSize;     // slots of the cell table (a power of two)
  vec3 gridOrigin;        // the cell grid's origin (scene bounds minimum)
  float gridInvCellSize;
  uint gatherStatistics;  // 1 when a later solve reads this sample pass's statistics
  uint pairCapacity;      // per-triangle CV: slots of the (cell, technique) pair table
  uint emitterCount;      // per-triangle CV: technique sources of punctual lights start here
  uint pad;
};
SHARED_END
#endif
