// Issue 13's scale point, end to end: a scene with 10,000 emissive triangles renders with one
// control-variate technique per triangle (--max-techniques 16384) within lavapipe's limits (each
// storage buffer at most 128 MiB: the device would refuse a larger one, and the render would
// fail), with the pair table's memory reported, zero validation errors, no NaN or Inf, and an
// image that agrees with pt-uniform per pixel; under the default budget the same triangles merge
// into groups. The light: a ceiling panel of 100 x 50 small quads (one glTF primitive), plus a
// small second light so that cms has two clusters to choose between.
#include <string>

#include <gtest/gtest.h>

#include "support/hard_scenes.h"
#include "support/render_agreement.h"

using namespace mixtrace;
using namespace mixtrace::testing;

namespace {

constexpr int kColumns = 100, kRows = 50;   // 2 triangles per quad: 10,000 emissive triangles

std::string manyEmittersScene() {
  using namespace mixtrace::testing::hard;
  GltfWriter w;
  addRoom(w, 1.0);
  addBox(w, {-0.6, 0.0, -0.7}, {-0.1, 0.6, -0.2}, w.addMaterial({glm::vec3(0.6f, 0.6f, 0.8f)}), false);
  const int panel = w.addMaterial({glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(4.0f)});
  std::vector<Tri> tris;
  const double width = 1.2, depth = 0.6, du = width / kColumns, dw = depth / kRows;
  for (int i = 0; i < kColumns; ++i)
    for (int j = 0; j < kRows; ++j) {
      std::vector<Tri> quad = rectangle({-0.6 + i * du, 1.999, -0.8 + j * dw}, {du, 0, 0}, {0, 0, dw}, {0, -1, 0});
      tris.insert(tris.end(), quad.begin(), quad.end());
    }
  w.addMesh(tris, panel);
  addCeilingLight(w, {0.6, 1.999, 0.3}, 0.2, 8.0f);
  w.setCamera(roomCamera(1.0));
  return w.json();
}

RenderWithStats renderVulkan(const std::string& scene, const std::string& args, const std::string& name) {
  RenderWithStats r = renderWithStats(scene + " --backend vulkan " + args,
                                      scratchDir("many_emitters") / (name + ".exr"), 1200);
  EXPECT_EQ(r.exitCode, 0) << name << ": " << r.stderrText;
  if (r.exitCode == 0) {
    EXPECT_EQ(r.stats.value("validation_errors", -1), 0) << name;
    EXPECT_EQ(r.stats["non_finite_samples"].get<uint64_t>(), 0u) << name;
  }
  return r;
}

}  // namespace

TEST(CmsManyEmitters, TenThousandEmissiveTrianglesRenderPerTriangleWithinTheDeviceLimits) {
  const std::string scene = (scratchDir("many_emitters") / "panel.gltf").string();
  writeFile(scene, manyEmittersScene());
  const std::string image = " --width 40 --height 30 --spp 64 --variance";
  RenderWithStats baseline = renderVulkan(scene, image + " --method pt-uniform --seed 1", "pt-uniform");
  RenderWithStats cms = renderVulkan(scene, image + " --method cms --max-techniques 16384 --seed 2", "cms");
  ASSERT_FALSE(baseline.mean.rgb.empty() || cms.mean.rgb.empty());
  EXPECT_EQ(cms.stats["estimator"], "cms");
  EXPECT_EQ(cms.stats["cms_cv_techniques"], "triangle");
  EXPECT_EQ(cms.stats["cms_techniques"].get<uint64_t>(), 2u * kColumns * kRows + 2u) << "one per emissive triangle";
  EXPECT_FALSE(cms.stats["cms_techniques_merged"].get<bool>());
  EXPECT_GT(cms.stats["cms_pairs_used"].get<uint64_t>(), 1000u) << "the panel's triangles reach the cells";
  // The memory used is reported; the table's buffers are each within the device's limit, or the
  // render above would have failed to allocate them.
  const uint64_t bytes = cms.stats["cms_pair_buffer_bytes"].get<uint64_t>();
  EXPECT_GT(bytes, 0u);
  EXPECT_LT(bytes, 4ull * 128ull * 1024ull * 1024ull);
  const ComparisonResult c = compareImages(cms.mean, cms.variance, baseline.mean, baseline.variance);
  EXPECT_TRUE(c.agree) << c.summary();

  RenderWithStats merged = renderVulkan(scene, " --width 16 --height 12 --spp 4 --method cv --seed 3", "merged");
  EXPECT_TRUE(merged.stats["cms_techniques_merged"].get<bool>()) << "the default budget merges triangles";
  EXPECT_LE(merged.stats["cms_techniques"].get<uint64_t>(), 128u);
}
