// The light BVH as the default selection of learned and cms (shaders/shared/cms_sampling.h,
// docs/estimator.md §7), compiled as C++ on the shipped scenes with cms's own tables: at shading
// points on the scenes' surfaces, for a cell that has learned nothing (all of the probability is
// the defaults') and one with a learned selection, the pmf of the light a light sample drew equals
// the pmf a BSDF sample that hits the same light evaluates (sampleClusterLight's c_k against
// bsdfHitClusterWeight), the evaluated pmfs over all lights sum to at most 1 (the rest: the BVH
// reaches no light), every light keeps a positive probability (the table's share of the defaults),
// and the drawn lights follow the evaluated pmf (chi-square).
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "cms/method_lights.h"
#include "cms/methods.h"
#include "gltf/gltf_loader.h"
#include "scene/prepared_scene.h"
namespace bvh_defaults_test {
const mixtrace::PreparedScene* gScene = nullptr;
const mixtrace::MethodLights* gLights = nullptr;
std::vector<float> gSolution;   // one cell (index 0)
}  // namespace bvh_defaults_test
#define SHARED_SCENE (*::bvh_defaults_test::gScene)
#define SHARED_LIGHT_SELECTION (::bvh_defaults_test::gLights->selection)
#define SHARED_LIGHT_BVH (::bvh_defaults_test::gLights->bvh)
#include "scene/shared_scene_access.h"
#define CELL_KEY_LOAD(slot) (uint64_t(0))
#define CELL_KEY_CAS(slot, expected, desired) (uint64_t(0))
#define CLUSTER(i) (::bvh_defaults_test::gLights->cms.clusters.clusters[i])
#define CLUSTER_LIGHT(i) (::bvh_defaults_test::gLights->cms.clusterLights[i])
#define CELL_SOLUTION(i) (::bvh_defaults_test::gSolution[i])
#define CLUSTER_DEFAULT(k) (::bvh_defaults_test::gLights->cms.clusters.defaultSelection[k])
#define CMS_STAT_REAL double
#define CMS_ADD_STAT(cell, index, value) ((void)0)
#include "shared/cms_vertex_terms.h"
#include "support/chi2.h"
#include "support/shipped_scenes.h"
#include "support/surface_points.h"

using namespace mixtrace;
using mixtrace::testing::sceneStem;
using mixtrace::testing::shippedScenes;
using mixtrace::testing::ShadingPoint;
using mixtrace::testing::surfacePoints;

namespace {

constexpr uint32_t kCell = 0;


// The cell's learned part: nothing, or (1 - eps) times a skewed pmf over the clusters.
void setSelection(uint32_t L, bool learned) {
  bvh_defaults_test::gSolution.assign(shared::cellSolutionStride(L), 0.0f);
  if (!learned) return;
  double total = 0.0;
  for (uint32_t k = 0; k < L; ++k) total += double(k + 1) * double(k + 1);
  for (uint32_t k = 0; k < L; ++k)
    bvh_defaults_test::gSolution[shared::solutionSelect(L, k)] = float(0.8 * double(k + 1) * double(k + 1) / total);
}

}  // namespace

class CmsBvhDefaultsOnScene : public ::testing::TestWithParam<std::string> {};

TEST_P(CmsBvhDefaultsOnScene, DrawnPmfEqualsEvaluatedPmfAndFollowsIt) {
  PreparedScene scene = prepareScene(loadGltf(GetParam()));
  const MethodInfo* cms = findMethod("cms");
  ASSERT_NE(cms, nullptr);
  ASSERT_EQ(cms->selection, LightSelection::Bvh) << "cms's defaults are the light BVH";
  MethodLights lights = buildMethodLights(scene, *cms, 16);
  bvh_defaults_test::gScene = &scene;
  bvh_defaults_test::gLights = &lights;
  const uint32_t L = uint32_t(lights.cms.clusters.clusters.size());
  const uint32_t n = uint32_t(scene.lights.lights.size());
  if (L < 2) GTEST_SKIP() << "one cluster: cms runs as plain MIS";
  ASSERT_TRUE(CMS_BVH_DEFAULTS);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (bool learned : {false, true}) {
    setSelection(L, learned);
    const float delta = shared::defaultsShare(kCell, L);
    EXPECT_NEAR(delta, learned ? 0.2f : 1.0f, 1e-5f);
    for (const ShadingPoint& s : surfacePoints(scene, 6, learned ? 17u : 13u)) {
      SCOPED_TRACE(std::string(learned ? "learned" : "defaults only") + " at (" + std::to_string(s.p.x) + ", " +
                   std::to_string(s.p.y) + ", " + std::to_string(s.p.z) + ")");
      // The evaluated pmf of every light: P(l | x) = c_k(l) q_l|k.
      std::vector<double> pmf(n);
      double sum = 0.0;
      for (uint32_t l = 0; l < n; ++l) {
        pmf[l] = double(shared::vertexClusterWeight(kCell, L, l, s.p, s.n, delta)) * LIGHT_CLUSTER_PMF(l);
        sum += pmf[l];
        if (LIGHT_CLUSTER_PMF(l) > 0.0f) EXPECT_GT(pmf[l], 0.0) << "light " << l << " can never be drawn";
      }
      EXPECT_LE(sum, 1.0 + 1e-5);
      // Draws: the drawn light's c_k is the evaluated one, also as a BSDF hit on its triangle.
      const int draws = 40000;
      std::vector<double> counts(n + 1, 0.0);   // the last bin: no light drawn
      for (int i = 0; i < draws; ++i) {
        uint32_t state = uint32_t(rng());
        uint k;
        float pk, ck;
        shared::LightSample ls;
        shared::sampleClusterLight(kCell, L, s.p, s.p, s.n, u(rng), u(rng), glm::vec2(u(rng), u(rng)), state, k, pk,
                                   ck, ls);
        if (k == shared::kNoCell) {
          counts[n] += 1.0;
          continue;
        }
        counts[ls.light] += 1.0;
        ASSERT_EQ(k, LIGHT_CLUSTER(ls.light));
        ASSERT_FLOAT_EQ(ck, shared::vertexClusterWeight(kCell, L, ls.light, s.p, s.n, delta));
        if (ls.triangle != shared::kNoHit)
          ASSERT_EQ(ck, shared::bsdfHitClusterWeight(kCell, L, k, ls.triangle, s.p, s.n)) << "light " << ls.light;
      }
      std::vector<double> observed, expected;
      for (uint32_t l = 0; l <= n; ++l) {
        double p = l < n ? pmf[l] : std::max(0.0, 1.0 - sum);
        if (p * draws < 1e-9) {
          EXPECT_EQ(counts[l], 0.0) << "bin " << l;
          continue;
        }
        observed.push_back(counts[l]);
        expected.push_back(p * draws);
      }
      if (observed.size() < 2) continue;
      chi2::ChiSquareResult r = chi2::chiSquareTest(observed, expected);
      EXPECT_GT(r.pValue, 1e-4) << "chi2 " << r.statistic << " dof " << r.dof;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Shipped, CmsBvhDefaultsOnScene, ::testing::ValuesIn(shippedScenes()),
                         [](const auto& info) { return sceneStem(info.param); });
