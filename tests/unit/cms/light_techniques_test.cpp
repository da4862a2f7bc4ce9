// Control-variate techniques (host/cms/light_techniques.h): one per emissive triangle and per
// punctual light within the budget, contiguous emitter groups inside their light beyond it, whole
// clusters at worst; the shares Q_t sum to 1 in every cluster and are what cluster sampling
// actually picks (chi-square against sampled frequencies), so p_t = p_k / Q_t is normalised.
#include <cmath>
#include <map>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "cms/light_clusters.h"
#include "cms/light_techniques.h"
#include "scene/prepared_scene.h"
#include "support/chi2.h"
#include "util/error.h"

using namespace mixtrace;

namespace {

// Emissive strips of triangles (one primitive = one light each, of `triangles` triangles of
// varying size and brightness) and point lights; one grey floor triangle.
PreparedScene stripsAndPoints(const std::vector<uint32_t>& trianglesPerLight, uint32_t points, uint32_t seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.5f, 2.0f);
  Scene s;
  s.name = "techniques";
  MaterialGpu grey{};
  grey.baseColor = glm::vec3(0.5f);
  grey.roughness = 1.0f;
  grey.baseColorTexture = grey.metallicRoughnessTexture = grey.emissiveTexture = -1;
  s.materials.push_back(grey);
  auto addTriangle = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, uint32_t material, uint32_t primitive) {
    Triangle t{};
    t.p[0] = a; t.p[1] = b; t.p[2] = c;
    t.n[0] = t.n[1] = t.n[2] = glm::vec3(0, -1, 0);
    t.material = material;
    t.primitive = primitive;
    s.triangles.push_back(t);
    for (const glm::vec3& p : t.p) s.bounds.grow(p);
  };
  uint32_t primitive = 0;
  for (uint32_t light = 0; light < trianglesPerLight.size(); ++light, ++primitive) {
    MaterialGpu m = grey;
    m.emission = glm::vec3(u(rng));
    s.materials.push_back(m);
    for (uint32_t i = 0; i < trianglesPerLight[light]; ++i) {
      float x = 0.01f * float(i), z = 3.0f * float(light), h = 0.01f * u(rng);
      addTriangle(glm::vec3(x, 5, z), glm::vec3(x + h, 5, z), glm::vec3(x, 5, z + h), uint32_t(s.materials.size() - 1),
                  primitive);
    }
  }
  for (uint32_t i = 0; i < points; ++i) {
    PunctualLight l;
    l.kind = shared::kLightPoint;
    l.position = glm::vec3(float(i), 3, -2);
    l.intensity = glm::vec3(u(rng) * 10.0f);
    s.punctualLights.push_back(l);
  }
  addTriangle(glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1), 0, primitive);
  return prepareScene(std::move(s));
}

// Every structural promise: each source has a technique of the right cluster, techniques hold
// sources of one cluster only, shares sum to 1 per cluster, are the sum of their sources'
// probabilities, and lie in (0, 1].
void expectValidTechniques(const PreparedScene& scene, const LightClusters& lc, const LightTechniques& t,
                           uint32_t budget) {
  const LightSet& ls = scene.lights;
  ASSERT_EQ(t.emitterCount, ls.emitters.size());
  ASSERT_EQ(t.sources.size(), ls.emitters.size() + ls.lights.size());
  ASSERT_EQ(t.byTechnique.size(), t.techniqueCount);
  EXPECT_LE(t.techniqueCount, budget);
  std::vector<double> summed(t.techniqueCount, 0.0);
  std::vector<float> share(t.techniqueCount, -1.0f);
  std::vector<std::set<uint32_t>> lightsOf(t.techniqueCount);
  for (uint32_t light = 0; light < ls.lights.size(); ++light) {
    const shared::LightGpu& l = ls.lights[light];
    const bool area = l.kind == shared::kLightArea;
    const uint32_t first = area ? l.firstEmitter : t.emitterCount + light;
    const uint32_t count = area ? l.emitterCount : 1u;
    for (uint32_t s = first; s < first + count; ++s) {
      const shared::TechniqueRefGpu& ref = t.sources[s];
      ASSERT_LT(ref.technique, t.techniqueCount);
      EXPECT_EQ(t.byTechnique[ref.technique].cluster, lc.lightCluster[light]) << "source " << s;
      summed[ref.technique] += double(lc.lightPmfInCluster[light]) * (area ? ls.emitters[s].pmf : 1.0);
      if (share[ref.technique] < 0.0f) share[ref.technique] = ref.share;
      EXPECT_EQ(share[ref.technique], ref.share) << "one share per technique";
      EXPECT_EQ(t.byTechnique[ref.technique].share, ref.share) << "the solve's share is the sources' share";
      lightsOf[ref.technique].insert(light);
    }
  }
  std::vector<double> perCluster(lc.clusters.size(), 0.0);
  for (uint32_t i = 0; i < t.techniqueCount; ++i) {
    EXPECT_GT(share[i], 0.0f);
    EXPECT_LE(share[i], 1.0f);
    EXPECT_NEAR(share[i], summed[i], 1e-6 * summed[i] + 1e-12);
    perCluster[t.byTechnique[i].cluster] += share[i];
    if (t.grouping != TechniqueGrouping::PerCluster) EXPECT_EQ(lightsOf[i].size(), 1u) << "technique " << i;
  }
  for (double q : perCluster) EXPECT_NEAR(q, 1.0, 1e-5);
}

}  // namespace

