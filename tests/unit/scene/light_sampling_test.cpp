// Light sampling as the shade stage runs it (shaders/shared/lights.h, compiled as C++): the pdf
// sampleLight() returns equals the pdf areaLightPdf() evaluates for the same point (the MIS
// weight of a BSDF sample that hits the light uses the latter); selection frequencies follow the
// selection pmf (chi-square); and light-sampling estimates of the irradiance from a quad light
// match the analytic polygon formula.
#include <cmath>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include "gltf/gltf_loader.h"
#include "scene/light_selection.h"
#include "scene/prepared_scene.h"
// The scene and selection table the shared headers read in this test (scene/shared_scene_access.h:
// its includer names them).
namespace light_sampling_test {
const mixtrace::PreparedScene* gScene = nullptr;
const std::vector<mixtrace::shared::LightSelectionGpu>* gSelection = nullptr;
bool gUniformEmitters = false;
}
#define SHARED_SCENE (*::light_sampling_test::gScene)
#define SHARED_LIGHT_SELECTION (*::light_sampling_test::gSelection)
#define SHARED_UNIFORM_EMITTERS (::light_sampling_test::gUniformEmitters)
#include "scene/shared_scene_access.h"
#include "support/chi2.h"
#include "support/shipped_scenes.h"

using namespace mixtrace;
using mixtrace::testing::shippedScenes;
namespace fs = std::filesystem;

class LightSamplingOnScene : public ::testing::TestWithParam<std::string> {};

TEST_P(LightSamplingOnScene, ReturnedPdfEqualsEvaluatedPdf) {
  for (LightSelection selection : {LightSelection::Uniform, LightSelection::Power}) {
    PreparedScene scene = prepareScene(loadGltf(GetParam()));
    const std::vector<shared::LightSelectionGpu> table = buildLightSelection(scene.lights, selection);
    light_sampling_test::gScene = &scene;
    light_sampling_test::gSelection = &table;
    light_sampling_test::gUniformEmitters = selection == LightSelection::Uniform;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const Bounds& b = scene.scene.bounds;
    uint32_t lightCount = uint32_t(scene.lights.lights.size());
    int areaSamples = 0;
    for (int i = 0; i < 20000; ++i) {
      glm::vec3 p = b.min + glm::vec3(u(rng), u(rng), u(rng)) * b.extent();
      shared::LightSample s;
      bool ok = shared::sampleLight(p, lightCount, u(rng), u(rng), glm::vec2(u(rng), u(rng)), s);
      if (!ok) continue;
      ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf > 0.0f);
      ASSERT_TRUE(std::isfinite(s.radiance.x) && std::isfinite(s.radiance.y) && std::isfinite(s.radiance.z));
      if (s.isDelta) {
        EXPECT_FLOAT_EQ(s.pdf, table[s.light].pmf);
        continue;
      }
      ++areaSamples;
      float evaluated = shared::areaLightPdf(s.triangle, p, s.position);
      ASSERT_NEAR(evaluated / s.pdf, 1.0f, 1e-3f) << "sample " << i;
      EXPECT_EQ(scene.lights.emitters[scene.shading[s.triangle].emitter].light, s.light);
    }
    if (scene.lights.hasArea()) EXPECT_GT(areaSamples, 1000);
  }
}

// Uniform selection is uniform over emissive triangles and punctual lights (the paper's baseline,
// pbrt-v4's uniform light sampler): the triangles a light sample lands on follow 1 / N (chi-square),
// and the selection part of every returned pdf is exactly 1 / N.
TEST_P(LightSamplingOnScene, UniformSelectionIsUniformOverTriangles) {
  PreparedScene scene = prepareScene(loadGltf(GetParam()));
  const std::vector<shared::LightSelectionGpu> table = buildLightSelection(scene.lights, LightSelection::Uniform);
  light_sampling_test::gScene = &scene;
  light_sampling_test::gSelection = &table;
  light_sampling_test::gUniformEmitters = true;
  const uint32_t lightCount = uint32_t(scene.lights.lights.size());
  const uint32_t emitters = uint32_t(scene.lights.emitters.size());
  // One bin per emitter, then one per light (the punctual ones).
  const uint32_t bins = emitters + lightCount;
  uint32_t sources = 0;
  for (const shared::LightGpu& l : scene.lights.lights) sources += l.kind == shared::kLightArea ? l.emitterCount : 1u;
  if (sources < 2) GTEST_SKIP() << "one light source: nothing to choose";
  const double pmf = 1.0 / double(sources);
  std::vector<double> counts(bins, 0.0), expected(bins, 0.0);
  for (uint32_t e = 0; e < emitters; ++e) expected[e] = pmf;
  for (uint32_t i = 0; i < lightCount; ++i)
    if (scene.lights.lights[i].kind != shared::kLightArea) expected[emitters + i] = pmf;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const glm::vec3 p = scene.scene.bounds.center();
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    shared::LightSample s;
    shared::sampleLight(p, lightCount, u(rng), u(rng), glm::vec2(u(rng), u(rng)), s);
    if (s.isDelta) {
      counts[emitters + s.light] += 1.0;
      ASSERT_NEAR(s.pdf, pmf, 1e-6 * pmf);
      continue;
    }
    const int32_t e = scene.shading[s.triangle].emitter;
    ASSERT_GE(e, 0);
    counts[uint32_t(e)] += 1.0;
    float point = shared::triangleSolidAnglePdf(scene.bvh.triangles[s.triangle], s.position - p);
    if (s.pdf > 0.0f && point > 0.0f) ASSERT_NEAR(s.pdf / point / pmf, 1.0, 1e-4) << "sample " << i;
  }
  std::vector<double> observed, wanted;   // the source bins only (an area light's own bin holds none)
  for (uint32_t b = 0; b < bins; ++b) {
    if (expected[b] > 0.0) {
      observed.push_back(counts[b]);
      wanted.push_back(expected[b] * n);
    } else {
      EXPECT_EQ(counts[b], 0.0);
    }
  }
  chi2::ChiSquareResult r = chi2::chiSquareTest(observed, wanted);
  EXPECT_GT(r.pValue, 1e-3) << "chi2 " << r.statistic << " dof " << r.dof;
}

