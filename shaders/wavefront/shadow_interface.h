// The shadow pass (wavefront/shadow.comp): the any-hit test of every queued shadow ray, and with
// controlled mixture sampling the light sample's terms that its visibility decides. Pushed the
// shade pass's VertexConstants (shade_interface.h says why). Declared once for the shader and the
// host (host/wavefront/passes/shadow_pass.cpp).
#ifndef MIXTRACE_WAVEFRONT_SHADOW_INTERFACE_H
#define MIXTRACE_WAVEFRONT_SHADOW_INTERFACE_H
#include "shared/cms_pair_state.h"
#include "wavefront/shade_interface.h"

#define SHADOW_BUFFERS(X)                                                                   \
  BUFFER_BVH_NODES(X) BUFFER_TRIANGLES(X) BUFFER_RADIANCE(X) BUFFER_SHADOW_QUEUE(X) BUFFER_QUEUE_STATE(X) \
  BUFFER_CELL_STATS(X) BUFFER_CELL_SAMPLES(X) BUFFER_CELL_SOLUTION_TEXELS(X) BUFFER_PIXEL_ESTIMATE(X) CMS_PAIR_SETTLE_BUFFERS(X) \
  BUFFER_TRIANGLE_SHADING(X) BUFFER_MATERIALS(X) BUFFER_TEXTURES(X) BUFFER_TEXELS(X) BUFFER_TRIANGLE_UV2(X) /* alpha */
// Named by functions of the headers it includes (the CMS sampling functions, the light and
// texture look-ups) that it never calls: declared for GLSL to compile them, dropped by the
// compiler, not bound (gpu/buffers.glsl).
#define SHADOW_UNREAD_BUFFERS(X)                                                                        \
  BUFFER_LIGHTS(X) BUFFER_EMITTERS(X) BUFFER_CLUSTER_DEFAULTS_TEXELS(X) BUFFER_CELL_KEYS(X) BUFFER_CLUSTERS(X) BUFFER_CLUSTER_LIGHTS(X) \
  BUFFER_LIGHT_SELECTION(X) BUFFER_ENVIRONMENT(X)

#endif
