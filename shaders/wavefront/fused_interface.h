// The fused pass (wavefront/fused.comp): the Vulkan renderer's schedule for CPU devices. One
// dispatch per sample pass traces every path of the chunk whole (shared/path_tracer.h), keeping
// its state in registers, where the wavefront schedule runs some twenty dispatches, each ended by
// a barrier that waits for the slowest worker thread. Writes each path's radiance for the
// accumulate pass. Declared once for the shader and the host (host/wavefront/passes/fused_pass.cpp).
#ifndef MIXTRACE_WAVEFRONT_FUSED_INTERFACE_H
#define MIXTRACE_WAVEFRONT_FUSED_INTERFACE_H
#include "shared/method_buffers.h"
#include "shared/path_state.h"
#include "shared/scene_buffers.h"

#define FUSED_BUFFERS(X)                                                                                  \
  BUFFER_CAMERA(X) BUFFER_BVH_NODES(X) BUFFER_TRIANGLES(X) BUFFER_TRIANGLE_SHADING(X) BUFFER_MATERIALS(X) \
  BUFFER_TEXTURES(X) BUFFER_TEXELS(X) BUFFER_TRIANGLE_UV2(X) BUFFER_LIGHTS(X) BUFFER_EMITTERS(X)          \
  BUFFER_ENVIRONMENT(X) BUFFER_LIGHT_SELECTION(X) BUFFER_LIGHT_BVH(X) BUFFER_RADIANCE(X) BUFFER_QUEUE_STATE(X)

SHARED_BEGIN
struct FusedConstants {
  uint pathCount;       // paths in this chunk
  uint pixelOffset;     // first pixel of the chunk
  uint sampleIndex;     // sample pass (spp index)
  uint seed;
  uint maxDepth;        // Mitsuba convention: 1 = emitters seen directly
  uint lightCount;
};
SHARED_END
#endif
