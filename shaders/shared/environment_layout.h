// Where the parts of the environment light live in its one float buffer (ENVIRONMENT,
// shared/scene_buffers.h), written by host/scene/environment_distribution.cpp and read by
// shared/environment.h. One buffer, not four, because the shade pass is one buffer short of
// lavapipe's 32 storage buffers per stage.
//
//   [0] width W, [1] height H (texels; exact in float up to 2^24)
//   [2] the environment's light index, or -1 where the scene has none
//   [3] cos, [4] sin of the rotation about +Y (--env-rotate)
//   [5..7] unused
//   marginal CDF over the rows:      H + 1 floats, 0 first and 1 last
//   conditional CDF of each row:     H x (W + 1) floats, each row 0 first and 1 last
//   radiance:                        3 x W x H floats, RGB, top row (+Y) first
#ifndef MIXTRACE_SHARED_ENVIRONMENT_LAYOUT_H
#define MIXTRACE_SHARED_ENVIRONMENT_LAYOUT_H
#include "shared/dialect.h"
SHARED_BEGIN

const uint kEnvHeaderFloats = 8u;
const uint kEnvWidth = 0u;
const uint kEnvHeight = 1u;
const uint kEnvLight = 2u;
const uint kEnvRotationCos = 3u;
const uint kEnvRotationSin = 4u;

SHARED_FN uint envMarginalOffset() { return kEnvHeaderFloats; }
SHARED_FN uint envConditionalOffset(uint w, uint h) { return kEnvHeaderFloats + h + 1u; }
SHARED_FN uint envRadianceOffset(uint w, uint h) { return envConditionalOffset(w, h) + h * (w + 1u); }
SHARED_FN uint envFloatCount(uint w, uint h) { return envRadianceOffset(w, h) + 3u * w * h; }

SHARED_END
#endif
