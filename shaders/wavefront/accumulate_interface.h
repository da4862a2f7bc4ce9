// The accumulate pass (wavefront/accumulate.comp): folds each path's radiance into its pixel.
// Declared once for the shader and the host (host/wavefront/passes/accumulate_pass.cpp).
#ifndef MIXTRACE_WAVEFRONT_ACCUMULATE_INTERFACE_H
#define MIXTRACE_WAVEFRONT_ACCUMULATE_INTERFACE_H
#include "shared/path_state.h"

#define ACCUMULATE_BUFFERS(X) BUFFER_RADIANCE(X) BUFFER_QUEUE_STATE(X) BUFFER_FILM(X)

SHARED_BEGIN
struct AccumulateConstants {
  uint pathCount;    // paths in this wavefront chunk
  uint pixelOffset;  // first pixel of the chunk
  uint sampleIndex;  // sample pass (spp index): the film's pixels hold sampleIndex samples so far
};
SHARED_END
#endif
