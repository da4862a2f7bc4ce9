// The pixel-estimate pass (cms/pixel_estimate.comp), at the start of every CMS training
// iteration: the pixel values the statistics' relative weights divide by, from the film so far.
// Declared once for the shader and the host (host/wavefront/passes/pixel_estimate_pass.cpp).
#ifndef MIXTRACE_CMS_PIXEL_ESTIMATE_INTERFACE_H
#define MIXTRACE_CMS_PIXEL_ESTIMATE_INTERFACE_H
#include "shared/cms_state.h"
#include "shared/path_state.h"
#include "shared/scene_buffers.h"

#define PIXEL_ESTIMATE_BUFFERS(X) BUFFER_CAMERA(X) BUFFER_FILM(X) BUFFER_PIXEL_ESTIMATE(X)

SHARED_BEGIN
struct PixelEstimateConstants {
  uint pixelCount;  // one invocation per pixel
};
SHARED_END
#endif
