#include "session/method_setup.h"

#include "cms/methods.h"
#include "util/error.h"
#include "util/log.h"

namespace mixtrace {

MethodSetup setUpMethod(const PreparedScene& prepared, const RenderOptions& o, const std::string& method) {
  // The option parser admits only the table's methods; a name from elsewhere is a bug.
  const MethodInfo* row = findMethod(method);
  if (!row) throw Error("unknown method '" + method + "'");
  MethodSetup m;
  RenderSettings& s = m.settings;
  s.width = uint32_t(o.width);
  s.height = uint32_t(o.height);
  s.maxDepth = uint32_t(o.maxDepth);
  s.seed = o.seed;
  s.generalPipelines = o.generalPipelines;
  s.cms = cmsMethodFor(*row);
  s.cells = uint32_t(o.cells);
  s.relativeWeighting = o.relativeWeighting;
  s.floatAtomics = o.floatAtomics;
  s.trainSpp = uint32_t(o.trainSpp);
  s.trainOnce = o.trainOnce;
  s.perTriangleCv = o.perTriangleCv;
  s.pairTableSlots = uint32_t(o.pairTableSlots);
  m.lights = buildMethodLights(prepared, *row, uint32_t(o.maxClusters), uint32_t(o.maxTechniques));
  m.estimator = method;
  if (cmsReducesToPlainMis(s.cms, m.lights.cms)) {
    info(plainMisNote(m.lights.cms));
    s.cms = CmsMethod{};
    m.estimator = kPlainMisMethod;
  }
  return m;
}

}  // namespace mixtrace
