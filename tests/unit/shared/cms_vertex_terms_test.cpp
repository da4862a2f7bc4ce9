// The per-vertex terms of controlled mixture sampling (shaders/shared/cms_vertex_terms.h, which
// both backends call) against docs/estimator.md written out directly: the mixture densities (§1,
// §2), the control variate's terms (§3) and the statistics' increments (§4), with the CPU's double
// precision. The backends' renders are checked against each other elsewhere
// (cms_cpu_reference_test); this pins the formulas themselves.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "scene/light_selection.h"
#include "scene/prepared_scene.h"

// The header's accessors, bound to this test's arrays: one cell (index 0) with L clusters.
namespace vertex_terms_test {
const mixtrace::PreparedScene* gScene = nullptr;   // lights.h's accessors; no test reads a scene
const std::vector<mixtrace::shared::LightSelectionGpu>* gSelection = nullptr;   // likewise
std::vector<float> gSolution;                      // cellSolutionStride(L) floats
std::vector<float> gDefaults;                      // the default selection c_k
std::vector<double> gStats;                        // cellStatsStride(L) doubles
void addStat(uint32_t cell, uint32_t index, double value);
}  // namespace vertex_terms_test
#define SHARED_SCENE (*::vertex_terms_test::gScene)
#define SHARED_LIGHT_SELECTION (*::vertex_terms_test::gSelection)
#include "scene/shared_scene_access.h"
#define CELL_KEY_LOAD(slot) (uint64_t(0))
#define CELL_KEY_CAS(slot, expected, desired) (uint64_t(0))
#define CLUSTER(i) (::mixtrace::shared::ClusterGpu{})
#define CLUSTER_LIGHT(i) (::mixtrace::shared::ClusterLightGpu{})
#define CELL_SOLUTION(i) (::vertex_terms_test::gSolution[i])
#define CLUSTER_DEFAULT(k) (::vertex_terms_test::gDefaults[k])
#define CMS_STAT_REAL double
#define CMS_ADD_STAT(cell, index, value) (::vertex_terms_test::addStat(cell, index, value))
#include "shared/cms_vertex_terms.h"

namespace vertex_terms_test {
void addStat(uint32_t cell, uint32_t index, double value) {
  ASSERT_EQ(cell, 0u);
  gStats[index] += value;
}
}  // namespace vertex_terms_test

using namespace mixtrace::shared;
using namespace vertex_terms_test;

namespace {

constexpr uint L = 3;
constexpr uint kCell = 0;

// A solved cell: alpha_k, alpha_B, selection c_k, valid.
void setUpCell(std::mt19937& rng) {
  std::uniform_real_distribution<float> alpha(-2.0f, 2.0f);
  gSolution.assign(cellSolutionStride(L), 0.0f);
  gDefaults.assign(L, 1.0f / L);
  for (uint k = 0; k < L; ++k) {
    for (uint c = 0; c < 3; ++c) gSolution[solutionAlpha(L, k, c)] = alpha(rng);
    gSolution[solutionSelect(L, k)] = 0.2f * float(k + 1);   // 0.2, 0.4, 0.6
  }
  for (uint c = 0; c < 3; ++c) gSolution[solutionAlphaB(L, c)] = alpha(rng);
  gSolution[solutionValid(L)] = 1.0f;
  gStats.assign(cellStatsStride(L), 0.0);
}

// `relative`: 1e-12 for the statistics (double), a few float ulps for the radiance terms (float).
void expectNear(double actual, double expected, const char* what, double relative = 1e-12) {
  EXPECT_NEAR(actual, expected, relative * std::max(1.0, std::abs(expected))) << what;
}

}  // namespace

TEST(CmsVertexTerms, MixtureDensitiesAreTheBalanceHeuristicsDenominators) {
  std::mt19937 rng(1);
  setUpCell(rng);
  // A BSDF sample that hit cluster 1: c_1 p_1 + p_B; one that hit no light: p_B. (Without the
  // BVH defaults the hit's cluster weight is the cell's c_j, whatever the triangle.)
  const vec3 p(0.0f), n(0.0f, 0.0f, 1.0f);
  EXPECT_EQ(bsdfHitClusterWeight(kCell, L, 1u, 0u, p, n), 0.4f);
  EXPECT_EQ(bsdfHitClusterWeight(kCell, L, kNoCell, 0u, p, n), 0.0f);
  EXPECT_FLOAT_EQ(bsdfSampleMixtureDensity(1u, bsdfHitClusterWeight(kCell, L, 1u, 0u, p, n), 2.0f, 0.5f),
                  0.4f * 2.0f + 0.5f);
  EXPECT_EQ(bsdfSampleMixtureDensity(kNoCell, 0.0f, 2.0f, 0.5f), 0.5f);
  // No cell: the default selection.
  EXPECT_FLOAT_EQ(bsdfSampleMixtureDensity(2u, bsdfHitClusterWeight(kNoCell, L, 2u, 0u, p, n), 3.0f, 0.5f),
                  3.0f / 3.0f + 0.5f);
  EXPECT_EQ(lightSampleMixtureDensity(0.75f, 0.25f), 1.0f);
  EXPECT_EQ(balanceWeight(0.25f, 1.0f), 0.25f);
}

