// The environment light (--env, --env-color) rendered by the real binary and judged against values
// computed independently of the renderer, per pixel (z-test on the renderer's own variance, with
// the power to reject a 5 % bias), on both backends:
//
//   EnvironmentFurnace   a convex sphere in a uniform environment: every bounce escapes, so a
//                        pixel on the sphere is Le times the BRDF's directional albedo and the
//                        background is Le (the white furnace's closed form for one bounce)
//   BrightTexel          a map black but for one texel lights a plane as a small distant area
//                        light of the same solid angle and radiance does (both against the
//                        quadrature of the texel, and against each other)
//   EnvironmentMethods   a map with a sky gradient and a sun beside an area light: every light
//                        selection (uniform, power, light BVH, learned, cv, cms: the environment
//                        is one more light and its own cluster) renders the same image
// and the command line's errors and the default for a scene without lights.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "compare/image_compare.h"
#include "shared/bsdf.h"
#include "support/analytic/direct_lighting.h"
#include "support/analytic/expect_matches.h"
#include "support/analytic/furnace.h"
#include "support/analytic/gltf_writer.h"
#include "support/analytic/meshes.h"
#include "support/analytic/pinhole.h"
#include "support/analytic/pixel_expectation.h"
#include "support/analytic/pixel_ztest.h"
#include "support/analytic/quadrature.h"
#include "support/analytic/render.h"
#include "support/pfm_writer.h"
#include "support/dark_cornell_box.h"
#include "support/image_difference.h"
#include "support/render_with_stats.h"
#include "support/run_binary.h"

