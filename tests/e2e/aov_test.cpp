// --aov albedo,normal,depth: the first hit's albedo, shading normal and distance, averaged over
// each pixel's samples, as extra EXR channels (rendered by the real binary on both backends and
// compared per pixel with the scene's geometry: a floor and a tilted quad of known colours, seen
// by a pinhole camera). The image itself is the image of a render without --aov, for the same seed.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "output/exr_io.h"
#include "util/error.h"
#include "support/analytic/gltf_writer.h"
#include "support/analytic/meshes.h"
#include "support/analytic/pinhole.h"
#include "support/analytic/pixel_expectation.h"
#include "support/run_binary.h"

namespace {

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;
using namespace mixtrace::testing::analytic;

const glm::vec3 kFloorColour(0.8f, 0.6f, 0.4f);
const glm::vec3 kQuadColour(0.2f, 0.5f, 0.9f);

class Aov : public ::testing::TestWithParam<const char*> {};

TEST_P(Aov, FirstHitAlbedoNormalAndDepthMatchTheGeometry) {
  const fs::path dir = scratchDir("aov");
  const std::vector<Tri> floor = rectangle({-1.5, 0.0, 1.5}, {3.0, 0.0, 0.0}, {0.0, 0.0, -3.0}, {0.0, 1.0, 0.0});
  const glm::dvec3 tilted = glm::normalize(glm::dvec3(0.3, 0.2, 1.0));
  const std::vector<Tri> quad = rectangle({-0.4, 0.3, -0.5}, {0.8, 0.0, -0.24}, {0.0, 0.6, -0.12}, tilted);
  GltfWriter w;
  w.addMesh(floor, w.addMaterial(MaterialSpec{kFloorColour, 0.0f, 1.0f, glm::vec3(0.0f), false}));
  w.addMesh(quad, w.addMaterial(MaterialSpec{kQuadColour, 1.0f, 0.4f, glm::vec3(0.0f), false}));
  CameraSpec camera;
  camera.position = {0.2, 1.2, 2.2};
  camera.target = {0.0, 0.2, -0.4};
  camera.yfov = 0.8;
  w.setCamera(camera);
  const fs::path scene = dir / "scene.gltf";
  writeFile(scene, w.json());

  const std::string common = "render " + scene.string() + " --width 40 --height 30 --spp 64 --seed 3 --no-png -q --backend " +
                             GetParam() + " --env-color 1,1,1";
  const fs::path withAov = dir / "aov.exr", without = dir / "plain.exr";
  const RunResult r = runMixtrace(common + " --aov albedo,normal,depth --out " + withAov.string());
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  ASSERT_EQ(runMixtrace(common + " --out " + without.string()).exitCode, 0);

  const Image albedo = readExrChannels(withAov.string(), {"albedo.R", "albedo.G", "albedo.B"});
  const Image normal = readExrChannels(withAov.string(), {"normal.X", "normal.Y", "normal.Z"});
  const Image depth = readExrChannels(withAov.string(), {"depth.Z"});
  EXPECT_THROW(readExrChannels(without.string(), {"albedo.R"}), Error);   // no AOV without --aov

  LabelledScene labelled;
  labelled.add(floor, 0);
  labelled.add(quad, 1);
  const Tri& quadTri = quad[0];
  glm::dvec3 quadNormal = quadTri.normal();
  const Expectation expectedAlbedo = pixelExpectation(camera, 40, 30, labelled,
      [&](int s, const Hit&, const Ray&) { return glm::dvec3(s == 0 ? kFloorColour : kQuadColour); });
  const Expectation expectedNormal = pixelExpectation(camera, 40, 30, labelled, [&](int s, const Hit&, const Ray& ray) {
    glm::dvec3 n = s == 0 ? glm::dvec3(0.0, 1.0, 0.0) : quadNormal;
    return glm::dot(n, ray.direction) < 0.0 ? n : -n;   // on the camera's side
  });
  // The depth's mean over the pixel and its mean square: a pixel's 64 samples of a depth that varies
  // across it (steeply on the far floor) leave a sampling error of sqrt(variance / 64).
  const Expectation expectedDepth = pixelExpectation(camera, 40, 30, labelled, [&](int, const Hit& h, const Ray&) {
    const double d = glm::length(h.point - camera.position);
    return glm::dvec3(d, d * d, 0.0);
  });
  size_t tested = 0, background = 0, quadPixels = 0;
  for (size_t p = 0; p < expectedAlbedo.tested.size(); ++p) {
    if (!expectedAlbedo.tested[p]) continue;
    ++tested;
    background += expectedAlbedo.value.rgb[3 * p] == 0.0f;
    quadPixels += expectedAlbedo.value.rgb[3 * p] == kQuadColour.x;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(albedo.rgb[3 * p + c], expectedAlbedo.value.rgb[3 * p + c], 1e-5f) << "pixel " << p;
      EXPECT_NEAR(normal.rgb[3 * p + c], expectedNormal.value.rgb[3 * p + c], 1e-4f) << "pixel " << p;
    }
    const double d = expectedDepth.value.rgb[3 * p], spread = std::max(0.0, expectedDepth.value.rgb[3 * p + 1] - d * d);
    EXPECT_NEAR(depth.rgb[3 * p], d, 5.0 * std::sqrt(spread / 64.0) + 2e-3 * d + 1e-6) << "pixel " << p;
  }
  // The framing is part of what is tested: background, floor and quad all in view.
  EXPECT_GT(background, 20u);
  EXPECT_GT(quadPixels, 40u);
  EXPECT_GT(tested, 900u);

  // The image is the one rendered without AOVs.
  const Image a = readExr(withAov.string()), b = readExr(without.string());
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  for (size_t i = 0; i < a.rgb.size(); ++i) ASSERT_NEAR(a.rgb[i], b.rgb[i], 1e-4f * std::max(1.0f, b.rgb[i])) << i;
}

INSTANTIATE_TEST_SUITE_P(Backends, Aov, ::testing::Values("vulkan", "cpu"),
                         [](const auto& info) { return std::string(info.param); });

TEST(AovOptions, UnknownNamesRepeatsAndNonExrOutputsAreRefused) {
  const fs::path dir = scratchDir("aov-options");
  const std::string box = std::string(MIXTRACE_SOURCE_DIR) + "/scenes/cornell_box.gltf --spp 1 --width 8 --height 8 ";
  const std::pair<std::string, std::string> cases[] = {
      {"--aov albedo,shadow --out " + (dir / "a.exr").string(), "'shadow' is not an AOV"},
      {"--aov depth,depth --out " + (dir / "a.exr").string(), "depth is named twice"},
      {"--aov normal --out " + (dir / "a.png").string(), "--aov needs an .exr"},
      {"--aov , --out " + (dir / "a.exr").string(), "is not an AOV"},
  };
  for (const auto& [args, named] : cases) {
    const RunResult r = runMixtrace("render " + box + args);
    EXPECT_NE(r.exitCode, 0) << args;
    EXPECT_NE(r.stderrText.find(named), std::string::npos) << args << ": " << r.stderrText;
    EXPECT_FALSE(fs::exists(dir / "a.exr") || fs::exists(dir / "a.png")) << args;
  }
}

}  // namespace
