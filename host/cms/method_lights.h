#pragma once
// A method's light data, beside the prepared scene (which describes the lights and is the same for
// every method): how the method picks a light, one LightSelectionGpu per light (the selection
// pmf and CDF and, for the methods with light clusters, each light's cluster and its pmf inside
// it), and the clusters themselves. The Vulkan renderer uploads `selection` as one buffer
// (BINDING_LIGHT_SELECTION); the CPU reference reads it through scene/shared_scene_access.h.
#include <cstdint>
#include <vector>

#include "cms/cms_setup.h"
#include "cms/methods.h"
#include "scene/prepared_scene.h"
#include "shared/layouts.h"

namespace mixtrace {

struct MethodLights {
  LightSelection kind = LightSelection::Power;         // the method's (the triangle inside a light too)
  std::vector<shared::LightSelectionGpu> selection;   // per light of the prepared scene
  CmsScene cms;                                        // the light clusters, for methods with clusters
  std::vector<shared::LightBvhNodeGpu> bvh;            // the light BVH (LightSelection::Bvh), else empty
};

// The tables of `method` on `scene`: the row's light selection and, where the row has clusters,
// at most maxClusters of them with the row's selection as their defaults. Reads the scene only.
// maxTechniques bounds the control variate's techniques (cms/light_techniques.h).
MethodLights buildMethodLights(const PreparedScene& scene, const MethodInfo& method, uint32_t maxClusters,
                               uint32_t maxTechniques = kDefaultMaxTechniques);

}  // namespace mixtrace