namespace {

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;
using namespace mixtrace::testing::analytic;

const double kPi = 3.14159265358979323846;
const char* const kBackends[] = {"vulkan", "cpu"};

// The world direction of map coordinates (u, v) without rotation (shared/environment.h).
glm::dvec3 mapDirection(double u, double v) {
  const double phi = 2.0 * kPi * u, theta = kPi * v;
  return {std::sin(phi) * std::sin(theta), std::cos(theta), -std::cos(phi) * std::sin(theta)};
}

RenderedImage renderWith(const fs::path& scene, const RenderSettings& s, const std::string& extra, const fs::path& out) {
  RenderedImage result;
  const RunResult run = runMixtrace("render " + scene.string() + " " + extra + " --width " + std::to_string(s.width) +
                                    " --height " + std::to_string(s.height) + " --spp " + std::to_string(s.spp) +
                                    " --max-depth " + std::to_string(s.maxDepth) + " --method " + s.method +
                                    " --backend " + s.backend + " --seed " + std::to_string(s.seed) +
                                    " --variance -q --no-png --out " + out.string(), "", 600);
  if (run.exitCode != 0) {
    result.error = "exit code " + std::to_string(run.exitCode) + ": " + run.stderrText;
    return result;
  }
  result.mean = readExr(out.string(), nullptr, &result.variance);
  return result;
}

class EnvironmentRender : public ::testing::TestWithParam<const char*> {};

// ---------------------------------------------------------------------------------------------
TEST_P(EnvironmentRender, FurnaceSphereIsLeTimesItsAlbedo) {
  const fs::path dir = scratchDir("env-furnace");
  const MaterialSpec white{glm::vec3(0.9f, 0.7f, 0.5f), 0.0f, 0.6f, glm::vec3(0.0f), false};
  const std::vector<Tri> sphere = icosphere(glm::dvec3(0.0), 0.5, 3, false);
  GltfWriter writer;
  writer.addMesh(sphere, writer.addMaterial(white));
  CameraSpec camera;
  camera.position = {0.0, 0.3, 2.0};
  camera.target = {0.0, 0.0, 0.0};
  camera.yfov = 0.8;
  writer.setCamera(camera);
  const fs::path scene = dir / "sphere.gltf";
  writeFile(scene, writer.json());

  RenderSettings s;
  s.width = 32;
  s.height = 32;
  s.spp = 128;
  s.maxDepth = 3;  // one bounce is all there is: the rest escapes
  s.backend = GetParam();
  const glm::dvec3 le(0.5, 0.75, 1.0);
  const RenderedImage img = renderWith(scene, s, "--env-color 0.5,0.75,1", dir / "sphere.exr");
  ASSERT_TRUE(img.error.empty()) << img.error;

  // Directional albedo of the BRDF as implemented, tabulated over the cosine to the facet normal.
  const SphereFurnace quadrature(shared::makeBsdfParams(white.baseColor, white.metallic, white.roughness),
                                 glm::dvec3(0.0), 2);
  constexpr int kTable = 257;
  std::vector<glm::dvec3> albedo;
  for (int i = 0; i < kTable; ++i) albedo.push_back(quadrature.albedo(double(i) / (kTable - 1)));
  LabelledScene labelled;
  labelled.add(sphere, 0);
  const Expectation expected = pixelExpectation(camera, s.width, s.height, labelled,
      [&](int, const Hit& h, const Ray& r) {
        const double mu = std::abs(glm::dot(r.direction, sphere[size_t(h.triangle)].normal()));
        const double at = mu * (kTable - 1);
        const int i = std::min(int(at), kTable - 2);
        return le * (albedo[size_t(i)] + (at - i) * (albedo[size_t(i) + 1] - albedo[size_t(i)]));
      },
      le);
  // Tolerance: the albedo table's interpolation and float.
  expectMatches(img, s.spp, expected, 2e-3);
  // The fully general pipelines (every feature compiled in) render the same image for the same seed.
  const RenderedImage general = renderWith(scene, s, "--env-color 0.5,0.75,1 --general-pipelines", dir / "general.exr");
  ASSERT_TRUE(general.error.empty()) << general.error;
  EXPECT_EQ(differingChannels(general.mean, img.mean, 1e-4f), 0u);
}

// ---------------------------------------------------------------------------------------------
// One bright texel of a 64x32 map (column 40, row 9: 51-56 degrees from the zenith) over a
// diffuse plane, and the same texel as a distant emitting patch (4x4 quads with their corners on
// a sphere of radius 1e4, facing the plane): the same solid angle and radiance.
TEST_P(EnvironmentRender, BrightTexelLightsLikeADistantAreaLight) {
  const fs::path dir = scratchDir("env-texel");
  constexpr int kW = 64, kH = 32, kColumn = 40, kRow = 9;
  const glm::vec3 texelLe(300.0f, 240.0f, 180.0f);
  std::vector<glm::vec3> map(size_t(kW) * kH, glm::vec3(0.0f));
  map[size_t(kRow) * kW + kColumn] = texelLe;
  writePfm(dir / "texel.pfm", kW, kH, map);

  const MaterialSpec grey{glm::vec3(0.8f, 0.6f, 0.4f), 0.0f, 1.0f, glm::vec3(0.0f), false};
  const std::vector<Tri> plane = rectangle({-1.5, 0.0, 1.5}, {3.0, 0.0, 0.0}, {0.0, 0.0, -3.0}, {0.0, 1.0, 0.0});
  CameraSpec camera;
  camera.position = {0.0, 2.0, 1.2};
  camera.target = {0.0, 0.0, -0.2};
  camera.yfov = 0.9;

  const double u0 = double(kColumn) / kW, u1 = double(kColumn + 1) / kW;
  const double v0 = double(kRow) / kH, v1 = double(kRow + 1) / kH;
  constexpr int kSplit = 4;
  constexpr double kRadius = 1e4;
  std::vector<Tri> patch;
  for (int j = 0; j < kSplit; ++j)
    for (int i = 0; i < kSplit; ++i) {
      auto corner = [&](int a, int b) {
        return glm::vec3(kRadius * mapDirection(u0 + (u1 - u0) * (i + a) / kSplit, v0 + (v1 - v0) * (j + b) / kSplit));
      };
      Tri t1{{corner(0, 0), corner(1, 0), corner(1, 1)}}, t2{{corner(0, 0), corner(1, 1), corner(0, 1)}};
      for (Tri* t : {&t1, &t2})
        if (glm::dot(t->normal(), t->centroid()) > 0.0) std::swap(t->p[1], t->p[2]);  // face the plane
      patch.push_back(t1);
      patch.push_back(t2);
    }

  GltfWriter texelScene, patchScene;
  texelScene.addMesh(plane, texelScene.addMaterial(grey));
  patchScene.addMesh(plane, patchScene.addMaterial(grey));
  patchScene.addMesh(patch, patchScene.addMaterial(MaterialSpec{glm::vec3(0.0f), 0.0f, 1.0f, texelLe, false}));
  texelScene.setCamera(camera);
  patchScene.setCamera(camera);
  writeFile(dir / "texel.gltf", texelScene.json());
  writeFile(dir / "patch.gltf", patchScene.json());

  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.spp = 64;
  s.maxDepth = 2;
  s.backend = GetParam();
  const RenderedImage texel = renderWith(dir / "texel.gltf", s, "--env " + (dir / "texel.pfm").string(), dir / "texel.exr");
  ASSERT_TRUE(texel.error.empty()) << texel.error;
  s.seed = 2;
  const RenderedImage distant = renderWith(dir / "patch.gltf", s, "", dir / "patch.exr");
  ASSERT_TRUE(distant.error.empty()) << distant.error;

  // The texel's quadrature: Gauss nodes in (u, v), solid angle 2 pi^2 sin(theta) du dv.
  std::vector<DirectionNode> nodes;
  for (const Node1D& a : compositeGauss(u0, u1, 2, 6))
    for (const Node1D& b : compositeGauss(v0, v1, 2, 6))
      nodes.push_back({mapDirection(a.x, b.x),
                       glm::dvec3(texelLe) * (2.0 * kPi * kPi * std::sin(kPi * b.x) * a.w * b.w)});
  const shared::BsdfParams bsdf = shared::makeBsdfParams(grey.baseColor, grey.metallic, grey.roughness);
  LabelledScene labelled;
  labelled.add(plane, 0);
  const Expectation expected = pixelExpectation(camera, s.width, s.height, labelled,
      [&](int, const Hit&, const Ray& r) { return directRadianceFromDirections(bsdf, {0.0, 1.0, 0.0}, -r.direction, nodes); });
  std::printf("texel:\n");
  expectMatches(texel, s.spp, expected, 2e-3);
  std::printf("distant patch:\n");
  expectMatches(distant, s.spp, expected, 2e-3);
  const ComparisonResult same = compareImages(texel.mean, texel.variance, distant.mean, distant.variance);
  EXPECT_TRUE(same.agree) << same.summary();
}

// ---------------------------------------------------------------------------------------------
// A sky (a gradient, brighter towards the zenith, with a small sun) and an area light over a
// plane with a sphere on it: the environment is one light of several, its own cluster under
// learned, cv and cms. Every method agrees with uniform selection; a wrong environment pdf in any
// selection's MIS weight, or a missing control-variate term for it, would show.
TEST_P(EnvironmentRender, EveryMethodAgreesWithUniformSelection) {
  const fs::path dir = scratchDir("env-methods");
  constexpr int kW = 32, kH = 16;
  std::vector<glm::vec3> map;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const float up = 1.0f - float(y) / kH;
      map.push_back(glm::vec3(0.2f + 0.3f * up, 0.3f + 0.4f * up, 0.5f + 0.5f * up) * (0.6f + 0.4f * float(x % 5) / 4.0f));
    }
  // The sun: two texels, bright enough to dominate the sky, not so bright that a few hundred
  // samples of uniform selection leave its tail unresolved.
  map[size_t(4) * kW + 11] = map[size_t(4) * kW + 12] = glm::vec3(60.0f, 50.0f, 40.0f);
  writePfm(dir / "sky.pfm", kW, kH, map);

