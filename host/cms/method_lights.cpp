#include "cms/method_lights.h"

#include "scene/light_bvh.h"

namespace mixtrace {

MethodLights buildMethodLights(const PreparedScene& scene, const MethodInfo& method, uint32_t maxClusters,
                               uint32_t maxTechniques) {
  MethodLights m;
  m.kind = method.selection;
  m.selection = buildLightSelection(scene.lights, method.selection);
  if (method.selection == LightSelection::Bvh) m.bvh = buildLightBvh(scene);
  if (method.clusters) m.cms = setUpClusters(scene, m.selection, maxClusters, method.selection, maxTechniques);
  return m;
}

}  // namespace mixtrace
