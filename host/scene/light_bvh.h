#pragma once
// The light BVH of method pt-bvh (shared/light_bvh.h descends it): a tree over the scene's lights
// with positions (area and punctual lights), each node bounding its lights' box, power and
// orientation cone; directional lights beside it, chosen with a fixed probability by power (as
// pbrt-v4's BVHLightSampler chooses its infinite lights). A method's table like the light
// selection (cms/method_lights.h), flattened in the layout of shared::LightBvhNodeGpu.
#include <vector>

#include "scene/prepared_scene.h"
#include "shared/layouts.h"

namespace mixtrace {

// The flattened tree of `scene`'s lights: header, one entry per light, the directional list, the
// interior nodes (shared/layouts.h). Every light's bit-trail fits in 32 bits.
std::vector<shared::LightBvhNodeGpu> buildLightBvh(const PreparedScene& scene);

}  // namespace mixtrace
