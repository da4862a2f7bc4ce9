#include "cpu/cpu_cms_path.h"

#include "cpu/cpu_kernel_access.h"

// The shared loop's two hooks (shared/cms_path_tracer.h), on the calling thread's cells.
#define CMS_PATH_WEIGHT(cell, beta, pixel) (::mixtrace::boundCpuKernel().cms->statisticsWeight(cell, beta, pixel))
#define CMS_PATH_COUNT_VERTEX(cell) ::mixtrace::countCmsVertex(cell)

namespace mixtrace {
namespace {

void countCmsVertex(uint32_t cell) {
  CpuCmsCells& cells = *boundCpuKernel().cms;
  if (cell == shared::kNoCell) cells.countVertexWithoutCell();
  else if (cells.gathering(cell)) cells.countVertex(cell);
}

}  // namespace
}  // namespace mixtrace

#include "shared/cms_path_tracer.h"

namespace mixtrace {

glm::vec3 traceCmsPath(glm::vec3 origin, glm::vec3 direction, uint32_t& rng, const CmsPathContext& ctx,
                       RenderCounters& counters) {
  const CpuCmsCells& cells = *ctx.cells;
  shared::CmsPathSetup c{};
  c.grid.origin = cells.grid().origin;
  c.grid.invCellSize = cells.grid().invCellSize;
  c.grid.tableSize = cells.grid().tableSize;
  c.clusterCount = cells.clusterCount();
  c.controlVariate = cells.controlVariate();
  c.pairTechniques = cells.pairTechniques();
  c.pairCapacity = cells.pairCapacity();
  c.emitterCount = cells.emitterCount();
  c.maxDepth = ctx.maxDepth;
  c.lightCount = ctx.lightCount;
  c.pixel = ctx.pixel;
  shared::PathCounters rays{0u, 0u};
  uint32_t firstCell;   // (the viewer's cell views are the Vulkan renderer's)
  const glm::vec3 radiance = shared::traceCmsPath(c, origin, direction, rng, rays, firstCell);
  counters.extensionRays += rays.extensionRays;
  counters.shadowRays += rays.shadowRays;
  return radiance;
}

}  // namespace mixtrace
