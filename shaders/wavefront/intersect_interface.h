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
  uint pathCount;  // paths in this wavefront chunk: the size of each half of the ray queue
  uint queueIn;    // which half (0/1) holds the rays
};
SHARED_END
#endif
