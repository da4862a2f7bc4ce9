#include "session/method_setup.h"

#include "cms/grid_resolution.h"
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
  s.schedule = o.schedule == "fused"       ? RenderSettings::Schedule::Fused
               : o.schedule == "wavefront" ? RenderSettings::Schedule::Wavefront
                                           : RenderSettings::Schedule::Auto;
  s.aovs = !o.aov.empty();
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
    // The lights keep the method's own selection (its defaults), so the image is that plain
    // method's, and the stats and header name it.
    const MethodInfo* plain = plainMisMethodFor(m.lights.kind);
    if (plain == nullptr) throw Error("internal: no plain MIS method selects lights as " + method + " does");
    info(plainMisNote(m.lights.cms, plain->name));
    s.cms = CmsMethod{};
    m.estimator = plain->name;
  }
  if (o.cells == 0 && s.cms.clusters) {
    const GridResolution grid = autoGridResolution(prepared, makeCamera(prepared.scene, s.width, s.height),
                                                   uint32_t(m.lights.cms.clusters.clusters.size()));
    s.cells = grid.cells;
    m.cellsChosen = true;
    info("--cells auto: " + std::to_string(grid.cells) + " cells along the longest axis (" +
         std::to_string(grid.primaryHits) + " of " + std::to_string(kFootprintRaysPerSide * kFootprintRaysPerSide) +
         " primary rays hit; a cell covers about " + std::to_string(kCellEdgePixels) + "x" +
         std::to_string(kCellEdgePixels) + " pixels)");
  } else if (o.cells == 0) {
    s.cells = kFallbackCells;  // no cells in this method: any valid value
  }
  return m;
}

}  // namespace mixtrace
