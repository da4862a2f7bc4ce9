#include "session/method_setup.h"

#include "util/log.h"

namespace mixtrace {
namespace {

LightSelection selectionFor(const std::string& method) {
  if (method == "pt-uniform") return LightSelection::Uniform;
  if (method == "pt-power") return LightSelection::Power;
  return cmsMethodFor(method).defaults;
}

}  // namespace

MethodSetup setUpMethod(const Scene& scene, const RenderOptions& o, const std::string& method) {
  MethodSetup m;
  m.prepared = prepareScene(scene, selectionFor(method));
  RenderSettings& s = m.settings;
  s.width = uint32_t(o.width);
  s.height = uint32_t(o.height);
  s.maxDepth = uint32_t(o.maxDepth);
  s.seed = o.seed;
  s.generalPipelines = o.generalPipelines;
  s.cms = cmsMethodFor(method);
  s.cells = uint32_t(o.cells);
  s.relativeWeighting = o.relativeWeighting;
  s.floatAtomics = o.floatAtomics;
  s.trainSpp = uint32_t(o.trainSpp);
  if (s.cms.clusters) m.cms = setUpClusters(m.prepared, uint32_t(o.maxClusters), s.cms.defaults);
  m.estimator = method;
  if (cmsReducesToPlainMis(s.cms, m.cms)) {
    info(plainMisNote(m.cms));
    s.cms = CmsMethod{};
    m.estimator = "pt-power";
  }
  return m;
}

}  // namespace mixtrace
