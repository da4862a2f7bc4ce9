// Light clusters (host/cms/light_clusters.h): on every shipped scene and on synthetic light sets
// (thousands of small quads in spatial groups, punctual lights) the clusters respect the budget,
// hold every light exactly once, never mix area and delta lights, and carry pmfs that sum to 1;
// well-separated groups and opposite-facing lights end up apart; 10k lights cluster fast.
#include <chrono>
#include <cmath>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "cms/light_clusters.h"
#include "gltf/gltf_loader.h"
#include "support/shipped_scenes.h"
#include "util/error.h"

using namespace mixtrace;
using mixtrace::testing::sceneStem;
using mixtrace::testing::shippedScenes;

namespace {

bool isArea(const PreparedScene& s, uint32_t light) { return s.lights.lights[light].kind == shared::kLightArea; }

// Every structural promise of LightClusters, for a result built with maxClusters.
void expectValidClusters(const PreparedScene& scene, const LightClusters& lc, uint32_t maxClusters) {
  const size_t n = scene.lights.lights.size();
  ASSERT_EQ(lc.lightCluster.size(), n);
  ASSERT_EQ(lc.lightPmfInCluster.size(), n);
  ASSERT_EQ(lc.clusterLights.size(), n);
  ASSERT_EQ(lc.defaultSelection.size(), lc.clusters.size());
  // The budget is used fully: min(lights, maxClusters) clusters.
  ASSERT_EQ(lc.clusters.size(), std::min<size_t>(n, maxClusters));
  if (n <= maxClusters) {
    for (uint32_t i = 0; i < n; ++i) EXPECT_EQ(lc.lightCluster[i], i) << "one cluster per light, in order";
  }

  std::vector<int> seen(n, 0);
  uint32_t next = 0;
  double selectionSum = 0.0;
  for (uint32_t c = 0; c < lc.clusters.size(); ++c) {
    const shared::ClusterGpu& cl = lc.clusters[c];
    ASSERT_EQ(cl.firstLight, next) << "clusters are contiguous in clusterLights";
    ASSERT_GE(cl.lightCount, 1u);
    next += cl.lightCount;
    ASSERT_LE(next, n);
    bool area = isArea(scene, lc.clusterLights[cl.firstLight]);
    EXPECT_EQ(cl.kind, area ? shared::kClusterArea : shared::kClusterDelta);
    double pmfSum = 0.0, power = 0.0, triangles = 0.0;
    for (uint32_t j = cl.firstLight; j < cl.firstLight + cl.lightCount; ++j) {
      uint32_t light = lc.clusterLights[j];
      ASSERT_LT(light, n);
      ++seen[light];
      EXPECT_EQ(lc.lightCluster[light], c);
      EXPECT_EQ(isArea(scene, light), area) << "cluster " << c << " mixes area and delta lights";
      EXPECT_GE(lc.lightPmfInCluster[light], 0.0f);
      pmfSum += lc.lightPmfInCluster[light];
      power += scene.lights.power[light];
      triangles += uniformSelectionWeight(scene.lights.lights[light]);
    }
    EXPECT_NEAR(pmfSum, 1.0, 1e-5) << "cluster " << c;
    EXPECT_NEAR(cl.power, power, 1e-5 * power + 1e-30);
    // Inside the cluster: by triangle count (uniform selection), else power-proportional.
    for (uint32_t j = cl.firstLight; j < cl.firstLight + cl.lightCount; ++j) {
      const uint32_t light = lc.clusterLights[j];
      if (lc.uniformEmitters)
        EXPECT_NEAR(lc.lightPmfInCluster[light], uniformSelectionWeight(scene.lights.lights[light]) / triangles, 1e-5);
      else if (power > 0.0)
        EXPECT_NEAR(lc.lightPmfInCluster[light], scene.lights.power[light] / power, 1e-5);
    }
    EXPECT_GE(lc.defaultSelection[c], 0.0f);
    selectionSum += lc.defaultSelection[c];
  }
  EXPECT_EQ(next, n);
  for (size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << "light " << i;
  if (!lc.clusters.empty()) EXPECT_NEAR(selectionSum, 1.0, 1e-5);
}

// Synthetic scenes: emissive quads (one light each) and punctual lights.
class SyntheticScene {
 public:
  SyntheticScene() {
    MaterialGpu grey{};
    grey.baseColor = glm::vec3(0.5f);
    grey.roughness = 1.0f;
    grey.baseColorTexture = grey.metallicRoughnessTexture = grey.emissiveTexture = -1;
    scene_.materials.push_back(grey);
    scene_.name = "synthetic";
  }

  uint32_t emissiveMaterial(float strength, bool doubleSided = false) {
    MaterialGpu m = scene_.materials[0];
    m.emission = glm::vec3(strength);
    m.flags = doubleSided ? shared::kMaterialDoubleSided : 0u;
    scene_.materials.push_back(m);
    return uint32_t(scene_.materials.size() - 1);
  }

  // A square of side `size` around `center` whose front face (cross(e1, e2)) points along `normal`.
  void addQuad(glm::vec3 center, glm::vec3 normal, float size, uint32_t material) {
    glm::vec3 n = glm::normalize(normal);
    glm::vec3 t = glm::normalize(glm::cross(n, std::abs(n.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
    glm::vec3 b = glm::cross(n, t);
    float h = 0.5f * size;
    glm::vec3 p[4] = {center - h * t - h * b, center + h * t - h * b, center + h * t + h * b, center - h * t + h * b};
    addTriangle(p[0], p[1], p[2], n, material, primitive_);
    addTriangle(p[0], p[2], p[3], n, material, primitive_);
    ++primitive_;
  }

  void addPunctual(uint32_t kind, glm::vec3 position, glm::vec3 direction, float intensity) {
    PunctualLight l;
    l.kind = kind;
    l.position = position;
    l.direction = glm::normalize(direction);
    l.intensity = glm::vec3(intensity);
    scene_.punctualLights.push_back(l);
  }

  PreparedScene prepare() {
    Scene s = scene_;
    // prepareScene needs a triangle; a small grey one keeps purely punctual scenes valid.
    addTriangleTo(s, glm::vec3(0, -0.01f, 0), glm::vec3(0.01f, -0.01f, 0), glm::vec3(0, -0.01f, 0.01f),
                  glm::vec3(0, 1, 0), 0, primitive_);
    return prepareScene(std::move(s));
  }

 private:
  static void addTriangleTo(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 n, uint32_t material,
                            uint32_t primitive) {
    Triangle t{};
    t.p[0] = a; t.p[1] = b; t.p[2] = c;
    t.n[0] = t.n[1] = t.n[2] = n;
    t.material = material;
    t.primitive = primitive;
    s.triangles.push_back(t);
    for (const glm::vec3& p : t.p) s.bounds.grow(p);
  }
  void addTriangle(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 n, uint32_t material, uint32_t primitive) {
    addTriangleTo(scene_, a, b, c, n, material, primitive);
  }
  Scene scene_;
  uint32_t primitive_ = 0;
};

glm::vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> g;
  glm::vec3 v(g(rng), g(rng), g(rng));
  return glm::normalize(v);
}

// `groups` spatial groups of small quads (random orientation within a hemisphere around -y,
// random brightness) plus point, spot and directional lights.
PreparedScene manyLights(uint32_t quads, uint32_t groups, uint32_t punctual, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  SyntheticScene s;
  std::vector<uint32_t> materials;
  for (int i = 0; i < 8; ++i) materials.push_back(s.emissiveMaterial(0.5f + 10.0f * u(rng), i == 7));
  std::vector<glm::vec3> centers;
  for (uint32_t g = 0; g < groups; ++g) centers.push_back(glm::vec3(40.0f * u(rng), 10.0f * u(rng), 40.0f * u(rng)));
  for (uint32_t i = 0; i < quads; ++i) {
    glm::vec3 c = centers[i % groups] + 3.0f * glm::vec3(u(rng), u(rng), u(rng));
    glm::vec3 n = randomUnit(rng);
    if (n.y > 0.0f) n.y = -n.y;
    s.addQuad(c, n, 0.05f + 0.2f * u(rng), materials[size_t(rng() % materials.size())]);
  }
  for (uint32_t i = 0; i < punctual; ++i) {
    uint32_t kind = i % 7 == 6 ? shared::kLightDirectional : i % 2 ? shared::kLightSpot : shared::kLightPoint;
    s.addPunctual(kind, glm::vec3(40.0f * u(rng), 10.0f * u(rng), 40.0f * u(rng)), randomUnit(rng), 1.0f + 50.0f * u(rng));
  }
  return s.prepare();
}

}  // namespace

class LightClustersOnScene : public ::testing::TestWithParam<std::string> {};

TEST_P(LightClustersOnScene, ValidForEveryBudget) {
  PreparedScene scene = prepareScene(loadGltf(GetParam()));
  ASSERT_FALSE(scene.lights.lights.empty());
  bool mixed = scene.lights.hasArea() && scene.lights.hasPunctual();
  for (uint32_t maxClusters : {1u, 2u, 3u, 5u, 8u, 32u}) {
    SCOPED_TRACE("maxClusters " + std::to_string(maxClusters));
    if (maxClusters == 1 && mixed && scene.lights.lights.size() > 1) {
      EXPECT_THROW(buildLightClusters(scene, maxClusters, LightSelection::Uniform), Error);
      continue;
    }
    for (LightSelection sel : {LightSelection::Uniform, LightSelection::Power})
      expectValidClusters(scene, buildLightClusters(scene, maxClusters, sel), maxClusters);
  }
}

INSTANTIATE_TEST_SUITE_P(Shipped, LightClustersOnScene, ::testing::ValuesIn(shippedScenes()),
                         [](const auto& info) { return sceneStem(info.param); });

TEST(LightClusters, ValidOnSyntheticLightSets) {
  for (uint32_t quads : {300u, 2000u}) {
    PreparedScene scene = manyLights(quads, 4, 60, quads);
    ASSERT_EQ(scene.lights.lights.size(), quads + 60);
    for (uint32_t maxClusters : {2u, 3u, 4u, 7u, 16u, 32u}) {
      SCOPED_TRACE("quads " + std::to_string(quads) + ", maxClusters " + std::to_string(maxClusters));
      LightClusters lc = buildLightClusters(scene, maxClusters, ClusterSelection::UniformOverClusters);
      expectValidClusters(scene, lc, maxClusters);
      bool areaCluster = false, deltaCluster = false;
      for (auto& c : lc.clusters) (c.kind == shared::kClusterArea ? areaCluster : deltaCluster) = true;
      EXPECT_TRUE(areaCluster && deltaCluster) << "both kinds get a cluster";
      // Directional lights share a cluster with point/spot lights only when the budget forces it.
      if (maxClusters >= 3) {
        for (auto& c : lc.clusters) {
          std::set<bool> directional;
          for (uint32_t j = c.firstLight; j < c.firstLight + c.lightCount; ++j)
            directional.insert(scene.lights.lights[lc.clusterLights[j]].kind == shared::kLightDirectional);
          EXPECT_EQ(directional.size(), 1u);
        }
      }
    }
  }
}

TEST(LightClusters, SeparatedGroupsBecomeTheTwoClusters) {
  // Two groups of quads far apart along an oblique direction, interleaved in light order.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  SyntheticScene s;
  uint32_t dim = s.emissiveMaterial(1.0f), bright = s.emissiveMaterial(20.0f);
  glm::vec3 offset = 8.0f * glm::normalize(glm::vec3(1, 2, 3));
  for (int i = 0; i < 400; ++i) {
    glm::vec3 c = (i % 2 ? offset : -offset) + 2.0f * glm::vec3(u(rng), u(rng), u(rng));
    s.addQuad(c, glm::vec3(0, -1, 0) + 0.5f * randomUnit(rng), 0.1f, i % 3 ? dim : bright);
  }
  PreparedScene scene = s.prepare();
  LightClusters lc = buildLightClusters(scene, 2, LightSelection::Uniform);
  expectValidClusters(scene, lc, 2);
  for (uint32_t i = 0; i < 400; ++i)
    EXPECT_EQ(lc.lightCluster[i], lc.lightCluster[i % 2]) << "light " << i << " left its spatial group";
  EXPECT_NE(lc.lightCluster[0], lc.lightCluster[1]);
}

TEST(LightClusters, OppositeFacingLightsSeparate) {
  // Quads mixed in one thin square, half facing up and half facing down: position cannot separate
  // them, orientation can.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  SyntheticScene s;
  uint32_t m = s.emissiveMaterial(5.0f);
  for (int i = 0; i < 400; ++i)
    s.addQuad(glm::vec3(4.0f * u(rng), 0.01f * u(rng), 4.0f * u(rng)), glm::vec3(0, i % 2 ? 1 : -1, 0), 0.1f, m);
  PreparedScene scene = s.prepare();
  LightClusters lc = buildLightClusters(scene, 2, LightSelection::Uniform);
  expectValidClusters(scene, lc, 2);
  int agree = 0;
  for (uint32_t i = 0; i < 400; ++i) agree += lc.lightCluster[i] == lc.lightCluster[i % 2];
  std::printf("opposite-facing quads grouped by facing: %d of 400\n", agree);
  EXPECT_GE(agree, 380);
  EXPECT_NE(lc.lightCluster[0], lc.lightCluster[1]);
}

TEST(LightClusters, OneClusterPerLightWithinBudget) {
  PreparedScene scene = manyLights(6, 2, 4, 11);
  const std::vector<shared::LightSelectionGpu> power = buildLightSelection(scene.lights, LightSelection::Power);
  ASSERT_EQ(scene.lights.lights.size(), 10u);
  for (uint32_t maxClusters : {10u, 11u, 32u}) {
    LightClusters lc = buildLightClusters(scene, maxClusters, LightSelection::Power);
    expectValidClusters(scene, lc, maxClusters);
    ASSERT_EQ(lc.clusters.size(), 10u);
    for (uint32_t i = 0; i < 10; ++i) {
      EXPECT_EQ(lc.clusterLights[i], i);
      EXPECT_EQ(lc.clusters[i].lightCount, 1u);
      EXPECT_FLOAT_EQ(lc.lightPmfInCluster[i], 1.0f);
      // With one light per cluster, power selection over clusters is the light set's.
      EXPECT_NEAR(lc.defaultSelection[i], power[i].pmf, 1e-6f);
    }
  }
}

TEST(LightClusters, InvalidBudgetThrows) {
  PreparedScene scene = manyLights(50, 2, 10, 13);
  EXPECT_THROW(buildLightClusters(scene, 0, LightSelection::Uniform), Error);
  EXPECT_THROW(buildLightClusters(scene, shared::kMaxClusters + 1, LightSelection::Uniform), Error);
  // One cluster cannot hold area and delta lights apart.
  EXPECT_THROW(buildLightClusters(scene, 1, LightSelection::Uniform), Error);
  expectValidClusters(scene, buildLightClusters(scene, shared::kMaxClusters, LightSelection::Uniform), shared::kMaxClusters);

  // Area lights alone fit one cluster.
  PreparedScene areaOnly = manyLights(50, 2, 0, 13);
  LightClusters lc = buildLightClusters(areaOnly, 1, LightSelection::Uniform);
  expectValidClusters(areaOnly, lc, 1);
  EXPECT_EQ(lc.clusters[0].lightCount, 50u);
  // Point and directional lights alone share one delta cluster.
  PreparedScene deltaOnly = manyLights(0, 1, 14, 13);
  lc = buildLightClusters(deltaOnly, 1, LightSelection::Uniform);
  expectValidClusters(deltaOnly, lc, 1);
  EXPECT_EQ(lc.clusters[0].kind, shared::kClusterDelta);
}

TEST(LightClusters, DefaultSelections) {
  PreparedScene scene = manyLights(500, 3, 40, 17);
  const std::vector<shared::LightSelectionGpu> selection = buildLightSelection(scene.lights, LightSelection::Power);
  const uint32_t L = 9;
  LightClusters uniform = buildLightClusters(scene, L, ClusterSelection::UniformOverClusters);
  for (float c : uniform.defaultSelection) EXPECT_NEAR(c, 1.0f / L, 1e-6f);

  // Uniform: each cluster its triangles' share, each light its triangle count inside the cluster,
  // so with a uniform triangle inside the light every emissive triangle (and punctual light) has
  // probability 1 / N, as uniform selection gives it.
  LightClusters count = buildLightClusters(scene, L, LightSelection::Uniform);
  EXPECT_TRUE(count.uniformEmitters);
  EXPECT_FALSE(buildLightClusters(scene, L, LightSelection::Power).uniformEmitters);
  double sources = 0.0;
  for (const shared::LightGpu& l : scene.lights.lights) sources += uniformSelectionWeight(l);
  const std::vector<shared::LightSelectionGpu> uniformTable = buildLightSelection(scene.lights, LightSelection::Uniform);
  for (uint32_t i = 0; i < scene.lights.lights.size(); ++i) {
    const shared::LightGpu& l = scene.lights.lights[i];
    const double perTriangle = l.kind == shared::kLightArea ? 1.0 / double(l.emitterCount) : 1.0;
    const double p = double(count.defaultSelection[count.lightCluster[i]]) * count.lightPmfInCluster[i] * perTriangle;
    EXPECT_NEAR(p * sources, 1.0, 1e-4) << "light " << i;
    EXPECT_NEAR(uniformTable[i].pmf * perTriangle * sources, 1.0, 1e-4) << "light " << i;
  }

  // Power over clusters times power inside: the light set's power selection, light by light.
  LightClusters power = buildLightClusters(scene, L, LightSelection::Power);
  for (uint32_t i = 0; i < scene.lights.lights.size(); ++i) {
    float p = power.defaultSelection[power.lightCluster[i]] * power.lightPmfInCluster[i];
    EXPECT_NEAR(p, selection[i].pmf, 1e-5f * selection[i].pmf + 1e-9f);
  }
}

TEST(LightClusters, ZeroPowerFallsBackToUniform) {
  PreparedScene scene = manyLights(100, 2, 10, 19);
  std::fill(scene.lights.power.begin(), scene.lights.power.end(), 0.0);
  LightClusters lc = buildLightClusters(scene, 4, LightSelection::Power);
  expectValidClusters(scene, lc, 4);
  for (size_t c = 0; c < lc.clusters.size(); ++c) {
    const auto& cl = lc.clusters[c];
    for (uint32_t j = cl.firstLight; j < cl.firstLight + cl.lightCount; ++j)
      EXPECT_FLOAT_EQ(lc.lightPmfInCluster[lc.clusterLights[j]], 1.0f / float(cl.lightCount));
    EXPECT_NEAR(lc.defaultSelection[c], float(cl.lightCount) / 110.0f, 1e-6f);
  }
}

TEST(LightClusters, TenThousandLightsClusterFast) {
  PreparedScene scene = manyLights(10000, 8, 200, 23);
  ASSERT_EQ(scene.lights.lights.size(), 10200u);
  auto start = std::chrono::steady_clock::now();
  LightClusters lc = buildLightClusters(scene, shared::kMaxClusters, LightSelection::Power);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("clustered %zu lights into %zu clusters in %.3f s\n", scene.lights.lights.size(), lc.clusters.size(), seconds);
  EXPECT_LT(seconds, 5.0);
  expectValidClusters(scene, lc, shared::kMaxClusters);
}