  GltfWriter writer;
  const int grey = writer.addMaterial(MaterialSpec{glm::vec3(0.7f), 0.0f, 0.8f, glm::vec3(0.0f), false});
  writer.addMesh(rectangle({-2.0, 0.0, 2.0}, {4.0, 0.0, 0.0}, {0.0, 0.0, -4.0}, {0.0, 1.0, 0.0}), grey);
  writer.addMesh(icosphere(glm::dvec3(0.3, 0.5, -0.3), 0.5, 2, false),
                 writer.addMaterial(MaterialSpec{glm::vec3(0.9f, 0.8f, 0.6f), 1.0f, 0.3f, glm::vec3(0.0f), false}));
  writer.addMesh(rectangle({-1.5, 1.5, -1.0}, {0.6, 0.0, 0.0}, {0.0, 0.0, 0.6}, {0.0, -1.0, 0.0}),
                 writer.addMaterial(MaterialSpec{glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(20.0f, 15.0f, 10.0f), false}));
  CameraSpec camera;
  camera.position = {0.0, 1.6, 3.2};
  camera.target = {0.0, 0.3, 0.0};
  camera.yfov = 0.8;
  writer.setCamera(camera);
  const fs::path scene = dir / "sky.gltf";
  writeFile(scene, writer.json());
  const std::string common = scene.string() + " --env " + (dir / "sky.pfm").string() +
                             " --env-rotate 40 --width 40 --height 30 --max-depth 4 --backend " + GetParam();

