// The method's buffers, uploaded once per renderer beside the prepared scene's: what a method adds
// to the same scene (host/cms/method_lights.h). Rows in the format of shared/buffer_table.h. The
// scene is prepared once for every method, so the method's light selection is not in LightGpu.
#ifndef MIXTRACE_SHARED_METHOD_BUFFERS_H
#define MIXTRACE_SHARED_METHOD_BUFFERS_H
#include "shared/buffer_table.h"
#include "shared/layouts.h"

// LightSelectionGpu per light: the selection pmf and CDF (uniform or by power), and for the
// learning methods the light's cluster and its pmf inside it.
#define BUFFER_LIGHT_SELECTION(X) \
  X(LIGHT_SELECTION, lightSelection, 31, TEXELS, LightSelectionGpu, UPLOADED, "light selection")

// LightBvhNodeGpu: the light BVH of method pt-bvh (scene/light_bvh.h); one placeholder node for the
// other methods, so that the binding is valid.
#define BUFFER_LIGHT_BVH(X) X(LIGHT_BVH, lightBvh, 32, TEXELS, LightBvhNodeGpu, UPLOADED, "light BVH")

#define METHOD_BUFFERS(X) BUFFER_LIGHT_SELECTION(X) BUFFER_LIGHT_BVH(X)

SHARED_BEGIN
METHOD_BUFFERS(BUFFER_BINDING_CONSTANT)
SHARED_END
#endif
