// The intersect pass (wavefront/intersect.comp): the closest hit of every queued extension ray.
// Declared once for the shader and the host (host/wavefront/passes/intersect_pass.cpp).
#ifndef MIXTRACE_WAVEFRONT_INTERSECT_INTERFACE_H
#define MIXTRACE_WAVEFRONT_INTERSECT_INTERFACE_H
#include "shared/path_state.h"
#include "shared/scene_buffers.h"

#define INTERSECT_BUFFERS(X)                                                                      \
  BUFFER_BVH_NODES(X) BUFFER_TRIANGLES(X) BUFFER_RAY_ORIGIN(X) BUFFER_RAY_DIRECTION(X) BUFFER_HITS(X) \
  BUFFER_RAY_QUEUE(X) BUFFER_QUEUE_STATE(X)                                                        \
  /* alpha (shared/alpha.h): read only where the scene has alpha-tested materials */             \
  BUFFER_TRIANGLE_SHADING(X) BUFFER_MATERIALS(X) BUFFER_TEXTURES(X) BUFFER_TEXELS(X) BUFFER_TRIANGLE_UV2(X)

SHARED_BEGIN
struct IntersectConstants {
  uint pathCount;  // paths in this wavefront chunk: the size of each third of the ray queue
  uint queueIn;    // which half (0/1) holds the rays
  // 1: queue the rays that hit something for the shade pass (the ray queue's third kShadeQueue),
  // which then never sees the others; 0: queue nothing (shade reads the rays of queueIn). Where
  // most rays hit, queueing costs intersect more than it saves shade (wavefront_renderer.cpp
  // decideShadeQueue).
  uint queueForShade;
};
SHARED_END
#endif
