// glTF alpha (shared/alpha.h), rendered by the real binary on both backends and judged by the
// per-pixel statistical comparison with a scene that means the same without alpha:
//   - MASK: a quad whose alpha runs from 0 to 1 across it, cut at 0.5, hides and shadows exactly as
//     the opaque half quad does (camera rays and shadow rays alike);
//   - BLEND: a black plane of alpha 0.5 between a light and a floor passes half the light, as the
//     same light at half its radiance does without the plane (stochastic transparency: unbiased);
//   - OPAQUE ignores alpha; scenes without alpha specialise it away (the stats' features).
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "compare/image_compare.h"
#include "support/analytic/gltf_writer.h"
#include "support/analytic/meshes.h"
#include "support/render_with_stats.h"
#include "support/run_binary.h"

namespace {

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;
using namespace mixtrace::testing::analytic;

const MaterialSpec kFloor{glm::vec3(0.8f), 0.0f, 1.0f, glm::vec3(0.0f), false};

MaterialSpec emitter(float le) { return MaterialSpec{glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(le), false}; }

CameraSpec overhead(double height) {
  CameraSpec camera;
  camera.position = {0.0, height, 1.4};
  camera.target = {0.0, 0.0, 0.0};
  camera.yfov = 1.0;
  return camera;
}

RenderWithStats render(const fs::path& dir, const std::string& name, const GltfWriter& w, const std::string& backend,
                       int seed, const std::string& extra = "") {
  const fs::path scene = dir / (name + ".gltf");
  writeFile(scene, w.json());
  RenderWithStats r = renderWithStats(scene.string() + " --width 40 --height 30 --spp 128 --max-depth 2 --method pt-power --backend " +
                                          backend + " --seed " + std::to_string(seed) + " " + extra,
                                      dir / (name + ".exr"), 600);
  EXPECT_EQ(r.exitCode, 0) << name << ": " << r.stderrText;
  return r;
}

ComparisonResult compare(const RenderWithStats& a, const RenderWithStats& b) {
  return compareImages(a.mean, a.variance, b.mean, b.variance);
}

class Alpha : public ::testing::TestWithParam<const char*> {};

TEST_P(Alpha, MaskedQuadHidesAndShadowsAsItsOpaqueHalf) {
  const fs::path dir = scratchDir("alpha-mask");
  const std::vector<Tri> floor = rectangle({-1.5, 0.0, 1.5}, {3.0, 0.0, 0.0}, {0.0, 0.0, -3.0}, {0.0, 1.0, 0.0});
  const std::vector<Tri> light = rectangle({-0.5, 1.6, -0.5}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {0.0, -1.0, 0.0});
  // The occluder at y = 0.8: alpha 0 at x = -0.6, 1 at x = +0.6 (COLOR_0's alpha), so MASK at 0.5
  // keeps x > 0: exactly the half quad of the reference.
  const std::vector<Tri> occluder = rectangle({-0.6, 0.8, 0.6}, {1.2, 0.0, 0.0}, {0.0, 0.0, -1.2}, {0.0, 1.0, 0.0});
  std::vector<glm::vec4> alphaRamp;
  for (const Tri& t : occluder)
    for (const glm::vec3& p : t.p) alphaRamp.push_back(glm::vec4(1.0f, 1.0f, 1.0f, p.x < 0.0f ? 0.0f : 1.0f));
  const std::vector<Tri> half = rectangle({0.0, 0.8, 0.6}, {0.6, 0.0, 0.0}, {0.0, 0.0, -1.2}, {0.0, 1.0, 0.0});
  const MaterialSpec grey{glm::vec3(0.3f, 0.5f, 0.7f), 0.0f, 1.0f, glm::vec3(0.0f), false};
  MaterialSpec masked = grey;
  masked.alphaMode = "MASK";

  GltfWriter withMask, withHalf, opaque;
  for (GltfWriter* w : {&withMask, &withHalf, &opaque}) {
    w->addMesh(floor, w->addMaterial(kFloor));
    w->addMesh(light, w->addMaterial(emitter(6.0f)));
    w->setCamera(overhead(2.2));
  }
  withMask.addMesh(occluder, withMask.addMaterial(masked), alphaRamp);
  withHalf.addMesh(half, withHalf.addMaterial(grey));
  opaque.addMesh(occluder, opaque.addMaterial(grey), alphaRamp);  // OPAQUE: alpha ignored

  const RenderWithStats mask = render(dir, "mask", withMask, GetParam(), 1);
  const RenderWithStats reference = render(dir, "half", withHalf, GetParam(), 2);
  const RenderWithStats whole = render(dir, "opaque", opaque, GetParam(), 3);
  const ComparisonResult same = compare(mask, reference);
  EXPECT_TRUE(same.agree) << same.summary();
  const ComparisonResult differs = compare(whole, reference);
  EXPECT_FALSE(differs.agree) << "the test cannot tell the whole quad from its half: " << differs.summary();
  EXPECT_NE(mask.stats["features"].get<std::string>().find("alpha=1"), std::string::npos) << mask.stats["features"];
  EXPECT_NE(whole.stats["features"].get<std::string>().find("alpha=0"), std::string::npos) << whole.stats["features"];
  // The general pipelines (alpha compiled in) render the same image for the same seed.
  const RenderWithStats general = render(dir, "opaque-general", opaque, GetParam(), 3, "--general-pipelines");
  EXPECT_TRUE(compare(general, whole).agree);
  EXPECT_LT(compare(general, whole).relMse, 1e-8);
}

// The camera sits under the plane, which only stands between the light and the floor; at max
// depth 2 the floor sees the light through it with probability 1/2.
TEST_P(Alpha, HalfBlendedPlanePassesHalfTheLight) {
  const fs::path dir = scratchDir("alpha-blend");
  const std::vector<Tri> floor = rectangle({-1.5, 0.0, 1.5}, {3.0, 0.0, 0.0}, {0.0, 0.0, -3.0}, {0.0, 1.0, 0.0});
  const std::vector<Tri> light = rectangle({-0.5, 1.6, -0.5}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, {0.0, -1.0, 0.0});
  const std::vector<Tri> plane = rectangle({-4.0, 1.2, 4.0}, {8.0, 0.0, 0.0}, {0.0, 0.0, -8.0}, {0.0, 1.0, 0.0});
  MaterialSpec blackBlend{glm::vec3(0.0f), 1.0f, 1.0f, glm::vec3(0.0f), false};  // black metal: reflects nothing
  blackBlend.alphaMode = "BLEND";
  blackBlend.alpha = 0.5f;

  GltfWriter blended, halved, full;
  blended.addMesh(floor, blended.addMaterial(kFloor));
  blended.addMesh(light, blended.addMaterial(emitter(6.0f)));
  blended.addMesh(plane, blended.addMaterial(blackBlend));
  halved.addMesh(floor, halved.addMaterial(kFloor));
  halved.addMesh(light, halved.addMaterial(emitter(3.0f)));
  full.addMesh(floor, full.addMaterial(kFloor));
  full.addMesh(light, full.addMaterial(emitter(6.0f)));
  for (GltfWriter* w : {&blended, &halved, &full}) w->setCamera(overhead(1.0));

  const RenderWithStats blend = render(dir, "blend", blended, GetParam(), 1);
  const RenderWithStats half = render(dir, "halved", halved, GetParam(), 2);
  const RenderWithStats whole = render(dir, "full", full, GetParam(), 3);
  const ComparisonResult same = compare(blend, half);
  EXPECT_TRUE(same.agree) << same.summary();
  EXPECT_FALSE(compare(blend, whole).agree) << "the test cannot tell half the light from all of it";
}

INSTANTIATE_TEST_SUITE_P(Backends, Alpha, ::testing::Values("vulkan", "cpu"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