TEST(CmsVertexTerms, HiddenPointsAreNotReachableAndKeepPositiveDensities) {
  std::mt19937 rng(2);
  setUpCell(rng);
  const vec3 n(0.0f, 0.0f, 1.0f);
  LightSample ls{};
  ls.direction = vec3(0.0f, 0.0f, 1.0f);
  ls.pdf = 0.3f;
  float pk = 0.5f;
  EXPECT_TRUE(lightPointReachable(0.6f, n, 1.0f, false, true, pk, ls));
  EXPECT_FALSE(lightPointReachable(0.6f, n, 1.0f, false, false, pk, ls)) << "emits nothing towards the vertex";
  ls.direction = vec3(0.0f, 0.0f, -1.0f);
  EXPECT_FALSE(lightPointReachable(0.6f, n, -1.0f, false, true, pk, ls)) << "below the surface";
  EXPECT_TRUE(lightPointReachable(0.6f, n, -1.0f, true, true, pk, ls)) << "below the surface, through glass";
  EXPECT_FALSE(lightPointReachable(0.6f, n, 0.2f, true, true, pk, ls))
      << "below the geometric surface but above the shading frame's: no BSDF lobe reaches it";
  EXPECT_EQ(pk, 0.5f);
  // No solid-angle density: hidden, with p_k = 1 and light density c_k.
  ls.direction = vec3(0.0f, 0.0f, 1.0f);
  ls.pdf = 0.0f;
  EXPECT_FALSE(lightPointReachable(0.6f, n, 1.0f, false, true, pk, ls));
  EXPECT_EQ(pk, 1.0f);
  EXPECT_FLOAT_EQ(ls.pdf, 0.6f);
}

TEST(CmsVertexTerms, ControlVariateTermsAreAlphaWeightedDensitiesOverTheMixture) {
  std::mt19937 rng(3);
  setUpCell(rng);
  const vec3 T(0.5f, 1.0f, 2.0f);
  const float pk = 1.5f, pB = 0.7f, peff = 0.6f * pk + pB;
  const vec3 term = controlVariateTerm(T, kCell, L, 2u, pk, pB, peff);
  const vec3 hitNoLight = controlVariateTerm(T, kCell, L, kNoCell, pk, pB, peff);
  const vec3 integral = controlVariateIntegral(T, kCell, L);
  for (int c = 0; c < 3; ++c) {
    const double alphaK = gSolution[solutionAlpha(L, 2, c)], alphaB = gSolution[solutionAlphaB(L, c)];
    expectNear(term[c], T[c] * (alphaK * pk + alphaB * pB) / peff, "T g / p_eff", 1e-6);
    expectNear(hitNoLight[c], T[c] * alphaB * pB / peff, "T alpha_B p_B / p_eff (no cluster)", 1e-6);
    EXPECT_EQ(integral[c], T[c] * gSolution[solutionAlphaSum(L, c)]) << "T sum(alpha)";
  }
  // A failed BSDF sample subtracts exactly T alpha_B.
  const vec3 failed = controlVariateTerm(T, kCell, L, kNoCell, 0.0f, kFailedBsdfSamplePdf, kFailedBsdfSamplePdf);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(failed[c], T[c] * gSolution[solutionAlphaB(L, c)]);
}

TEST(CmsVertexTerms, StatisticsAddWeightedDensityProductsOverTheMixtureSquared) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.01f, 4.0f);
  for (int trial = 0; trial < 100; ++trial) {
    setUpCell(rng);
    const uint k = uint(trial) % L;
    const float pk = u(rng), pB = trial % 4 == 0 ? 0.0f : u(rng), ck = 0.2f * float(k + 1);
    const float peff = ck * pk + pB;
    const vec3 f(u(rng), 0.0f, u(rng));
    const double w = u(rng);
    addSampleStatistics(kCell, L, k, pk, pB, peff, f, w);
    const double p2 = double(peff) * peff;
    expectNear(gStats[statsAkk(L, k)], w * pk * pk / p2, "A_kk");
    expectNear(gStats[statsAkB(L, k)], w * pk * pB / p2, "A_kB");
    expectNear(gStats[statsABB(L)], w * pB * pB / p2, "A_BB");
    for (uint c = 0; c < 3; ++c) {
      expectNear(gStats[statsBk(L, k, c)], w * f[c] * pk / p2, "b_k");
      expectNear(gStats[statsBB(L, c)], w * f[c] * pB / p2, "b_B");
    }
    // Only A_kk, A_kB, A_BB, b_k and b_B: the other clusters' entries stay 0.
    for (uint j = 0; j < L; ++j) {
      if (j == k) continue;
      EXPECT_EQ(gStats[statsAkk(L, j)], 0.0);
      EXPECT_EQ(gStats[statsAkB(L, j)], 0.0);
      for (uint c = 0; c < 3; ++c) EXPECT_EQ(gStats[statsBk(L, j, c)], 0.0);
    }
  }
}

TEST(CmsVertexTerms, SamplesOutsideEveryClusterOrWithoutWeightAddOnlyWhatTheyTouch) {
  std::mt19937 rng(5);
  setUpCell(rng);
  // A failed BSDF sample: w to A_BB, nothing else.
  addSampleStatistics(kCell, L, kNoCell, 0.0, kFailedBsdfSamplePdf, kFailedBsdfSamplePdf, vec3(0.0f), 0.75);
  for (uint i = 0; i < cellStatsStride(L); ++i) EXPECT_EQ(gStats[i], i == statsABB(L) ? 0.75 : 0.0) << i;
  // A sample of a vertex that does not gather (w = 0, or NaN from a NaN throughput) adds nothing.
  gStats.assign(cellStatsStride(L), 0.0);
  addSampleStatistics(kCell, L, 1u, 1.0, 1.0, 2.0, vec3(1.0f), 0.0);
  addSampleStatistics(kCell, L, 1u, 1.0, 1.0, 2.0, vec3(1.0f), std::nan(""));
  for (uint i = 0; i < cellStatsStride(L); ++i) EXPECT_EQ(gStats[i], 0.0) << i;
}