TEST(LightTechniques, OnePerTriangleAndPunctualLightWithinBudget) {
  PreparedScene scene = stripsAndPoints({7, 1, 30}, 3);
  LightClusters lc = buildLightClusters(scene, 16, LightSelection::Power);
  LightTechniques t = buildLightTechniques(scene.lights, lc, kDefaultMaxTechniques);
  expectValidTechniques(scene, lc, t, kDefaultMaxTechniques);
  EXPECT_EQ(t.techniqueCount, 7u + 1u + 30u + 3u);
  EXPECT_FALSE(t.merged());
  // A triangle's technique density p_k / Q_t is its own point density: Q_t is exactly the pmf of
  // picking it inside its cluster.
  for (uint32_t e = 0; e < scene.lights.emitters.size(); ++e) {
    uint32_t light = scene.lights.emitters[e].light;
    EXPECT_FLOAT_EQ(t.sources[e].share, lc.lightPmfInCluster[light] * scene.lights.emitters[e].pmf);
  }
  // A punctual light is its own technique (counting measure, p_t = 1 on its atom).
  for (uint32_t light = 0; light < scene.lights.lights.size(); ++light)
    if (scene.lights.lights[light].kind != shared::kLightArea)
      EXPECT_FLOAT_EQ(t.sources[t.emitterCount + light].share, lc.lightPmfInCluster[light]);
}

TEST(LightTechniques, SharesAreWhatClusterSamplingPicks) {
  // Two clusters of several lights each (max 2 clusters for 6 lights): the technique sampled by
  // "light from the cluster's pmf, then emitter from the light's pmf" has frequency Q_t.
  PreparedScene scene = stripsAndPoints({5, 9, 3, 12, 4, 6}, 0);
  LightClusters lc = buildLightClusters(scene, 2, LightSelection::Power);
  for (uint32_t budget : {kDefaultMaxTechniques, 12u}) {
    LightTechniques t = buildLightTechniques(scene.lights, lc, budget);
    expectValidTechniques(scene, lc, t, budget);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (uint32_t k = 0; k < lc.clusters.size(); ++k) {
      const shared::ClusterGpu& c = lc.clusters[k];
      std::map<uint32_t, double> observed, expected;
      const int n = 200000;
      for (int i = 0; i < n; ++i) {
        double x = u(rng), cdf = 0.0;
        uint32_t light = lc.clusterLights[c.firstLight + c.lightCount - 1];
        for (uint32_t j = c.firstLight; j < c.firstLight + c.lightCount; ++j) {
          cdf += lc.lightPmfInCluster[lc.clusterLights[j]];
          if (x < cdf) { light = lc.clusterLights[j]; break; }
        }
        const shared::LightGpu& l = scene.lights.lights[light];
        double y = u(rng), ecdf = 0.0;
        uint32_t e = l.firstEmitter + l.emitterCount - 1;
        for (uint32_t j = l.firstEmitter; j < l.firstEmitter + l.emitterCount; ++j) {
          ecdf += scene.lights.emitters[j].pmf;
          if (y < ecdf) { e = j; break; }
        }
        observed[t.sources[e].technique] += 1.0;
      }
      for (uint32_t s = 0; s < t.emitterCount; ++s)
        if (t.byTechnique[t.sources[s].technique].cluster == k) expected[t.sources[s].technique] = n * t.sources[s].share;
      std::vector<double> o, x;
      for (auto& [tech, count] : expected) {
        x.push_back(count);
        o.push_back(observed[tech]);
      }
      for (auto& [tech, count] : observed) EXPECT_TRUE(expected.count(tech)) << "sampled a foreign technique";
      chi2::ChiSquareResult r = chi2::chiSquareTest(o, x);
      EXPECT_GT(r.pValue, 1e-4) << "budget " << budget << " cluster " << k << " chi2 " << r.statistic << " dof " << r.dof;
    }
  }
}

