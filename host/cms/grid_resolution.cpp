#include "cms/grid_resolution.h"

#include <algorithm>
#include <cmath>

#include "cms/cell_grid.h"

// The traversal reads the BVH through these macros (as a shader reads its storage buffers); they
// name the scene autoGridResolution is tracing, set for the duration of that call on its thread.
namespace mixtrace::grid_resolution_buffers {
thread_local const PreparedScene* scene = nullptr;
}  // namespace mixtrace::grid_resolution_buffers
#define BVH_NODE(i) (::mixtrace::grid_resolution_buffers::scene->bvh.nodes[i])
#define BVH_TRIANGLE(i) (::mixtrace::grid_resolution_buffers::scene->bvh.triangles[i])
#include "shared/bvh_traverse.h"
#include "shared/camera.h"

namespace mixtrace {

float pixelFootprintArea(const shared::CameraGpu& camera, glm::vec3 direction, float distance, float cosAtSurface) {
  // A pixel's edge on the image plane at distance 1 (square pixels: the aspect is width/height).
  const float pixelEdge = 2.0f * camera.tanHalfFovY / float(std::max(camera.height, 1u));
  const float cosAxis = std::max(glm::dot(direction, camera.forward), 0.0f);
  const float solidAngle = pixelEdge * pixelEdge * cosAxis * cosAxis * cosAxis;
  return solidAngle * distance * distance / std::max(std::abs(cosAtSurface), 0.1f);
}

uint32_t maxAutoCells(uint32_t clusters) {
  // The table is sized for 48 slots per cell^2 (cellTableSizeFor); beyond the resolution whose
  // wanted size reaches the table's memory limit, finer cells would only overflow the table.
  const double fits = std::floor(std::sqrt(double(cellTableSlotLimit(clusters)) / 48.0));
  return uint32_t(std::clamp(fits, double(kMinAutoCells), double(kMaxAutoCells)));
}

uint32_t cellsForFootprint(double meanFootprintArea, const Bounds& b, uint32_t clusters) {
  const uint32_t hi = maxAutoCells(clusters);
  const double longest = std::max({double(b.extent().x), double(b.extent().y), double(b.extent().z)});
  if (!(longest > 0.0) || !std::isfinite(longest)) return kMinAutoCells;  // a point: one cell does
  if (!(meanFootprintArea > 0.0)) return hi;                              // pixels of no size
  const double cellEdge = kCellEdgePixels * std::sqrt(meanFootprintArea);
  const double cells = longest / cellEdge;
  if (!std::isfinite(cells)) return hi;
  return uint32_t(std::clamp(std::round(cells), double(kMinAutoCells), double(hi)));
}

GridResolution autoGridResolution(const PreparedScene& scene, const shared::CameraGpu& camera, uint32_t clusters) {
  GridResolution r;
  if (scene.bvh.nodes.empty()) return r;
  grid_resolution_buffers::scene = &scene;
  double areaSum = 0.0;
  const uint32_t n = kFootprintRaysPerSide;
  for (uint32_t j = 0; j < n; ++j)
    for (uint32_t i = 0; i < n; ++i) {
      // The centre of the pixel at the centre of stratum (i, j).
      const uint32_t x = std::min(uint32_t((i + 0.5) * camera.width / n), camera.width - 1);
      const uint32_t y = std::min(uint32_t((j + 0.5) * camera.height / n), camera.height - 1);
      const glm::vec3 dir = shared::cameraRayDirection(camera, x, y, glm::vec2(0.5f));
      const shared::HitRecord hit = shared::traceClosest(camera.position, dir, 3.0e38f);
      if (hit.triangle == shared::kNoHit) continue;
      const shared::TriangleGeom& tri = scene.bvh.triangles[hit.triangle];
      const glm::vec3 normal = glm::cross(tri.e1, tri.e2);
      const float normalLength = glm::length(normal);
      const float cosAtSurface = normalLength > 0.0f ? glm::dot(normal, dir) / normalLength : 1.0f;
      areaSum += pixelFootprintArea(camera, dir, hit.t, cosAtSurface);
      ++r.primaryHits;
    }
  grid_resolution_buffers::scene = nullptr;
  if (r.primaryHits == 0) return r;  // nothing seen: no vertex will ask for a cell
  r.meanFootprintArea = areaSum / r.primaryHits;
  r.cells = cellsForFootprint(r.meanFootprintArea, scene.scene.bounds, clusters);
  return r;
}

}  // namespace mixtrace
