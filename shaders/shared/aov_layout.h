// Where the AOVs live in their buffer (BUFFER_AOV, shared/path_state.h), vec3s per pixel:
// [kAovStride * pixel + kAovAlbedo], [.. + kAovNormal], [.. + kAovDepth] (the distance in .x).
// Written by shared/first_hit_aov.h's callers, read back by the host.
#ifndef MIXTRACE_SHARED_AOV_LAYOUT_H
#define MIXTRACE_SHARED_AOV_LAYOUT_H
#include "shared/dialect.h"
SHARED_BEGIN
const uint kAovStride = 3u;
const uint kAovAlbedo = 0u;
const uint kAovNormal = 1u;
const uint kAovDepth = 2u;
SHARED_END
#endif
