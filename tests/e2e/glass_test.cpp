// Glass (KHR_materials_transmission, _ior, _volume; shaders/shared/dielectric.h) rendered by the
// real binary on both backends:
//   - a clear smooth glass sphere in a white furnace is invisible: a closed volume of a lossless
//     dielectric neither creates nor absorbs light, so every pixel sees radiance 1;
//   - a rough one loses only what single-scattering microfacets lose (a few per cent), never more
//     than 1 comes out;
//   - a clear thin pane of IOR 1 (no reflection, no bending) between a light and a floor leaves the
//     floor as without it: the light reaches the floor through the pane by BSDF sampling alone,
//     since shadow rays stop at glass;
//   - controlled mixture sampling (whose statistics see transmitted samples) agrees with
//     pt-uniform in a room with a glass sphere;
//   - the feature is compiled only into scenes that have glass (the stats' features).
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "compare/image_compare.h"
#include "support/analytic/expect_matches.h"
#include "support/analytic/gltf_writer.h"
#include "support/analytic/meshes.h"
#include "support/analytic/pixel_expectation.h"
#include "support/analytic/pixel_ztest.h"
#include "support/image_difference.h"
#include "support/render_with_stats.h"
#include "support/run_binary.h"

namespace {

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;
using namespace mixtrace::testing::analytic;

MaterialSpec glass(float roughness, float ior, bool volumetric) {
  MaterialSpec m{glm::vec3(1.0f), 0.0f, roughness, glm::vec3(0.0f), true};
  m.transmission = 1.0f;
  m.ior = ior;
  m.volumetric = volumetric;
  return m;
}

RenderWithStats render(const fs::path& dir, const std::string& name, const GltfWriter& w, const std::string& args) {
  const fs::path scene = dir / (name + ".gltf");
  writeFile(scene, w.json());
  RenderWithStats r = renderWithStats(scene.string() + " " + args, dir / (name + ".exr"), 600);
  EXPECT_EQ(r.exitCode, 0) << name << ": " << r.stderrText;
  return r;
}

GltfWriter furnaceSphere(const MaterialSpec& material) {
  GltfWriter w;
  w.addMesh(icosphere(glm::dvec3(0.0), 0.5, 3, false), w.addMaterial(material));
  CameraSpec camera;
  camera.position = {0.0, 0.3, 2.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.yfov = 0.7;
  w.setCamera(camera);
  return w;
}

class Glass : public ::testing::TestWithParam<const char*> {};

TEST_P(Glass, SmoothSphereVanishesInAFurnace) {
  const fs::path dir = scratchDir("glass-furnace");
  const RenderWithStats r = render(dir, std::string("smooth-") + GetParam(), furnaceSphere(glass(0.0f, 1.5f, true)),
                                   "--env-color 1,1,1 --width 24 --height 24 --spp 64 --max-depth 40 --variance "
                                   "--method pt-power --backend " + std::string(GetParam()));
  ASSERT_EQ(r.exitCode, 0);
  EXPECT_NE(r.stats["features"].get<std::string>().find("transmission=1"), std::string::npos) << r.stats.dump();
  // The fully general pipelines (every feature compiled in) render the same image for the same seed.
  const RenderWithStats general =
      render(dir, std::string("smooth-general-") + GetParam(), furnaceSphere(glass(0.0f, 1.5f, true)),
             "--env-color 1,1,1 --width 24 --height 24 --spp 64 --max-depth 40 --variance --method pt-power "
             "--general-pipelines --backend " + std::string(GetParam()));
  ASSERT_EQ(general.exitCode, 0);
  EXPECT_EQ(differingChannels(general.mean, r.mean, 1e-4f), 0u);
  // Every pixel is 1; the tolerance allows for the paths still inside after 40 vertices and for
  // alpha 0.002 not being a perfect mirror at grazing angles.
  Expectation one(r.mean.width, r.mean.height);
  for (float& v : one.value.rgb) v = 1.0f;
  const ZTestResult z = zTest(r.mean, r.variance, 64, one, 5e-3);
  EXPECT_TRUE(z.passed()) << z.summary();
  const ZTestResult dark = zTest(r.mean, r.variance, 64, one, 5e-3, 0.97);
  EXPECT_FALSE(dark.passed()) << "the check cannot see a 3 % loss: " << dark.summary();
}

TEST_P(Glass, RoughSphereLosesOnlyWhatSingleScatteringLoses) {
  const fs::path dir = scratchDir("glass-furnace");
  const RenderWithStats r = render(dir, std::string("rough-") + GetParam(), furnaceSphere(glass(0.5f, 1.5f, true)),
                                   "--env-color 1,1,1 --width 24 --height 24 --spp 64 --max-depth 40 --variance "
                                   "--method pt-power --backend " + std::string(GetParam()));
  ASSERT_EQ(r.exitCode, 0);
  double sum = 0.0, maxZ = 0.0;
  for (size_t i = 0; i < r.mean.rgb.size(); ++i) {
    sum += r.mean.rgb[i];
    const double se = std::max<double>(r.variance.rgb[i], 1e-6);
    maxZ = std::max(maxZ, (r.mean.rgb[i] - 1.0) / se);
  }
  const double mean = sum / r.mean.rgb.size();
  EXPECT_LT(maxZ, 5.0) << "a pixel above 1: energy created";
  EXPECT_LT(mean, 0.995) << "rough glass loses some energy";
  EXPECT_GT(mean, 0.85) << "rough glass loses far more than single scattering does";
}

// A floor lit by an area light, with and without a clear thin pane of IOR 1 in between.
TEST_P(Glass, ClearThinPaneLetsTheLightThrough) {
  const fs::path dir = scratchDir("glass-pane");
  const MaterialSpec floorMaterial{glm::vec3(0.8f), 0.0f, 1.0f, glm::vec3(0.0f), false};
  const MaterialSpec light{glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(4.0f), false};
  CameraSpec camera;
  camera.position = {0.0, 2.4, 1.4};
  camera.target = {0.0, 0.0, 0.0};
  camera.yfov = 1.0;
  GltfWriter withPane, without;
  for (GltfWriter* w : {&withPane, &without}) {
    w->addMesh(rectangle({-1.5, 0.0, 1.5}, {3.0, 0.0, 0.0}, {0.0, 0.0, -3.0}, {0.0, 1.0, 0.0}), w->addMaterial(floorMaterial));
    w->addMesh(rectangle({-0.75, 1.6, -0.75}, {1.5, 0.0, 0.0}, {0.0, 0.0, 1.5}, {0.0, -1.0, 0.0}), w->addMaterial(light));
    w->setCamera(camera);
  }
  withPane.addMesh(rectangle({-0.6, 0.8, 0.6}, {1.2, 0.0, 0.0}, {0.0, 0.0, -1.2}, {0.0, 1.0, 0.0}),
                   withPane.addMaterial(glass(0.0f, 1.0f, false)));
  // Depth 5: the pane is a vertex of its own, twice for a camera ray that sees the floor through it.
  const std::string args = "--env none --width 40 --height 30 --max-depth 5 --variance --method pt-power --backend " +
                           std::string(GetParam());
  const RenderWithStats a = render(dir, std::string("pane-") + GetParam(), withPane, args + " --spp 512 --seed 1");
  const RenderWithStats b = render(dir, std::string("open-") + GetParam(), without, args + " --spp 128 --seed 2");
  ASSERT_EQ(a.exitCode, 0);
  ASSERT_EQ(b.exitCode, 0);
  const ComparisonResult c = compareImages(a.mean, a.variance, b.mean, b.variance);
  EXPECT_TRUE(c.agree) << c.summary();
  std::printf("pane against none: %s\n", c.summary().c_str());
  EXPECT_EQ(b.stats["features"].get<std::string>().find("transmission=1"), std::string::npos)
      << "a scene without glass compiles no glass: " << b.stats.dump();
}

// A room (floor, back wall, two lights) with a rough glass sphere and a thin glass pane: every
// method agrees with pt-uniform, controlled mixture sampling with its statistics and control
// variate over transmitted samples included.
TEST_P(Glass, EveryMethodAgreesWithUniformSelection) {
  const fs::path dir = scratchDir("glass-methods");
  GltfWriter w;
  const int grey = w.addMaterial(MaterialSpec{glm::vec3(0.7f), 0.0f, 0.8f, glm::vec3(0.0f), false});
  w.addMesh(rectangle({-2.0, 0.0, 2.0}, {4.0, 0.0, 0.0}, {0.0, 0.0, -4.0}, {0.0, 1.0, 0.0}), grey);
  w.addMesh(rectangle({-2.0, 0.0, -1.5}, {4.0, 0.0, 0.0}, {0.0, 3.0, 0.0}, {0.0, 0.0, 1.0}), grey);
  MaterialSpec tinted = glass(0.3f, 1.5f, true);
  tinted.baseColor = glm::vec3(0.9f, 0.7f, 0.5f);
  w.addMesh(icosphere(glm::dvec3(-0.4, 0.5, 0.0), 0.5, 2, false), w.addMaterial(tinted));
  w.addMesh(rectangle({0.3, 0.0, 0.5}, {0.0, 1.0, 0.0}, {0.8, 0.0, -0.8}, {1.0, 0.0, 1.0}), w.addMaterial(glass(0.2f, 1.5f, false)));
  w.addMesh(rectangle({-1.5, 2.0, -1.0}, {0.6, 0.0, 0.0}, {0.0, 0.0, 0.6}, {0.0, -1.0, 0.0}),
            w.addMaterial(MaterialSpec{glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(12.0f, 10.0f, 8.0f), false}));
  w.addMesh(rectangle({0.8, 1.6, 0.2}, {0.4, 0.0, 0.0}, {0.0, 0.0, 0.4}, {0.0, -1.0, 0.0}),
            w.addMaterial(MaterialSpec{glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(8.0f, 10.0f, 12.0f), false}));
  CameraSpec camera;
  camera.position = {0.0, 1.4, 3.0};
  camera.target = {0.0, 0.5, 0.0};
  camera.yfov = 0.8;
  w.setCamera(camera);
  const std::string common = "--env none --width 32 --height 24 --max-depth 5 --variance --backend " + std::string(GetParam());
  const RenderWithStats baseline = render(dir, std::string("uniform-") + GetParam(), w, common + " --spp 1024 --method pt-uniform --seed 1");
  ASSERT_EQ(baseline.exitCode, 0);
  int seed = 2;
  for (const char* method : {"pt-bvh", "cms"}) {
    const RenderWithStats r =
        render(dir, std::string(method) + "-" + GetParam(), w, common + " --spp 256 --method " + method + " --seed " + std::to_string(seed++));
    ASSERT_EQ(r.exitCode, 0);
    const ComparisonResult c = compareImages(r.mean, r.variance, baseline.mean, baseline.variance);
    EXPECT_TRUE(c.agree) << method << ": " << c.summary();
    std::printf("%s: %s\n", method, c.summary().c_str());
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, Glass, ::testing::Values("vulkan", "cpu"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
