#pragma once
// How many cells the CMS grid has along the scene's longest axis when `--cells auto` asks the
// renderer to choose: the rule of the reference implementation (AdaptGridResolution in
// qingqhua/ControlledMixtureSampling), in our terms. A cell should cover about 16 x 16 pixels
// where the camera sees the scene: the world-space area one pixel covers at the primary hits
// (its footprint) is averaged over a fixed set of primary rays, and the grid's cell edge is 16
// times the square root of that mean. One function, device-free, for both backends
// (docs/estimator.md §5).
#include <cstdint>

#include <glm/glm.hpp>

#include "scene/prepared_scene.h"
#include "shared/layouts.h"
#include "util/bounds.h"

namespace mixtrace {

// The cell's edge in pixels the rule aims at (the reference's choice).
constexpr uint32_t kCellEdgePixels = 16;
// Fewer cells than this along the longest axis lump a whole room into a handful of cells.
constexpr uint32_t kMinAutoCells = 4;
// More than this and a cell sees too few vertices per iteration at any sample count worth
// rendering here; the reference's own experiments stop at 256 too.
constexpr uint32_t kMaxAutoCells = 256;
// What `--cells auto` gives when no primary ray hits the scene (there are no vertices to key, so
// any grid does): today's fixed default.
constexpr uint32_t kFallbackCells = 16;
// The primary rays the rule traces: a kFootprintRaysPerSide^2 stratified grid of pixel centres.
// Deterministic, so that both backends and every run of a scene choose the same grid.
constexpr uint32_t kFootprintRaysPerSide = 16;

// World-space area one pixel of `camera` covers on a surface at `distance` along the unit
// `direction`, whose normal makes the cosine `cosAtSurface` with the ray: the pixel's solid angle
// (its area on the image plane at distance 1, times cos^3 of the angle to the optical axis) times
// distance^2 / |cos|. |cos| is held above 0.1: a grazing hit would otherwise dominate the mean with
// an area no cell is ever that large in.
float pixelFootprintArea(const shared::CameraGpu& camera, glm::vec3 direction, float distance, float cosAtSurface);

// The largest resolution the cell table holds with `clusters` clusters (cms/cell_grid.h), capped
// at kMaxAutoCells.
uint32_t maxAutoCells(uint32_t clusters);

// Cells along the longest axis of `bounds` for a mean pixel footprint area: the longest extent
// over (kCellEdgePixels * sqrt(area)), clamped to [kMinAutoCells, maxAutoCells(clusters)]. A
// degenerate input (no extent, no area, not finite) gives a value in that range too.
uint32_t cellsForFootprint(double meanFootprintArea, const Bounds& bounds, uint32_t clusters);

struct GridResolution {
  uint32_t cells = kFallbackCells;
  uint32_t primaryHits = 0;        // of the kFootprintRaysPerSide^2 rays traced
  double meanFootprintArea = 0.0;  // world units^2; 0 without hits
};

// The rule on a scene: traces the primary rays of `camera` (the image size is the camera's) on the
// host through the shared BVH traversal, and turns the mean footprint at their hits into cells.
GridResolution autoGridResolution(const PreparedScene& scene, const shared::CameraGpu& camera, uint32_t clusters);

}  // namespace mixtrace