TEST_P(LightSamplingOnScene, SelectionFollowsPmf) {
  PreparedScene scene = prepareScene(loadGltf(GetParam()));
  const std::vector<shared::LightSelectionGpu> lights = buildLightSelection(scene.lights, LightSelection::Power);
  light_sampling_test::gScene = &scene;
  light_sampling_test::gSelection = &lights;
  double pmfSum = 0.0;
  for (auto& l : lights) pmfSum += l.pmf;
  EXPECT_NEAR(pmfSum, 1.0, 1e-5);
  const int n = 200000;
  std::vector<double> counts(lights.size(), 0.0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int i = 0; i < n; ++i) counts[shared::selectLight(u(rng), uint32_t(lights.size()))] += 1.0;
  std::vector<double> expected(lights.size());
  for (size_t i = 0; i < lights.size(); ++i) expected[i] = n * double(lights[i].pmf);
  if (lights.size() < 2) return;
  chi2::ChiSquareResult r = chi2::chiSquareTest(counts, expected);
  EXPECT_GT(r.pValue, 1e-3) << "chi2 " << r.statistic << " dof " << r.dof;
}

INSTANTIATE_TEST_SUITE_P(Scenes, LightSamplingOnScene, ::testing::ValuesIn(shippedScenes()),
                         [](const auto& info) { return fs::path(info.param).stem().string(); });
// The paper's Modern Hall: lights of 2 and of 270 triangles, where uniform over triangles and
// uniform over lights differ most.
INSTANTIATE_TEST_SUITE_P(Paper, LightSamplingOnScene,
                         ::testing::Values(std::string(MIXTRACE_SOURCE_DIR) + "/scenes/paper/ModernHall/ModernHall.gltf"),
                         [](const auto& info) { return fs::path(info.param).stem().string(); });

// Irradiance at a point from a unit-radiance quad: E = 1/2 * sum_edges angle_i * (n . unit(r_i x r_i+1))
// (Lambert's polygon formula), against the light-sampling estimator mean(Le cos / pdf).
TEST(LightSampling, QuadIrradianceMatchesPolygonFormula) {
  Scene s;
  s.name = "quad";
  MaterialGpu m{};
  m.emission = glm::vec3(1.0f);
  m.baseColorTexture = m.metallicRoughnessTexture = m.emissiveTexture = -1;
  s.materials.push_back(m);
  // A 1 x 0.5 quad at height 1, facing down (counter-clockwise seen from below).
  glm::vec3 q[4] = {{-0.5f, 1.0f, -0.25f}, {0.5f, 1.0f, -0.25f}, {0.5f, 1.0f, 0.25f}, {-0.5f, 1.0f, 0.25f}};
  for (int t = 0; t < 2; ++t) {
    Triangle tri{};
    tri.p[0] = q[0];
    tri.p[1] = q[1 + t];
    tri.p[2] = q[2 + t];
    glm::vec3 n = glm::normalize(glm::cross(tri.p[1] - tri.p[0], tri.p[2] - tri.p[0]));
    tri.n[0] = tri.n[1] = tri.n[2] = n;
    s.triangles.push_back(tri);
  }
  ASSERT_LT(glm::normalize(glm::cross(q[1] - q[0], q[2] - q[0])).y, 0.0f) << "quad must face down";
  for (auto& t : s.triangles) for (auto& p : t.p) s.bounds.grow(p);
  PreparedScene scene = prepareScene(s);
  const std::vector<shared::LightSelectionGpu> table = buildLightSelection(scene.lights, LightSelection::Power);
  light_sampling_test::gScene = &scene;
  light_sampling_test::gSelection = &table;

  for (glm::vec3 p : {glm::vec3(0.0f), glm::vec3(0.7f, 0.2f, 0.1f), glm::vec3(-1.5f, 0.5f, 0.3f)}) {
    glm::vec3 n(0.0f, 1.0f, 0.0f);
    double analytic = 0.0;
    for (int i = 0; i < 4; ++i) {
      glm::dvec3 a = glm::normalize(glm::dvec3(q[i] - p)), b = glm::normalize(glm::dvec3(q[(i + 1) % 4] - p));
      glm::dvec3 c = glm::cross(a, b);
      analytic += std::acos(glm::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(glm::dvec3(n), glm::normalize(c));
    }
    analytic = std::abs(0.5 * analytic);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const int samples = 200000;
    double sum = 0.0, sumSq = 0.0;
    for (int i = 0; i < samples; ++i) {
      shared::LightSample ls;
      double v = 0.0;
      if (shared::sampleLight(p, 1, u(rng), u(rng), glm::vec2(u(rng), u(rng)), ls))
        v = ls.radiance.x * std::max(0.0f, glm::dot(n, ls.direction)) / ls.pdf;
      sum += v;
      sumSq += v * v;
    }
    double mean = sum / samples, stderrMean = std::sqrt((sumSq / samples - mean * mean) / samples);
    EXPECT_NEAR(mean, analytic, 4.0 * stderrMean + 1e-6) << "at (" << p.x << "," << p.y << "," << p.z << ")";
  }
}
