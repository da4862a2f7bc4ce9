#pragma once
// The environment light as the shaders read it: the one float buffer of
// shared/environment_layout.h, with the piecewise-constant distribution that
// shared/environment.h samples (each texel weighted by luminance x its solid angle).
#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace mixtrace {

// The ENVIRONMENT buffer; `light` is the environment's index in the light set (-1: none, and then
// only the header, which says so).
std::vector<float> buildEnvironmentBuffer(const Environment& env, int32_t light);

// The integral of luminance(L) over the sphere of directions, of the map as the renderer reads it
// (piecewise constant per texel): the environment's light-selection power is pi r^2 times this
// (what crosses a disk of the scene's radius).
double environmentLuminanceIntegral(const Environment& env);

}  // namespace mixtrace
