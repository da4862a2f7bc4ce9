// The CMS grid resolution of `--cells auto` (cms/grid_resolution.h): a cell covers about 16x16
// pixels of footprint at the primary hits, so the resolution follows the image and the camera,
// and stays in range for any scene.
#include "cms/grid_resolution.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "cms/cell_grid.h"

namespace mixtrace {
namespace {

constexpr float kPlaneSide = 10.0f;
constexpr uint32_t kClusters = 16;

// A grey square of side kPlaneSide in the plane z = 0, facing +Z: a flat scene (no extent in Z).
Scene flatPlane() {
  Scene s;
  s.name = "plane";
  MaterialGpu grey{};
  grey.baseColor = glm::vec3(0.5f);
  grey.roughness = 1.0f;
  grey.baseColorTexture = grey.metallicRoughnessTexture = grey.emissiveTexture = -1;
  s.materials.push_back(grey);
  const float h = 0.5f * kPlaneSide;
  const glm::vec3 p[4] = {{-h, -h, 0}, {h, -h, 0}, {h, h, 0}, {-h, h, 0}};
  for (const auto& [a, b, c] : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}}) {
    Triangle t{};
    t.p[0] = p[a]; t.p[1] = p[b]; t.p[2] = p[c];
    t.n[0] = t.n[1] = t.n[2] = glm::vec3(0, 0, 1);
    s.triangles.push_back(t);
    for (const glm::vec3& q : t.p) s.bounds.grow(q);
  }
  return s;
}

// The camera on the +Z axis at `distance`, looking at the plane's centre.
Scene withCamera(Scene s, float distance, float yfov, glm::vec3 forward = {0, 0, -1}) {
  s.camera.position = glm::vec3(0, 0, distance);
  s.camera.forward = forward;
  s.camera.up = glm::vec3(0, 1, 0);
  s.camera.yfov = yfov;
  s.camera.fromFile = true;
  return s;
}

GridResolution resolve(const PreparedScene& p, uint32_t width, uint32_t height) {
  return autoGridResolution(p, makeCamera(p.scene, width, height), kClusters);
}

// Facing a plane head-on, every pixel's footprint is the same square of edge 2 tan(fov/2) d / H
// (the cos^3 of the solid angle cancels the distance and slant terms), so the rule is exact.
TEST(GridResolution, AFrontalPlaneGivesTheFootprintFormula) {
  const float d = 5.0f, fov = 0.8f;
  const PreparedScene p = prepareScene(withCamera(flatPlane(), d, fov));
  const GridResolution r = resolve(p, 320, 240);
  EXPECT_EQ(r.primaryHits, kFootprintRaysPerSide * kFootprintRaysPerSide);
  const double pixelEdge = 2.0 * std::tan(0.5 * fov) * d / 240.0;
  EXPECT_NEAR(r.meanFootprintArea, pixelEdge * pixelEdge, 1e-3 * pixelEdge * pixelEdge);
  EXPECT_EQ(r.cells, uint32_t(std::lround(kPlaneSide / (kCellEdgePixels * pixelEdge))));  // 35
}

TEST(GridResolution, GrowsWithTheImageAndShrinksWithAWiderViewOrAFartherCamera) {
  const PreparedScene base = prepareScene(withCamera(flatPlane(), 5.0f, 0.8f));
  const uint32_t small = resolve(base, 160, 120).cells, large = resolve(base, 320, 240).cells;
  EXPECT_NEAR(double(large) / small, 2.0, 0.1) << small << " -> " << large;
  const PreparedScene wide = prepareScene(withCamera(flatPlane(), 5.0f, 1.2f));
  EXPECT_LT(resolve(wide, 320, 240).cells, large);
  const PreparedScene far = prepareScene(withCamera(flatPlane(), 8.0f, 0.8f));
  EXPECT_LT(resolve(far, 320, 240).cells, large);
  // Scale invariance: the scene and the camera scaled together choose the same grid.
  Scene scaled = withCamera(flatPlane(), 5.0f, 0.8f);
  for (Triangle& t : scaled.triangles)
    for (glm::vec3& q : t.p) q *= 100.0f;
  scaled.bounds.min *= 100.0f;
  scaled.bounds.max *= 100.0f;
  scaled.camera.position *= 100.0f;
  EXPECT_EQ(resolve(prepareScene(scaled), 320, 240).cells, large);
}

