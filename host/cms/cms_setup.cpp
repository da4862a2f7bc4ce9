#include "cms/cms_setup.h"

namespace mixtrace {

CmsMethod cmsMethodFor(const MethodInfo& method) {
  CmsMethod m;
  if (!method.clusters) return m;   // the pt-* methods: no clusters, and the defaults unused
  m.clusters = true;
  m.controlVariate = method.controlVariate;
  m.learnSelection = method.learnSelection;
  m.defaults = method.selection;
  return m;
}

CmsMethod cmsMethodFor(const std::string& method) {
  const MethodInfo* row = findMethod(method);
  return row ? cmsMethodFor(*row) : CmsMethod{};
}

CmsScene setUpClusters(const PreparedScene& scene, std::vector<shared::LightSelectionGpu>& selection,
                       uint32_t maxClusters, LightSelection defaults, uint32_t maxTechniques) {
  CmsScene cms;
  cms.clusters = buildLightClusters(scene, maxClusters, defaults);
  LightClusters& c = cms.clusters;
  if (defaults != LightSelection::Uniform) {
    // The defaults are also the defensive part of a learned selection (docs/estimator.md §7). Half
    // of it uniform over clusters keeps every c_k >= eps / (2 L): the control-variate term of a
    // light sample, about alpha_k / c_k, stays bounded even for a cluster of very little power.
    const float uniform = 1.0f / float(c.defaultSelection.size());
    for (float& d : c.defaultSelection) d = 0.5f * d + 0.5f * uniform;
  }
  for (size_t light = 0; light < scene.lights.lights.size(); ++light) {
    selection[light].cluster = c.lightCluster[light];
    selection[light].clusterPmf = c.lightPmfInCluster[light];
  }
  cms.clusterLights.resize(c.clusterLights.size());
  for (const shared::ClusterGpu& cluster : c.clusters) {
    float cdf = 0.0f;
    for (uint32_t i = cluster.firstLight; i < cluster.firstLight + cluster.lightCount; ++i) {
      uint32_t light = c.clusterLights[i];
      cdf += c.lightPmfInCluster[light];
      cms.clusterLights[i].light = light;
      // The last entry is exactly 1 so that any u in [0, 1) finds a light.
      cms.clusterLights[i].cdf = (i + 1 == cluster.firstLight + cluster.lightCount) ? 1.0f : cdf;
    }
  }
  cms.techniques = buildLightTechniques(scene.lights, c, maxTechniques);
  return cms;
}

bool cmsReducesToPlainMis(const CmsMethod& method, const CmsScene& scene) {
  return method.learnSelection && method.controlVariate && scene.clusters.clusters.size() <= 1;
}

std::string plainMisNote(const CmsScene& scene, const std::string& estimator) {
  const std::string plainMis = "; rendering with plain MIS (" + estimator + "'s estimator; --method cv forces it)";
  if (scene.clusters.lightCluster.empty())   // one entry per light of the scene
    return "cms: the scene has no lights, so there is no light selection to learn and no direct light to "
           "control" + plainMis;
  return "cms: the scene's lights form one cluster, so there is no light selection to learn and the control "
         "variate alone does not pay" + plainMis;
}

}  // namespace mixtrace
