#pragma once
// How a method picks one light of a light set at a shading point: uniformly, or in proportion to
// the lights' emitted power. The distribution is the method's, so it lives beside the prepared
// scene (one LightSelectionGpu per light, host/cms/method_lights.h) and not in its lights; the
// same prepared scene serves every method.
#include <vector>

#include "scene/light_set.h"
#include "shared/layouts.h"

namespace mixtrace {

// Uniform: every emissive triangle (and punctual light) equally likely, as the paper's baseline,
// SeeSharp and pbrt-v4's uniform light sampler pick lights (each makes every emissive triangle a
// light): a light in proportion to its triangle count, then one of its triangles uniformly.
// Power: a light in proportion to its emitted power, then a triangle by area x radiance.
// Bvh: by the light BVH at the shading point (scene/light_bvh.h); its method's table below holds
// the power distribution, which no part of the BVH path reads. The values are the shaders'
// kLightSelect* (shared/layouts.h), which the vertex passes receive.
enum class LightSelection : uint32_t {
  Uniform = shared::kLightSelectUniform,
  Power = shared::kLightSelectPower,
  Bvh = shared::kLightSelectBvh,
};

// The weight of light `l` under uniform selection: its triangle count (1 for a punctual light).
inline double uniformSelectionWeight(const shared::LightGpu& l) {
  return l.kind == shared::kLightArea ? double(l.emitterCount) : 1.0;
}

// One entry per light of `lights`: the selection pmf and its inclusive CDF (the last entry exactly
// 1), uniform where every weight is 0. Every light is its own cluster with in-cluster pmf 1: what
// a method without light clusters reads (cms/cms_setup.h records the clusters of the others).
std::vector<shared::LightSelectionGpu> buildLightSelection(const LightSet& lights, LightSelection selection);

}  // namespace mixtrace
