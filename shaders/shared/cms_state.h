// The buffers of controlled mixture sampling (shared/cms_layouts.h, shared/cluster_layout.h): the
// cell table, its statistics and solutions, the clusters, the per-path state of the previous
// vertex's BSDF sample and the per-pixel estimate and first-hit cells. Rows in the format of
// shared/buffer_table.h. For the methods without CMS each is a placeholder of one element (the
// extents CELL_* with a one-slot table, CMS_PATHS, CMS_PIXELS), so every pass's set is complete.
#ifndef MIXTRACE_SHARED_CMS_STATE_H
#define MIXTRACE_SHARED_CMS_STATE_H
#include "shared/buffer_table.h"
#include "shared/cluster_layout.h"
#include "shared/cms_layouts.h"
#include "shared/layouts.h"

#define BUFFER_CELL_STATS(X) X(CELL_STATS, cellStats, 20, READ_WRITE, float, CELL_STATS, "CMS cell statistics")
#define BUFFER_CELL_SAMPLES(X) \
  X(CELL_SAMPLES, cellSamples, 21, READ_WRITE, uint, CELL_SLOTS, "CMS cell sample counts")
#define BUFFER_CELL_SOLUTION(X) \
  X(CELL_SOLUTION, cellSolution, 22, READ_WRITE, float, CELL_SOLUTIONS, "CMS cell solutions")
// The default selection pmf over the clusters (for vertices without a solved cell).
#define BUFFER_CLUSTER_DEFAULTS(X) \
  X(CLUSTER_DEFAULTS, clusterDefaults, 23, READ_ONLY, float, UPLOADED, "cluster defaults")
// Hashed cell keys, 0 = an empty slot (shared/cms_cells.h).
#define BUFFER_CELL_KEYS(X) X(CELL_KEYS, cellKeys, 24, READ_WRITE, uint64_t, CELL_SLOTS, "CMS cell table")
#define BUFFER_CLUSTERS(X) X(CLUSTERS, clusters, 25, TEXELS, ClusterGpu, UPLOADED, "clusters")
// The lights grouped by cluster, with their CDFs inside it.
#define BUFFER_CLUSTER_LIGHTS(X) \
  X(CLUSTER_LIGHTS, clusterLights, 26, READ_ONLY, ClusterLightGpu, UPLOADED, "cluster lights")
// Per path: the previous vertex's cell, throughput and bsdf * cos (its terms are paid at the next).
#define BUFFER_CV_STATE(X) X(CV_STATE, cvState, 27, READ_WRITE, CvPathState, CMS_PATHS, "path state (CMS)")
// The pixel values the statistics' relative weights divide by (shared/pixel_estimate.h).
#define BUFFER_PIXEL_ESTIMATE(X) \
  X(PIXEL_ESTIMATE, pixelEstimate, 28, READ_WRITE, vec3, CMS_PIXELS, "CMS pixel estimate")
// The cell of each pixel's first hit (the viewer's debug views).
#define BUFFER_FIRST_CELL(X) X(FIRST_CELL, firstCell, 29, READ_WRITE, uint, CMS_PIXELS, "CMS first-hit cells")

#define CMS_STATE_BUFFERS(X)                                                                               \
  BUFFER_CELL_STATS(X) BUFFER_CELL_SAMPLES(X) BUFFER_CELL_SOLUTION(X) BUFFER_CLUSTER_DEFAULTS(X)          \
  BUFFER_CELL_KEYS(X) BUFFER_CLUSTERS(X) BUFFER_CLUSTER_LIGHTS(X) BUFFER_CV_STATE(X) BUFFER_PIXEL_ESTIMATE(X) \
  BUFFER_FIRST_CELL(X)

// Views: a row above read as RGBA32UI texels (access TEXELS, shared/buffer_table.h) by the passes
// that only read it, the shade, shadow and fused passes, where the solve writes (or reads) it as a
// storage buffer (lavapipe gathers texels with vector instructions but loads a storage buffer one lane at
// a time). No buffer of their own: the renderer binds the viewed row's buffer at the view's
// binding (host/wavefront/device_buffers.cpp, from CMS_STATE_VIEWED), its length padded to whole
// texels; word views (shared/buffer_table.h kWordsPerTexel, gpu/cms_buffers.glsl).
#define BUFFER_CELL_SOLUTION_TEXELS(X) \
  X(CELL_SOLUTION_TEXELS, cellSolutionTexels, 58, TEXELS, float, CELL_SOLUTIONS, "CMS cell solutions (texels)")
#define BUFFER_CLUSTER_DEFAULTS_TEXELS(X) \
  X(CLUSTER_DEFAULTS_TEXELS, clusterDefaultsTexels, 64, TEXELS, float, UPLOADED, "cluster defaults (texels)")
#define CMS_STATE_VIEWS(X) BUFFER_CELL_SOLUTION_TEXELS(X) BUFFER_CLUSTER_DEFAULTS_TEXELS(X)
// Each view and the row whose buffer it views: V(view ID, viewed ID).
#define CMS_STATE_VIEWED(V) V(CELL_SOLUTION_TEXELS, CELL_SOLUTION) V(CLUSTER_DEFAULTS_TEXELS, CLUSTER_DEFAULTS)

SHARED_BEGIN
CMS_STATE_BUFFERS(BUFFER_BINDING_CONSTANT)
CMS_STATE_VIEWS(BUFFER_BINDING_CONSTANT)
SHARED_END
#endif