  // The baseline with more samples: every comparison shares its noise.
  const RenderWithStats baseline =
      renderWithStats(common + " --spp 1024 --method pt-uniform --seed 1", dir / "uniform.exr", 600);
  ASSERT_EQ(baseline.exitCode, 0) << baseline.stderrText;
  EXPECT_EQ(baseline.stats["lights"], 2) << baseline.stats.dump();
  int seed = 2;
  for (const char* method : {"pt-power", "pt-bvh", "learned", "cv", "cms"}) {
    const RenderWithStats r =
        renderWithStats(common + " --spp 256 --method " + method + " --seed " + std::to_string(seed++), dir / (std::string(method) + ".exr"), 600);
    ASSERT_EQ(r.exitCode, 0) << method << ": " << r.stderrText;
    const ComparisonResult c = compareImages(r.mean, r.variance, baseline.mean, baseline.variance);
    EXPECT_TRUE(c.agree) << method << ": " << c.summary();
    std::printf("%s: %s\n", method, c.summary().c_str());
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, EnvironmentRender, ::testing::ValuesIn(kBackends),
                         [](const auto& info) { return std::string(info.param); });

// ---------------------------------------------------------------------------------------------
TEST(EnvironmentOptions, AnyErrorIsOneLineAndNothingIsWritten) {
  const fs::path dir = scratchDir("env-options");
  const std::string box = std::string(MIXTRACE_SOURCE_DIR) + "/scenes/cornell_box.gltf";
  writeFile(dir / "bad.hdr", "#?RADIANCE\nnot really\n");
  writeFile(dir / "short.pfm", "PF\n4 2\n-1.0\n1234");
  writeFile(dir / "map.png", "x");
  const std::pair<std::string, std::string> cases[] = {
      {"--env " + (dir / "missing.exr").string(), "missing.exr"},
      {"--env " + (dir / "bad.hdr").string(), "bad.hdr"},
      {"--env " + (dir / "short.pfm").string(), "short.pfm"},
      {"--env " + (dir / "map.png").string(), ".exr, .hdr or .pfm"},
      {"--env-color 1,2", "--env-color"},
      {"--env-color 1,-2,3", "--env-color"},
      {"--env-color 1,1,1 --env none", "not both"},
      {"--env-scale -1 --env-color 1,1,1", "--env-scale"},
      {"--env-scale nan --env-color 1,1,1", "--env-scale"},
      {"--env-rotate abc --env-color 1,1,1", "--env-rotate"},
  };
  for (const auto& [args, named] : cases) {
    const fs::path out = dir / "out.exr";
    const RunResult r = runMixtrace("render " + box + " " + args + " --width 8 --height 8 --spp 1 --no-png --out " + out.string());
    EXPECT_NE(r.exitCode, 0) << args;
    EXPECT_NE(r.stderrText.find(named), std::string::npos) << args << ": " << r.stderrText;
    EXPECT_EQ(std::count(r.stderrText.begin(), r.stderrText.end(), '\n'), 1) << args << ": " << r.stderrText;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

// A scene without lights is lit by a uniform white environment of radiance 1, and says so; with
// --env none it stays black, and the render says why.
TEST(EnvironmentDefault, SceneWithoutLightsGetsAWhiteEnvironment) {
  const fs::path dir = scratchDir("env-default");
  const fs::path dark = writeDarkCornellBox(dir);
  const std::string common = "render " + dark.string() + " --width 16 --height 16 --spp 4 --no-png ";
  const RunResult lit = runMixtrace(common + "--out " + (dir / "lit.exr").string() + " --stats " + (dir / "lit.json").string());
  ASSERT_EQ(lit.exitCode, 0) << lit.stderrText;
  EXPECT_NE(lit.stderrText.find("has no lights: lit by a uniform white environment of radiance 1"), std::string::npos)
      << lit.stderrText;
  EXPECT_EQ(lit.stderrText.find("entirely black"), std::string::npos) << lit.stderrText;
  const Image litImage = readExr((dir / "lit.exr").string());
  double sum = 0.0;
  for (float v : litImage.rgb) sum += v;
  // The box is open towards the camera: the white sky reaches its walls.
  EXPECT_GT(sum / litImage.rgb.size(), 0.05);
  const nlohmann::json stats = nlohmann::json::parse(readText(dir / "lit.json"));
  EXPECT_EQ(stats["lights"], 1) << stats.dump();

  const RunResult black = runMixtrace(common + "--env none --out " + (dir / "black.exr").string());
  ASSERT_EQ(black.exitCode, 0) << black.stderrText;
  EXPECT_NE(black.stderrText.find("warning: the image is entirely black: the scene has no lights"), std::string::npos)
      << black.stderrText;
  for (float v : readExr((dir / "black.exr").string()).rgb) ASSERT_EQ(v, 0.0f);
}

}  // namespace