TEST(GridResolution, ClampedAtBothEnds) {
  const PreparedScene far = prepareScene(withCamera(flatPlane(), 50.0f, 1.5f));
  EXPECT_EQ(resolve(far, 16, 12).cells, kMinAutoCells);
  const PreparedScene near = prepareScene(withCamera(flatPlane(), 0.5f, 0.3f));
  EXPECT_EQ(resolve(near, 16384, 12288).cells, maxAutoCells(kClusters));
  EXPECT_EQ(cellsForFootprint(1e-30, flatPlane().bounds, kClusters), maxAutoCells(kClusters));
  EXPECT_EQ(cellsForFootprint(1e30, flatPlane().bounds, kClusters), kMinAutoCells);
}

// What the table holds bounds the resolution: more clusters, wider statistics, fewer slots.
TEST(GridResolution, TheLargestResolutionFitsTheCellTable) {
  uint32_t previous = kMaxAutoCells;
  for (uint32_t L : {1u, 4u, 16u, 32u, 256u, 5000u}) {
    const uint32_t hi = maxAutoCells(L);
    EXPECT_LE(hi, previous) << L;
    EXPECT_GE(hi, kMinAutoCells) << L;
    if (hi > kMinAutoCells) EXPECT_LE(48ull * hi * hi, cellTableSlotLimit(L)) << L;
    previous = hi;
  }
  EXPECT_GE(maxAutoCells(16), 32u) << "the resolutions the issue measured as better than 16 must be reachable";
}

TEST(GridResolution, DegenerateScenesGiveAValidGrid) {
  Bounds point;
  point.grow(glm::vec3(1.0f));
  EXPECT_EQ(cellsForFootprint(0.01, point, kClusters), kMinAutoCells);
  EXPECT_EQ(cellsForFootprint(0.01, Bounds{}, kClusters), kMinAutoCells);  // empty
  for (double area : {0.0, -1.0, double(NAN), double(INFINITY)}) {
    const uint32_t c = cellsForFootprint(area, flatPlane().bounds, kClusters);
    EXPECT_GE(c, kMinAutoCells) << area;
    EXPECT_LE(c, maxAutoCells(kClusters)) << area;
  }
  // A camera that sees nothing: no hits, today's default, and a grid makeCellGrid accepts.
  const PreparedScene away = prepareScene(withCamera(flatPlane(), 5.0f, 0.8f, {0, 0, 1}));
  const GridResolution r = resolve(away, 320, 240);
  EXPECT_EQ(r.primaryHits, 0u);
  EXPECT_EQ(r.cells, kFallbackCells);
  const CellGridSetup grid = makeCellGrid(away.scene.bounds, r.cells, kClusters);
  EXPECT_TRUE(std::isfinite(grid.invCellSize));
  EXPECT_GT(grid.invCellSize, 0.0f);
}

// Grazing hits would dominate the mean with areas no cell is ever that large in: held at |cos| 0.1.
TEST(GridResolution, AGrazingHitsFootprintIsBounded) {
  shared::CameraGpu c{};
  c.forward = glm::vec3(0, 0, -1);
  c.tanHalfFovY = 0.5f;
  c.height = 100;
  const float headOn = pixelFootprintArea(c, c.forward, 2.0f, 1.0f);
  EXPECT_NEAR(headOn, 4.0f * 0.01f * 0.01f, 1e-9f);
  EXPECT_FLOAT_EQ(pixelFootprintArea(c, c.forward, 2.0f, 1e-6f), 10.0f * headOn);
  EXPECT_FLOAT_EQ(pixelFootprintArea(c, c.forward, 2.0f, -0.5f), 2.0f * headOn);
}

}  // namespace
}  // namespace mixtrace
