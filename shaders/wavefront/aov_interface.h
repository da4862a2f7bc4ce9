// The AOV pass (wavefront/aov.comp): after the camera rays' intersection, folds each path's first
// hit into its pixel's albedo, normal and depth (shared/first_hit_aov.h). Recorded only for a
// render that writes them (--aov). Declared once for the shader and the host
// (host/wavefront/passes/aov_pass.cpp).
#ifndef MIXTRACE_WAVEFRONT_AOV_INTERFACE_H
#define MIXTRACE_WAVEFRONT_AOV_INTERFACE_H
#include "shared/method_buffers.h"
#include "shared/path_state.h"
#include "shared/scene_buffers.h"

#define AOV_BUFFERS(X)                                                                                   \
  BUFFER_TRIANGLES(X) BUFFER_TRIANGLE_SHADING(X) BUFFER_MATERIALS(X) BUFFER_TEXTURES(X) BUFFER_TEXELS(X) BUFFER_TRIANGLE_UV2(X) \
  BUFFER_RAY_DIRECTION(X) BUFFER_HITS(X) BUFFER_AOV(X)
// Named by functions of the headers it includes (light look-ups) that it never calls.
#define AOV_UNREAD_BUFFERS(X) BUFFER_LIGHTS(X) BUFFER_EMITTERS(X) BUFFER_LIGHT_SELECTION(X) BUFFER_ENVIRONMENT(X)

SHARED_BEGIN
struct AovConstants {
  uint pathCount;    // paths in this wavefront chunk
  uint pixelOffset;  // first pixel of the chunk
  uint sampleIndex;  // sample pass: the pixel's AOVs hold sampleIndex samples so far
};
SHARED_END
#endif
