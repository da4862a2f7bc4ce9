// The viewer's display pass (viewer/display.comp): the film, or a debug view of the CMS cells,
// letterboxed into the window as packed 8-bit colour. Pushed DisplayConstants (shared/display.h).
// It reads the renderer's film and cells (host/viewer/display_pass.cpp binds them from the
// renderer's buffers) and writes the viewer's own buffer, whose row is declared here: it is the
// viewer's, not the renderer's.
#ifndef MIXTRACE_VIEWER_DISPLAY_INTERFACE_H
#define MIXTRACE_VIEWER_DISPLAY_INTERFACE_H
#include "shared/cms_state.h"
#include "shared/display.h"
#include "shared/path_state.h"
#include "shared/method_buffers.h"
#include "shared/scene_buffers.h"

// Packed 8-bit colour per window pixel, copied into the swapchain image.
#define BUFFER_WINDOW(X) X(WINDOW, window, 30, READ_BACK, uint, WINDOW_PIXELS, "display")

#define DISPLAY_BUFFERS(X)                                                                          \
  BUFFER_FILM(X) BUFFER_FIRST_CELL(X) BUFFER_CELL_SAMPLES(X) BUFFER_CELL_SOLUTION(X) BUFFER_CLUSTER_DEFAULTS(X) \
  BUFFER_WINDOW(X)
// Named by functions of shared/cms_sampling.h it never calls: declared for GLSL to compile them,
// dropped by the compiler, not bound (gpu/buffers.glsl).
#define DISPLAY_UNREAD_BUFFERS(X)                                                                       \
  BUFFER_TRIANGLES(X) BUFFER_TRIANGLE_SHADING(X) BUFFER_MATERIALS(X) BUFFER_TEXTURES(X) BUFFER_TEXELS(X) BUFFER_TRIANGLE_UV2(X) \
  BUFFER_LIGHTS(X) BUFFER_EMITTERS(X) BUFFER_CELL_KEYS(X) BUFFER_CLUSTERS(X) BUFFER_CLUSTER_LIGHTS(X) \
  BUFFER_LIGHT_SELECTION(X) BUFFER_ENVIRONMENT(X)

SHARED_BEGIN
BUFFER_WINDOW(BUFFER_BINDING_CONSTANT)
SHARED_END
#endif