TEST(LightTechniques, MergesContiguousEmitterGroupsUnderBudget) {
  PreparedScene scene = stripsAndPoints({40, 10, 25}, 2);   // 75 triangles + 2 points
  LightClusters lc = buildLightClusters(scene, 16, LightSelection::Power);
  for (uint32_t budget : {76u, 40u, 20u, 6u, 5u}) {
    LightTechniques t = buildLightTechniques(scene.lights, lc, budget);
    expectValidTechniques(scene, lc, t, budget);
    EXPECT_TRUE(t.merged());
    EXPECT_EQ(t.grouping, TechniqueGrouping::EmitterGroups) << budget;
    // Contiguous groups of groupSize inside each light, the smallest size that fits.
    for (const shared::LightGpu& l : scene.lights.lights) {
      if (l.kind != shared::kLightArea) continue;
      for (uint32_t j = 0; j < l.emitterCount; ++j)
        EXPECT_EQ(t.sources[l.firstEmitter + j].technique, t.sources[l.firstEmitter + (j / t.groupSize) * t.groupSize].technique);
      if (l.emitterCount > t.groupSize)
        EXPECT_NE(t.sources[l.firstEmitter].technique, t.sources[l.firstEmitter + t.groupSize].technique);
    }
    if (t.groupSize > 2) {
      uint32_t smaller = 0;
      for (const shared::LightGpu& l : scene.lights.lights)
        smaller += l.kind == shared::kLightArea ? (l.emitterCount + t.groupSize - 2) / (t.groupSize - 1) : 1;
      EXPECT_GT(smaller, budget) << "a smaller group size would have fitted";
    }
  }
  // Below one technique per light: whole clusters.
  LightClusters two = buildLightClusters(scene, 2, LightSelection::Power);
  LightTechniques t = buildLightTechniques(scene.lights, two, 4);
  expectValidTechniques(scene, two, t, 4);
  EXPECT_EQ(t.grouping, TechniqueGrouping::PerCluster);
  EXPECT_EQ(t.techniqueCount, 2u);
  EXPECT_THROW(buildLightTechniques(scene.lights, two, 1), Error);
}

TEST(LightTechniques, TenThousandTrianglesOneEachOrMergedUnderTheDefaultBudget) {
  PreparedScene scene = stripsAndPoints({10000}, 0);
  LightClusters lc = buildLightClusters(scene, 16, LightSelection::Power);
  LightTechniques t = buildLightTechniques(scene.lights, lc, 16384);
  expectValidTechniques(scene, lc, t, 16384);
  EXPECT_EQ(t.techniqueCount, 10000u);
  EXPECT_FALSE(t.merged());
  LightTechniques merged = buildLightTechniques(scene.lights, lc, kDefaultMaxTechniques);
  expectValidTechniques(scene, lc, merged, kDefaultMaxTechniques);
  EXPECT_TRUE(merged.merged());
  EXPECT_LE(merged.techniqueCount, kDefaultMaxTechniques);
  EXPECT_GT(merged.techniqueCount, kDefaultMaxTechniques / 2);
  // The pair table for them stays within lavapipe's 128 MiB per storage buffer.
  uint32_t capacity = shared::pairTableCapacityFor(1u << 21);
  EXPECT_LE(uint64_t(capacity) * shared::kPairStatsBytes, 128ull << 20);
}
