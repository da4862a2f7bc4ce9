#pragma once
// How a method picks one light of a light set at a shading point: uniformly, or in proportion to
// the lights' emitted power. The distribution is the method's, so it lives beside the prepared
// scene (one LightSelectionGpu per light, host/cms/method_lights.h) and not in its lights; the
// same prepared scene serves every method.
#include <vector>

#include "scene/light_set.h"
#include "shared/layouts.h"

namespace mixtrace {

// Bvh: by the light BVH at the shading point (scene/light_bvh.h); its method's table below holds
// the power distribution, which no part of the BVH path reads.
enum class LightSelection { Uniform, Power, Bvh };

// One entry per light of `lights`: the selection pmf and its inclusive CDF (the last entry exactly
// 1), uniform where every weight is 0. Every light is its own cluster with in-cluster pmf 1: what
// a method without light clusters reads (cms/cms_setup.h records the clusters of the others).
std::vector<shared::LightSelectionGpu> buildLightSelection(const LightSet& lights, LightSelection selection);

}  // namespace mixtrace
