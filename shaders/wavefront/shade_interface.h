// The shade pass (wavefront/shade.comp): emission, one light sample (a shadow ray) and one BSDF
// sample (the next extension ray) at every queued hit, and with controlled mixture sampling the
// cell look-up, the cluster selection, the control variate and the statistics. Declared once for
// the shader and the host (host/wavefront/passes/shade_pass.cpp).
//
// VertexConstants is shared with the shadow pass (shadow_interface.h), which settles the light
// samples shade queued: both add CMS statistics of one sample pass at one depth, through the same
// functions (gpu/cms_statistics.glsl), so both are pushed the same values.
#ifndef MIXTRACE_WAVEFRONT_SHADE_INTERFACE_H
#define MIXTRACE_WAVEFRONT_SHADE_INTERFACE_H
#include "shared/cms_state.h"
#include "shared/method_buffers.h"
#include "shared/path_state.h"
#include "shared/scene_buffers.h"

// No pair rows (shared/cms_pair_state.h): with them shade would bind 36 storage buffers, past
// lavapipe's 32 per stage. With the per-triangle control variate shade queues each sample's pair
// terms as a record for the shadow pass (kShadowRayBsdfPair, kShadowRayHidden), which binds them.
#define SHADE_BUFFERS(X)                                                                                \
  BUFFER_TRIANGLES(X) BUFFER_TRIANGLE_SHADING(X) BUFFER_MATERIALS(X) BUFFER_TEXTURES(X) BUFFER_TEXELS(X) BUFFER_TRIANGLE_UV2(X) \
  BUFFER_LIGHTS(X) BUFFER_EMITTERS(X) BUFFER_ENVIRONMENT(X) BUFFER_LIGHT_SELECTION(X) BUFFER_LIGHT_BVH(X) BUFFER_MIS_NORMAL(X) \
  BUFFER_RAY_ORIGIN(X) BUFFER_RAY_DIRECTION(X) BUFFER_THROUGHPUT(X) BUFFER_RADIANCE(X) BUFFER_RNG(X)    \
  BUFFER_MIS_PDF(X) BUFFER_HITS(X) BUFFER_RAY_QUEUE(X) BUFFER_SHADOW_QUEUE(X) BUFFER_QUEUE_STATE(X)     \
  BUFFER_CELL_STATS(X) BUFFER_CELL_SAMPLES(X) BUFFER_CELL_SOLUTION_TEXELS(X) BUFFER_CLUSTER_DEFAULTS_TEXELS(X)        \
  BUFFER_CELL_KEYS(X) BUFFER_CLUSTERS(X) BUFFER_CLUSTER_LIGHTS(X) BUFFER_CV_STATE(X)                    \
  BUFFER_PIXEL_ESTIMATE(X) BUFFER_FIRST_CELL(X)

SHARED_BEGIN
struct VertexConstants {
  uint pathCount;         // paths in this wavefront chunk: the size of each third of the ray queue
  uint pixelOffset;       // first pixel of the chunk
  uint depth;             // 1 = the camera ray's vertex
  uint maxDepth;          // Mitsuba convention: 1 = emitters seen directly
  uint queueIn;           // which half (0/1) of the ray queue is read; the other is written
  uint lightCount;
  uint clusterCount;      // CMS: L
  uint cellTableSize;     // CMS: slots of the cell table (a power of two)
  vec3 gridOrigin;        // CMS: the cell grid's origin (scene bounds minimum)
  float gridInvCellSize;
  uint gatherStatistics;  // CMS: 1 when a later solve reads this sample pass's statistics
  uint pairCapacity;      // per-triangle CV: slots of the (cell, technique) pair table (a power of two)
  uint emitterCount;      // per-triangle CV: technique sources of punctual lights start here
  uint shadeQueued;       // shade: 1 reads the rays intersect queued for it (the ray queue's third kShadeQueue), 0 the rays of queueIn
};
SHARED_END
#endif
