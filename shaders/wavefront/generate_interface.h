// The generate pass (wavefront/generate.comp): one camera ray per path of the chunk; resets the
// path state and fills the first ray queue. What it binds and what it is pushed, declared once for
// the shader and the host (host/wavefront/passes/generate_pass.cpp).
#ifndef MIXTRACE_WAVEFRONT_GENERATE_INTERFACE_H
#define MIXTRACE_WAVEFRONT_GENERATE_INTERFACE_H
#include "shared/path_state.h"
#include "shared/scene_buffers.h"

#define GENERATE_BUFFERS(X)                                                                            \
  BUFFER_CAMERA(X) BUFFER_RAY_ORIGIN(X) BUFFER_RAY_DIRECTION(X) BUFFER_THROUGHPUT(X) BUFFER_RADIANCE(X) \
  BUFFER_RNG(X) BUFFER_MIS_PDF(X) BUFFER_RAY_QUEUE(X) BUFFER_QUEUE_STATE(X)

SHARED_BEGIN
struct GenerateConstants {
  uint pathCount;    // paths in this wavefront chunk
  uint pixelOffset;  // first pixel of the chunk
  uint sampleIndex;  // sample pass (spp index)
  uint seed;
};
SHARED_END
#endif
