// Test kernel tests/trace_rays.comp: the wavefront's BVH traversal on rays given by the host
// (tests/gpu/gpu_bvh_test.cpp). Mode 0: closest hit into hits[]; mode 1: any hit in
// (0, misPdf[i]) into misPdf[i] (1 blocked, 0 free).
#ifndef MIXTRACE_TESTS_TRACE_RAYS_INTERFACE_H
#define MIXTRACE_TESTS_TRACE_RAYS_INTERFACE_H
#include "shared/path_state.h"
#include "shared/scene_buffers.h"

#define TRACE_RAYS_BUFFERS(X) \
  BUFFER_BVH_NODES(X) BUFFER_TRIANGLES(X) BUFFER_RAY_ORIGIN(X) BUFFER_RAY_DIRECTION(X) BUFFER_MIS_PDF(X) BUFFER_HITS(X)

SHARED_BEGIN
struct TraceRaysConstants {
  uint rayCount;
  uint mode;  // 0: closest hit, 1: any hit
};
SHARED_END
#endif
