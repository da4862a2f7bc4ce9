// The sparse statistics of one control-variate technique per emissive triangle and their exact
// arrowhead solve (cms/sparse_statistics.h, cms/sparse_solve.h; ../shared/cms.md §4, §6):
// agreement with a dense solve, the invariants that keep dropped techniques harmless, the
// stability cases of issue 13 point 6, and convergence to the true optimum of a 1-D integral.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "cms/reference_solve.h"
#include "cms/sparse_solve.h"
#include "cms/sparse_statistics.h"
#include "shared/cms_layouts.h"
#include "shared/cms_pair_layout.h"
#include "shared/cms_solve.h"

namespace mixtrace {
namespace {

using Vec = glm::dvec3;

// --- A dense solve written here, independent of the arrowhead elimination: the full
// (T+1)x(T+1) system (A + r I) alpha = b over the given techniques and B, by Gaussian elimination
// with partial pivoting in long double.
struct DenseResult {
  std::vector<Vec> alpha;   // per pair
  Vec alphaB{0.0};
};

DenseResult denseSolve(const SparseCellStatistics& cell, double ridge, bool withB = true) {
  const size_t T = cell.pairs.size();
  const size_t m = T + (withB ? 1 : 0);
  long double mean = 0;
  for (const auto& p : cell.pairs) mean += p.aTT;
  if (withB) mean += cell.totals.aBB;
  const long double r = ridge * mean / m;
  std::vector<long double> M(m * m, 0.0L), rhs(m * 3, 0.0L);
  for (size_t t = 0; t < T; ++t) {
    M[t * m + t] = cell.pairs[t].aTT + r;
    if (withB) M[t * m + T] = M[T * m + t] = cell.pairs[t].aTB;
    for (int c = 0; c < 3; ++c) rhs[t * 3 + c] = cell.pairs[t].bT[c];
  }
  if (withB) {
    M[T * m + T] = cell.totals.aBB + r;
    for (int c = 0; c < 3; ++c) rhs[T * 3 + c] = cell.totals.bB[c];
  }
  for (size_t j = 0; j < m; ++j) {
    size_t piv = j;
    for (size_t i = j + 1; i < m; ++i)
      if (std::fabs(M[i * m + j]) > std::fabs(M[piv * m + j])) piv = i;
    for (size_t l = 0; l < m; ++l) std::swap(M[j * m + l], M[piv * m + l]);
    for (int c = 0; c < 3; ++c) std::swap(rhs[j * 3 + c], rhs[piv * 3 + c]);
    for (size_t i = j + 1; i < m; ++i) {
      long double f = M[i * m + j] / M[j * m + j];
      if (f == 0) continue;
      for (size_t l = j; l < m; ++l) M[i * m + l] -= f * M[j * m + l];
      for (int c = 0; c < 3; ++c) rhs[i * 3 + c] -= f * rhs[j * 3 + c];
    }
  }
  std::vector<long double> x(m * 3);
  for (size_t i = m; i-- > 0;)
    for (int c = 0; c < 3; ++c) {
      long double v = rhs[i * 3 + c];
      for (size_t l = i + 1; l < m; ++l) v -= M[i * m + l] * x[l * 3 + c];
      x[i * 3 + c] = v / M[i * m + i];
    }
  DenseResult out;
  out.alpha.resize(T);
  for (size_t t = 0; t < T; ++t) out.alpha[t] = Vec(double(x[t * 3]), double(x[t * 3 + 1]), double(x[t * 3 + 2]));
  if (withB) out.alphaB = Vec(double(x[T * 3]), double(x[T * 3 + 1]), double(x[T * 3 + 2]));
  return out;
}

double maxAbs(const Vec& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }
bool finite3(const Vec& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void expectAllFinite(const SparseCellSolution& s) {
  EXPECT_TRUE(finite3(s.alphaB));
  EXPECT_TRUE(finite3(s.alphaSum));
  for (const Vec& a : s.alpha) EXPECT_TRUE(finite3(a));
  for (const Vec& a : s.clusterAlpha) EXPECT_TRUE(finite3(a));
}

void expectAllZero(const SparseCellSolution& s) {
  EXPECT_EQ(maxAbs(s.alphaB), 0.0);
  EXPECT_EQ(maxAbs(s.alphaSum), 0.0);
  for (const Vec& a : s.alpha) EXPECT_EQ(maxAbs(a), 0.0);
}

// Residual of (A + r I) alpha = b, relative to |b| + |A||alpha| per row: independent of how the
// solve eliminated.
double relativeResidual(const SparseCellStatistics& cell, const SparseCellSolution& s, double r) {
  double worst = 0.0;
  Vec rowB = (cell.totals.aBB + r) * s.alphaB - cell.totals.bB;
  Vec scaleB = glm::abs(cell.totals.bB) + (cell.totals.aBB + r) * glm::abs(s.alphaB);
  for (size_t t = 0; t < cell.pairs.size(); ++t) {
    const auto& p = cell.pairs[t];
    Vec row = (p.aTT + r) * s.alpha[t] + p.aTB * s.alphaB - p.bT;
    Vec scale = glm::abs(p.bT) + (p.aTT + r) * glm::abs(s.alpha[t]) + std::fabs(p.aTB) * glm::abs(s.alphaB);
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(row[c]) / (scale[c] + 1e-300));
    rowB += p.aTB * s.alpha[t];
    scaleB += std::fabs(p.aTB) * glm::abs(s.alpha[t]);
  }
  for (int c = 0; c < 3; ++c) worst = std::max(worst, std::fabs(rowB[c]) / (scaleB[c] + 1e-300));
  return worst;
}

double meanDiagonal(const SparseCellStatistics& cell) {
  double sum = cell.totals.aBB;
  for (const auto& p : cell.pairs) sum += p.aTT;
  return sum / double(cell.pairs.size() + 1);
}

// A random cell gathered through add(): light samples spread over T techniques, BSDF samples
// that hit one of them or nothing. Well conditioned when every technique gets several samples.
SparseStatisticsTable randomTable(uint32_t T, uint32_t samplesPerTechnique, uint32_t seed, size_t spare = 0) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.1, 2.0);
  SparseStatisticsTable table(T + 1 + spare);
  const uint32_t n = T * samplesPerTechnique + 100;
  for (uint32_t i = 0; i < n; ++i) {
    SparseSample s;
    s.technique = i % 5 == 4 ? kNoLightTechnique : uint32_t(rng() % T);
    s.pT = s.technique == kNoLightTechnique ? 0.0 : u(rng);
    s.pB = i % 3 == 0 ? 0.0 : u(rng);   // a blocked light sample has p_B = 0
    s.pEff = 0.3 * s.pT + s.pB + (s.pT == 0 && s.pB == 0 ? 1.0 : 0.0);
    s.f = Vec(u(rng), u(rng), u(rng)) * (s.pT + s.pB);
    s.weight = u(rng);
    EXPECT_EQ(table.add(0, s), SparseAddResult::Added);
  }
  return table;
}

// --- (a) agreement with the dense solve

void expectAgreesWithDense(uint32_t T, double ridge) {
  SparseStatisticsTable table = randomTable(T, 8, 1234 + T);
  const SparseCellStatistics& cell = *table.cell(0);
  ASSERT_EQ(cell.pairs.size(), T);
  SparseSolveParams params;
  params.ridge = ridge;
  SparseCellSolution s = solveSparseCell(cell, params);
  ASSERT_TRUE(s.valid);
  EXPECT_TRUE(s.bInSystem);
  EXPECT_EQ(s.techniquesInSystem, T);
  DenseResult d = denseSolve(cell, ridge);
  double scale = maxAbs(d.alphaB);
  for (const Vec& a : d.alpha) scale = std::max(scale, maxAbs(a));
  EXPECT_LE(maxAbs(s.alphaB - d.alphaB), 1e-10 * scale);
  Vec sum = d.alphaB;
  for (uint32_t t = 0; t < T; ++t) {
    EXPECT_LE(maxAbs(s.alpha[t] - d.alpha[t]), 1e-10 * scale) << "technique " << t;
    sum += d.alpha[t];
  }
  EXPECT_LE(maxAbs(s.alphaSum - sum), 1e-10 * scale * T);
}

TEST(SparseSolve, AgreesWithADenseSolveForOneTechnique) {
  expectAgreesWithDense(1, 0.0);
  expectAgreesWithDense(1, 1e-3);
}
TEST(SparseSolve, AgreesWithADenseSolveForThreeTechniques) {
  expectAgreesWithDense(3, 0.0);
  expectAgreesWithDense(3, 1e-3);
}
TEST(SparseSolve, AgreesWithADenseSolveForFiftyTechniques) {
  expectAgreesWithDense(50, 0.0);
  expectAgreesWithDense(50, 1e-3);
}

// When f is exactly a combination of the densities, the sample statistics satisfy b = A beta for
// any samples, so the unregularised solve must return beta itself.
TEST(SparseSolve, RecoversTheCoefficientsOfAnIntegrandInTheSpanOfTheDensities) {
  const uint32_t T = 7;
  std::vector<Vec> beta(T);
  for (uint32_t t = 0; t < T; ++t) beta[t] = Vec(0.5 + t, -0.25 * t, 2.0);
  const Vec betaB(0.7, 1.5, -0.3);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.05, 3.0);
  SparseStatisticsTable table(100);
  for (int i = 0; i < 500; ++i) {
    SparseSample s;
    s.technique = i % 4 == 3 ? kNoLightTechnique : uint32_t(rng() % T);
    s.pT = s.technique == kNoLightTechnique ? 0.0 : u(rng);
    s.pB = u(rng);
    s.pEff = 0.2 * s.pT + s.pB;
    s.f = betaB * s.pB + (s.technique == kNoLightTechnique ? Vec(0.0) : beta[s.technique] * s.pT);
    s.weight = u(rng);
    table.add(3, s);
  }
  SparseSolveParams params;
  params.ridge = 0.0;
  SparseCellSolution s = solveSparseCell(*table.cell(3), params);
  ASSERT_TRUE(s.valid);
  EXPECT_LE(maxAbs(s.alphaB - betaB), 1e-9);
  for (size_t i = 0; i < s.alpha.size(); ++i)
    EXPECT_LE(maxAbs(s.alpha[i] - beta[table.cell(3)->pairs[i].technique]), 1e-9);
}

// The table-full fallback (docs/estimator.md §4): cluster 0 holds four triangles of shares 0.1,
// 0.2, 0.3, 0.4. Triangles 0 and 1 have pairs with many samples (solved), triangle 2 a pair with
// too few (dropped), triangle 3 none (its samples went to the remainder). Cluster 1 has a remainder
// pair and no solved triangle. With f in the span of the densities the solve recovers every
// coefficient, and the integral counts alpha_R of cluster 0 with P_R = 1 - 0.1 - 0.2 = 0.7 (the
// mass of triangles 2 and 3, which use alpha_R) and cluster 1's with 1.
TEST(SparseSolve, ARemainderTechniqueIntegratesToTheMassOfItsClustersUnsolvedTriangles) {
  const double share[4] = {0.1, 0.2, 0.3, 0.4};
  const Vec beta[2] = {Vec(0.5, 1.0, 2.0), Vec(-0.3, 0.2, 0.9)};   // triangles 0, 1
  const Vec betaR0(1.5, 0.25, -0.5), betaR1(0.75, 0.5, 0.1), betaB(0.2, 0.4, 0.6);
  const uint32_t r0 = shared::remainderTechnique(0), r1 = shared::remainderTechnique(1);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0.05, 3.0);
  SparseStatisticsTable table(100);
  for (int i = 0; i < 600; ++i) {
    SparseSample s;
    const uint32_t kind = i % 6;   // 0, 1: triangles; 2: triangle 2 (few samples); 3, 4: remainders; 5: none
    s.technique = kind < 2 ? kind : kind == 2 ? (i < 12 ? 2u : kNoLightTechnique) : kind == 3 ? r0 : kind == 4 ? r1 : kNoLightTechnique;
    s.pT = s.technique == kNoLightTechnique ? 0.0 : u(rng);
    s.pB = u(rng);
    s.pEff = 0.2 * s.pT + s.pB;
    const Vec light = kind < 2 ? beta[kind] : s.technique == r0 ? betaR0 : s.technique == r1 ? betaR1 : Vec(0.0);
    s.f = betaB * s.pB + light * s.pT;
    table.add(0, s);
  }
  SparseCellStatistics cell = *table.cell(0);
  for (SparsePairStatistics& p : cell.pairs)
    if (!shared::isRemainderTechnique(p.technique)) p.share = share[p.technique];   // cluster 0
  SparseSolveParams params;
  params.ridge = 0.0;
  params.minTechniqueSamples = 8;   // triangle 2 has 2
  SparseCellSolution sol = solveSparseCell(cell, params);
  ASSERT_TRUE(sol.valid);
  EXPECT_LE(maxAbs(sol.alphaB - betaB), 1e-9);
  Vec expectedSum = sol.alphaB;
  uint32_t seen = 0;
  for (size_t i = 0; i < cell.pairs.size(); ++i) {
    const uint32_t t = cell.pairs[i].technique;
    if (t == 2u) {
      EXPECT_FALSE(sol.inSystem[i]) << "too few samples";
      EXPECT_EQ(sol.mass[i], 1.0);
      continue;
    }
    EXPECT_TRUE(sol.inSystem[i]) << t;
    const Vec expected = t == r0 ? betaR0 : t == r1 ? betaR1 : beta[t];
    EXPECT_LE(maxAbs(sol.alpha[i] - expected), 1e-9) << t;
    const double mass = t == r0 ? 0.7 : 1.0;
    EXPECT_NEAR(sol.mass[i], mass, 1e-15) << t;
    expectedSum += expected * mass;
    ++seen;
  }
  EXPECT_EQ(seen, 4u);
  EXPECT_LE(maxAbs(sol.alphaSum - expectedSum), 1e-9);
}

// The rules are today's per-cluster solve's: with one pair per cluster, the sparse solve and the
// double-precision reference (host/cms/reference_solve.cpp, a dense Cholesky with its own drop
// logic) must agree on the same statistics, dropped techniques and invalid cells included.
void expectAgreesWithTheClusterReference(const SparseCellStatistics& cell, const char* what, float ridge = 1e-3f,
                                         bool expectB = false) {
  const uint32_t L = uint32_t(cell.pairs.size());
  std::vector<double> stats(shared::cellStatsStride(L), 0.0);
  for (uint32_t k = 0; k < L; ++k) {
    stats[shared::statsAkk(L, k)] = cell.pairs[k].aTT;
    stats[shared::statsAkB(L, k)] = cell.pairs[k].aTB;
    for (uint32_t c = 0; c < 3; ++c) stats[shared::statsBk(L, k, c)] = cell.pairs[k].bT[c];
  }
  stats[shared::statsABB(L)] = cell.totals.aBB;
  for (uint32_t c = 0; c < 3; ++c) stats[shared::statsBB(L, c)] = cell.totals.bB[c];
  shared::SolveParams params{};
  params.clusterCount = L;
  params.minSamples = 64;
  params.flags = shared::kSolveControlVariate;
  params.ridge = ridge;
  params.defensive = 0.2f;
  std::vector<float> defaults(L, 1.0f / L);
  CellSolution ref = solveCellReference(stats.data(), uint32_t(cell.totals.samples), L, params, defaults.data());
  SparseSolveParams sparseParams;
  sparseParams.ridge = double(params.ridge);
  SparseCellSolution s = solveSparseCell(cell, sparseParams);
  ASSERT_EQ(s.valid, ref.valid) << what;
  EXPECT_EQ(s.bInSystem, bool(ref.inSystem[L])) << what;
  double scale = maxAbs(ref.alphaB) + 1e-300;
  for (uint32_t k = 0; k < L; ++k) {
    EXPECT_EQ(s.inSystem[k], bool(ref.inSystem[k])) << what << " technique " << k;
    scale = std::max(scale, maxAbs(ref.alpha[k]));
  }
  EXPECT_LE(maxAbs(s.alphaB - ref.alphaB), 1e-9 * scale) << what;
  for (uint32_t k = 0; k < L; ++k) EXPECT_LE(maxAbs(s.alpha[k] - ref.alpha[k]), 1e-9 * scale) << what << " " << k;
  EXPECT_LE(maxAbs(s.alphaSum - ref.alphaSum), 1e-9 * scale * (L + 1)) << what;
  if (expectB) EXPECT_TRUE(s.bInSystem) << what;
}

TEST(SparseSolve, AgreesWithThePerClusterReferenceSolveOnTheSameStatistics) {
  for (uint32_t T : {1u, 5u, 32u}) expectAgreesWithTheClusterReference(*randomTable(T, 10, 40 + T).cell(0), "random");
  SparseCellStatistics base = *randomTable(6, 10, 50).cell(0);
  SparseCellStatistics c = base;
  c.pairs[2].aTT = c.pairs[2].aTB = 0.0;
  c.pairs[2].bT = Vec(0.0);
  expectAgreesWithTheClusterReference(c, "zero row");
  c = base;
  c.pairs[4].aTB = std::numeric_limits<double>::quiet_NaN();
  expectAgreesWithTheClusterReference(c, "NaN row");
  c = base;
  c.totals.aBB = 0.0;
  expectAgreesWithTheClusterReference(c, "no B");
  c = base;
  double schur = 0.0;
  for (const auto& p : c.pairs) schur += p.aTB * p.aTB / p.aTT;
  c.totals.aBB = schur;   // B a combination of the techniques: singular without the ridge
  expectAgreesWithTheClusterReference(c, "singular");
  expectAgreesWithTheClusterReference(c, "singular, no ridge", 0.0f);
  // Scaled Schur pivots either side of kSolvePivotFloor (1e-5), without the ridge: 1e-4 keeps B.
  c.totals.aBB = schur / (1.0 - 1e-4);
  expectAgreesWithTheClusterReference(c, "pivot 1e-4", 0.0f, true);
  c.totals.aBB = schur / (1.0 - 1e-6);
  expectAgreesWithTheClusterReference(c, "pivot 1e-6", 0.0f);
  c = base;
  c.totals.samples = 63;
  expectAgreesWithTheClusterReference(c, "too few samples");
  c = base;
  c.pairs[1].bT *= 1e32;
  expectAgreesWithTheClusterReference(c, "sum beyond the bound");
}

// --- statistics increments, exactly as cms.md §4 writes them

TEST(SparseStatistics, AddFormsTheIncrementsOfCmsSection4) {
  SparseStatisticsTable table(4);
  SparseSample s;
  s.technique = 9;
  s.pT = 0.5;
  s.pB = 2.0;
  s.pEff = 0.25 * 0.5 + 2.0;
  s.f = Vec(1.0, 2.0, 3.0);
  s.weight = 1.5;
  ASSERT_EQ(table.add(4, s), SparseAddResult::Added);
  SparseSample bsdfMiss;
  bsdfMiss.pB = 0.8;
  bsdfMiss.pEff = 0.8;
  bsdfMiss.f = Vec(0.0);
  ASSERT_EQ(table.add(4, bsdfMiss), SparseAddResult::Added);
  const SparseCellStatistics& c = *table.cell(4);
  const double e2 = s.pEff * s.pEff;
  EXPECT_DOUBLE_EQ(c.totals.aBB, 1.5 * 2.0 * 2.0 / e2 + 1.0);
  EXPECT_DOUBLE_EQ(c.totals.bB.z, 1.5 * 3.0 * 2.0 / e2);
  EXPECT_EQ(c.totals.samples, 2u);
  ASSERT_EQ(c.pairs.size(), 1u);
  EXPECT_EQ(c.pairs[0].technique, 9u);
  EXPECT_DOUBLE_EQ(c.pairs[0].aTT, 1.5 * 0.5 * 0.5 / e2);
  EXPECT_DOUBLE_EQ(c.pairs[0].aTB, 1.5 * 0.5 * 2.0 / e2);
  EXPECT_DOUBLE_EQ(c.pairs[0].bT.y, 1.5 * 2.0 * 0.5 / e2);
  EXPECT_EQ(c.pairs[0].samples, 1u);
  EXPECT_EQ(table.entries(), 2u);
}

// --- (b) techniques without usable samples are dropped and do not spoil the others

SparseCellStatistics withExtraPair(SparseCellStatistics cell, const SparsePairStatistics& extra, size_t at) {
  cell.pairs.insert(cell.pairs.begin() + at, extra);
  return cell;
}

void expectSameAsWithout(const SparseCellStatistics& base, const SparsePairStatistics& extra,
                         const SparseSolveParams& params) {
  const size_t at = 1;
  SparseCellSolution without = solveSparseCell(base, params);
  SparseCellSolution with = solveSparseCell(withExtraPair(base, extra, at), params);
  ASSERT_TRUE(without.valid);
  ASSERT_TRUE(with.valid);
  expectAllFinite(with);
  EXPECT_FALSE(with.inSystem[at]);
  EXPECT_EQ(maxAbs(with.alpha[at]), 0.0);
  EXPECT_EQ(with.alphaB, without.alphaB);
  EXPECT_EQ(with.alphaSum, without.alphaSum);
  for (size_t i = 0, j = 0; i < with.alpha.size(); ++i)
    if (i != at) EXPECT_EQ(with.alpha[i], without.alpha[j++]);
}

TEST(SparseSolve, ATechniqueWithZeroSamplesGetsZeroAndChangesNothingElse) {
  SparseStatisticsTable table = randomTable(4, 10, 77);
  SparsePairStatistics empty;
  empty.technique = 99;
  expectSameAsWithout(*table.cell(0), empty, SparseSolveParams{});
  // Zero samples but stale numbers (a restarted pair): still dropped.
  empty.aTT = 5.0;
  empty.aTB = 1.0;
  empty.bT = Vec(3.0);
  expectSameAsWithout(*table.cell(0), empty, SparseSolveParams{});
}

TEST(SparseSolve, AZeroRowIsDroppedAndAnAllZeroCellIsInvalid) {
  SparseStatisticsTable table = randomTable(4, 10, 78);
  SparsePairStatistics zero;   // samples that all had p_t = 0 (underflowed)
  zero.technique = 50;
  zero.samples = 12;
  expectSameAsWithout(*table.cell(0), zero, SparseSolveParams{});

  SparseCellStatistics nothing;
  nothing.totals.samples = 1000;
  nothing.pairs.assign(3, zero);
  SparseCellSolution s = solveSparseCell(nothing, SparseSolveParams{});
  EXPECT_FALSE(s.valid);
  EXPECT_EQ(s.techniquesInSystem, 0u);
  expectAllZero(s);
}

// --- (c) stability

TEST(SparseSolve, BsdfSamplingIdenticalToALightTechniqueIsSingularAndDropsB) {
  // Every sample has p_B = p_t: A_tt = A_tB = A_BB, an exactly singular system.
  SparseStatisticsTable table(8);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.1, 2.0);
  for (int i = 0; i < 200; ++i) {
    SparseSample s;
    s.technique = 0;
    s.pT = s.pB = u(rng);
    s.pEff = 1.5 * s.pT;
    s.f = Vec(u(rng));
    table.add(0, s);
  }
  const SparseCellStatistics& cell = *table.cell(0);
  SparseSolveParams exact;
  exact.ridge = 0.0;
  SparseCellSolution s = solveSparseCell(cell, exact);
  ASSERT_TRUE(s.valid);
  EXPECT_FALSE(s.bInSystem);
  EXPECT_EQ(maxAbs(s.alphaB), 0.0);
  EXPECT_LE(maxAbs(s.alpha[0] - cell.pairs[0].bT / cell.pairs[0].aTT), 1e-12 * maxAbs(s.alpha[0]));
  // With the ridge the system is regular again: finite, and agreeing with the dense solve.
  SparseCellSolution r = solveSparseCell(cell, SparseSolveParams{});
  ASSERT_TRUE(r.valid);
  expectAllFinite(r);
  DenseResult d = denseSolve(cell, SparseSolveParams{}.ridge, r.bInSystem);
  EXPECT_LE(maxAbs(r.alpha[0] - d.alpha[0]), 1e-8 * maxAbs(d.alpha[0]));
}

TEST(SparseSolve, BsdfSamplingACombinationOfTheLightTechniquesDropsB) {
  // p_B = lambda_t p_t on the support of t: A_BB = sum_t A_tB^2 / A_tt, the Schur pivot is 0.
  SparseStatisticsTable table(8);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0.1, 2.0);
  const double lambda[3] = {0.5, 2.0, 1.0};
  for (int i = 0; i < 300; ++i) {
    SparseSample s;
    s.technique = uint32_t(i % 3);
    s.pT = u(rng);
    s.pB = lambda[s.technique] * s.pT;
    s.pEff = 0.4 * s.pT + s.pB;
    s.f = Vec(u(rng), 1.0, 0.0);
    table.add(0, s);
  }
  SparseSolveParams exact;
  exact.ridge = 0.0;
  SparseCellSolution s = solveSparseCell(*table.cell(0), exact);
  ASSERT_TRUE(s.valid);
  EXPECT_FALSE(s.bInSystem);
  expectAllFinite(s);
  for (size_t t = 0; t < 3; ++t) {
    const auto& p = table.cell(0)->pairs[t];
    EXPECT_LE(maxAbs(s.alpha[t] - p.bT / p.aTT), 1e-12 * (maxAbs(s.alpha[t]) + 1.0));
  }
}

TEST(SparseSolve, ConditionNumber1e12AgreesWithTheDenseSolve) {
  const uint32_t T = 13;
  SparseCellStatistics cell;
  cell.totals.aBB = 1.0;
  cell.totals.bB = Vec(1.0, -2.0, 0.5);
  cell.totals.samples = 10000;
  for (uint32_t t = 0; t < T; ++t) {
    SparsePairStatistics p;
    p.technique = t;
    p.aTT = std::pow(10.0, -6.0 + 12.0 * t / (T - 1));   // diagonal from 1e-6 to 1e6
    p.aTB = 0.6 * std::sqrt(p.aTT * cell.totals.aBB / T);   // scaled pivot 1 - 0.36
    p.bT = Vec(p.aTT, 0.3 * std::sqrt(p.aTT), 1.0);
    p.samples = 500;
    cell.pairs.push_back(p);
  }
  SparseSolveParams params;
  params.ridge = 0.0;
  SparseCellSolution s = solveSparseCell(cell, params);
  ASSERT_TRUE(s.valid);
  ASSERT_TRUE(s.bInSystem);
  DenseResult d = denseSolve(cell, 0.0);
  EXPECT_LE(maxAbs(s.alphaB - d.alphaB), 1e-12 * (maxAbs(d.alphaB) + 1.0));
  for (uint32_t t = 0; t < T; ++t)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(s.alpha[t][c], d.alpha[t][c], 1e-10 * std::fabs(d.alpha[t][c]) + 1e-12) << t;
  EXPECT_LE(relativeResidual(cell, s, 0.0), 1e-12);
}

TEST(SparseSolve, OneSampleIsBelowTheMinimumAndStillFiniteWhenAllowed) {
  SparseStatisticsTable table(4);
  SparseSample s;
  s.technique = 2;
  s.pT = 1.3;
  s.pB = 0.4;
  s.pEff = 0.5 * 1.3 + 0.4;
  s.f = Vec(2.0, 1.0, 0.5);
  table.add(0, s);
  SparseCellSolution tooFew = solveSparseCell(*table.cell(0), SparseSolveParams{});
  EXPECT_FALSE(tooFew.valid);
  expectAllZero(tooFew);
  for (double ridge : {0.0, 1e-3}) {
    SparseSolveParams one;
    one.minCellSamples = 1;
    one.ridge = ridge;
    SparseCellSolution s1 = solveSparseCell(*table.cell(0), one);   // a rank-1 system
    EXPECT_TRUE(s1.valid);
    expectAllFinite(s1);
    if (ridge == 0.0) EXPECT_FALSE(s1.bInSystem);
  }
}

TEST(SparseSolve, HundredMillionSamplesAndCountsBeyond32Bits) {
  SparseStatisticsTable table = randomTable(5, 10, 9);
  SparseCellStatistics cell = *table.cell(0);
  SparseCellSolution base = solveSparseCell(cell, SparseSolveParams{});
  // The same distribution summed over 1e8 samples: every sum 1e8 / n times larger.
  for (uint64_t total : {uint64_t(100000000), uint64_t(6000000000)}) {
    SparseCellStatistics many = cell;
    const double k = double(total) / double(cell.totals.samples);
    many.totals.aBB *= k;
    many.totals.bB *= k;
    many.totals.samples = total;
    for (auto& p : many.pairs) {
      p.aTT *= k;
      p.aTB *= k;
      p.bT *= k;
      p.samples = uint64_t(double(p.samples) * k);
    }
    SparseCellSolution s = solveSparseCell(many, SparseSolveParams{});
    ASSERT_TRUE(s.valid);
    EXPECT_LE(maxAbs(s.alphaSum - base.alphaSum), 1e-12 * maxAbs(base.alphaSum));
  }
}

TEST(SparseSolve, MagnitudesFrom1em8To1e8ScaleAlphaExactly) {
  SparseStatisticsTable table = randomTable(6, 10, 10);
  const SparseCellStatistics& cell = *table.cell(0);
  SparseCellSolution base = solveSparseCell(cell, SparseSolveParams{});
  ASSERT_TRUE(base.valid);
  for (double a : {1e-8, 1e-4, 1.0, 1e4, 1e8})
    for (double f : {1e-8, 1.0, 1e8}) {
      SparseCellStatistics scaled = cell;   // A scaled by a, b by a * f: alpha scales by f
      scaled.totals.aBB *= a;
      scaled.totals.bB *= a * f;
      for (auto& p : scaled.pairs) {
        p.aTT *= a;
        p.aTB *= a;
        p.bT *= a * f;
      }
      SparseCellSolution s = solveSparseCell(scaled, SparseSolveParams{});
      ASSERT_TRUE(s.valid) << a << " " << f;
      EXPECT_LE(maxAbs(s.alphaB - f * base.alphaB), 1e-12 * f * maxAbs(base.alphaB)) << a << " " << f;
      for (size_t t = 0; t < s.alpha.size(); ++t)
        EXPECT_LE(maxAbs(s.alpha[t] - f * base.alpha[t]), 1e-12 * f * maxAbs(base.alpha[t])) << a << " " << f;
    }
}

TEST(SparseSolve, NanOrInfInATechniqueDropsItAndNeverLeaksOut) {
  SparseStatisticsTable table = randomTable(4, 10, 11);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  SparsePairStatistics bad;
  bad.technique = 70;
  bad.samples = 10;
  bad.aTT = 1.0;
  bad.aTB = 0.1;
  bad.bT = Vec(1.0);
  for (int which = 0; which < 6; ++which) {
    SparsePairStatistics b = bad;
    if (which == 0) b.aTT = nan;
    if (which == 1) b.aTT = inf;
    if (which == 2) b.aTB = -inf;
    if (which == 3) b.aTB = nan;
    if (which == 4) b.bT.y = nan;
    if (which == 5) b.bT.z = inf;
    expectSameAsWithout(*table.cell(0), b, SparseSolveParams{});
  }
}

TEST(SparseSolve, NanOrInfInTheBsdfRowDropsBOrTheCellNeverLeaksOut) {
  SparseStatisticsTable table = randomTable(4, 10, 12);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (int which = 0; which < 3; ++which) {
    SparseCellStatistics cell = *table.cell(0);
    if (which == 0) cell.totals.aBB = nan;
    if (which == 1) cell.totals.aBB = inf;
    if (which == 2) cell.totals.bB.x = -inf;
    SparseCellSolution s = solveSparseCell(cell, SparseSolveParams{});
    ASSERT_TRUE(s.valid);
    EXPECT_FALSE(s.bInSystem);
    expectAllFinite(s);
    EXPECT_EQ(maxAbs(s.alphaB), 0.0);
  }
  // A NaN sample (p_eff = 0) through add() spoils B and the technique it touched.
  SparseStatisticsTable poisoned = randomTable(4, 10, 12);
  SparseSample s;
  s.technique = 1;
  s.pT = 1.0;
  s.pB = 1.0;
  s.pEff = 0.0;
  s.f = Vec(1.0);
  poisoned.add(0, s);
  SparseCellSolution p = solveSparseCell(*poisoned.cell(0), SparseSolveParams{});
  expectAllFinite(p);
  EXPECT_FALSE(p.bInSystem);
  // Everything spoiled: invalid, all zero.
  SparseCellStatistics all = *poisoned.cell(0);
  for (auto& q : all.pairs) q.aTT = nan;
  SparseCellSolution none = solveSparseCell(all, SparseSolveParams{});
  EXPECT_FALSE(none.valid);
  expectAllZero(none);
}

TEST(SparseSolve, ASumBeyondTheBoundInvalidatesTheCell) {
  SparseStatisticsTable table = randomTable(3, 10, 13);
  SparseCellStatistics cell = *table.cell(0);
  for (double k : {1e32, 1e40}) {   // alpha_t ~ k: within float but beyond kSolveMaxAlphaSum; beyond float
    SparseCellStatistics big = cell;
    big.pairs[0].bT *= k;
    SparseCellSolution s = solveSparseCell(big, SparseSolveParams{});
    EXPECT_FALSE(s.valid) << k;
    expectAllZero(s);
  }
  // Two coefficients beyond float's range that cancel in the sum: the GPU cannot store them.
  SparseCellStatistics cancel;
  cancel.totals.samples = 1000;
  for (double sign : {1.0, -1.0}) {
    SparsePairStatistics p;
    p.technique = cancel.pairs.size();
    p.aTT = 1.0;
    p.bT = Vec(sign * 1e39);
    p.samples = 500;
    cancel.pairs.push_back(p);
  }
  SparseCellSolution s = solveSparseCell(cancel, SparseSolveParams{});
  EXPECT_FALSE(s.valid);
  expectAllZero(s);
}

TEST(SparseStatistics, AFullTableRefusesAndCountsNewPairsAndCells) {
  SparseStatisticsTable table(5);   // cell 0's totals and 4 pairs
  auto sample = [](uint32_t t) {
    SparseSample s;
    s.technique = t;
    s.pT = 1.0;
    s.pB = 0.5;
    s.pEff = 1.0;
    s.f = Vec(1.0);
    return s;
  };
  for (uint32_t t = 0; t < 4; ++t) EXPECT_EQ(table.add(0, sample(t)), SparseAddResult::Added);
  EXPECT_EQ(table.entries(), 5u);
  EXPECT_EQ(table.add(0, sample(2)), SparseAddResult::Added);   // existing pair: fine
  EXPECT_EQ(table.add(0, sample(7)), SparseAddResult::PairRefused);
  EXPECT_EQ(table.add(0, sample(7)), SparseAddResult::PairRefused);
  EXPECT_EQ(table.add(0, sample(8)), SparseAddResult::PairRefused);
  EXPECT_EQ(table.add(1, sample(0)), SparseAddResult::CellRefused);
  EXPECT_EQ(table.refusedPairs(), 2u);
  EXPECT_EQ(table.refusedPairSamples(), 3u);
  EXPECT_EQ(table.refusedCellSamples(), 1u);
  // The cell's totals hold every sample of the cell, refused pairs included.
  EXPECT_EQ(table.cell(0)->totals.samples, 8u);
  EXPECT_DOUBLE_EQ(table.cell(0)->totals.aBB, 8 * 0.25);
  EXPECT_EQ(table.cell(0)->pairs.size(), 4u);
  EXPECT_EQ(table.cell(1), nullptr);
  // Freeing entries elsewhere does not let a refused pair in late (it would miss samples).
  table.resetCell(0);
  EXPECT_EQ(table.entries(), 0u);
  EXPECT_EQ(table.add(1, sample(0)), SparseAddResult::Added);
  EXPECT_EQ(table.add(0, sample(7)), SparseAddResult::Added);   // cell 0 restarted: 7 fits now
  EXPECT_EQ(table.entries(), 4u);
}

TEST(SparseStatistics, ARefusedPairStaysRefusedWhenAnotherCellFreesEntries) {
  SparseStatisticsTable table(4);
  SparseSample s;
  s.pT = 1.0;
  s.pB = 0.5;
  s.f = Vec(1.0);
  s.technique = 0;
  table.add(0, s);   // cell 0 and (0, 0)
  table.add(1, s);   // cell 1 and (1, 0): full
  s.technique = 7;
  EXPECT_EQ(table.add(0, s), SparseAddResult::PairRefused);
  table.resetCell(1);   // two entries free
  EXPECT_EQ(table.entries(), 2u);
  EXPECT_EQ(table.add(0, s), SparseAddResult::PairRefused);   // (0, 7) would miss its first sample
  EXPECT_EQ(table.refusedPairs(), 1u);
  EXPECT_EQ(table.refusedPairSamples(), 2u);
  s.technique = 8;
  EXPECT_EQ(table.add(0, s), SparseAddResult::Added);   // a pair never refused may use the room
}

// Worker tables merged into one hold what one table fed every sample holds; with a small
// destination every sample is still accounted for: in a pair, refused to its cell's totals only,
// or refused whole.
TEST(SparseStatistics, MergingWorkerTablesKeepsEverySampleAccountedFor) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0.1, 2.0);
  std::vector<std::pair<uint32_t, SparseSample>> stream;
  for (int i = 0; i < 3000; ++i) {
    SparseSample s;
    s.technique = i % 4 == 0 ? kNoLightTechnique : uint32_t(rng() % 40);
    s.pT = s.technique == kNoLightTechnique ? 0.0 : u(rng);
    s.pB = u(rng);
    s.pEff = 0.1 * s.pT + s.pB;
    s.f = Vec(u(rng));
    stream.emplace_back(uint32_t(rng() % 6), s);
  }
  SparseStatisticsTable single(1000);
  std::vector<SparseStatisticsTable> workers(3, SparseStatisticsTable(1000));
  for (size_t i = 0; i < stream.size(); ++i) {
    single.add(stream[i].first, stream[i].second);
    workers[i % 3].add(stream[i].first, stream[i].second);
  }
  SparseStatisticsTable merged(1000);
  for (const auto& w : workers) merged.merge(w);
  ASSERT_EQ(merged.cells().size(), single.cells().size());
  EXPECT_EQ(merged.entries(), single.entries());
  for (const auto& [id, cell] : single.cells()) {
    const SparseCellStatistics& m = *merged.cell(id);
    EXPECT_EQ(m.totals.samples, cell.totals.samples);
    EXPECT_NEAR(m.totals.aBB, cell.totals.aBB, 1e-12 * cell.totals.aBB);
    SparseCellSolution a = solveSparseCell(cell, SparseSolveParams{}), b = solveSparseCell(m, SparseSolveParams{});
    ASSERT_EQ(a.valid, b.valid);
    EXPECT_LE(maxAbs(a.alphaSum - b.alphaSum), 1e-9 * (maxAbs(a.alphaSum) + 1.0));
  }
  // A destination with room for little: nothing is lost without being counted.
  SparseStatisticsTable small(30);
  for (const auto& w : workers) small.merge(w);
  EXPECT_EQ(small.entries(), 30u);
  EXPECT_GT(small.refusedPairs(), 0u);
  uint64_t inCells = 0, refusedToTotals = 0;
  for (const auto& [id, cell] : small.cells()) {
    uint64_t inPairs = 0, noTechnique = 0;
    for (const auto& p : cell.pairs) inPairs += p.samples;
    for (size_t i = 0; i < stream.size(); ++i)
      if (stream[i].first == id && stream[i].second.technique == kNoLightTechnique) noTechnique += 1;
    EXPECT_EQ(inPairs + cell.refusedPairSamples + noTechnique, cell.totals.samples) << id;
    inCells += cell.totals.samples;
    refusedToTotals += cell.refusedPairSamples;
  }
  EXPECT_EQ(refusedToTotals, small.refusedPairSamples());
  EXPECT_EQ(inCells + small.refusedCellSamples(), stream.size());
}

TEST(SparseSolve, TenThousandTechniquesInOneCellSolveFast) {
  const uint32_t T = 10000;
  SparseStatisticsTable table(T + 1);
  std::mt19937_64 rng(14);
  std::uniform_real_distribution<double> u(0.1, 2.0);
  for (uint32_t i = 0; i < 4 * T; ++i) {
    SparseSample s;
    s.technique = i % 4 == 3 ? kNoLightTechnique : uint32_t(rng() % T);
    s.pT = s.technique == kNoLightTechnique ? 0.0 : u(rng);
    s.pB = u(rng);
    s.pEff = 1e-4 * s.pT + s.pB;   // c_t ~ 1/T
    s.f = Vec(u(rng)) * s.pB;
    table.add(0, s);
  }
  const SparseCellStatistics& cell = *table.cell(0);
  EXPECT_GT(cell.pairs.size(), 9000u);
  TechniqueClusters clusters;
  clusters.clusterCount = 16;
  for (uint32_t t = 0; t < T; ++t) clusters.clusterOf.push_back(t % 16);
  auto start = std::chrono::steady_clock::now();
  SparseCellSolution s = solveSparseCell(cell, SparseSolveParams{}, &clusters);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("solve of %zu pairs: %.3f ms\n", cell.pairs.size(), seconds * 1e3);
  EXPECT_LT(seconds, 0.1);
  ASSERT_TRUE(s.valid);
  expectAllFinite(s);
  const double r = SparseSolveParams{}.ridge * meanDiagonal(cell);
  EXPECT_LE(relativeResidual(cell, s, r), 1e-9);
}

TEST(SparseSolve, ATechniqueReachedByASingleSample) {
  SparseStatisticsTable table = randomTable(5, 20, 15, 1);
  SparseSample s;   // one stray BSDF hit of a far, tiny triangle
  s.technique = 42;
  s.pT = 1e-3;
  s.pB = 1.0;
  s.pEff = 1e-5 * s.pT + s.pB;
  s.f = Vec(3.0);
  table.add(0, s);
  const SparseCellStatistics& cell = *table.cell(0);
  ASSERT_EQ(cell.pairs.back().technique, 42u);
  ASSERT_EQ(cell.pairs.back().samples, 1u);
  SparseCellSolution kept = solveSparseCell(cell, SparseSolveParams{});
  ASSERT_TRUE(kept.valid);
  EXPECT_TRUE(kept.inSystem.back());
  expectAllFinite(kept);
  // The ridge (relative to the mean diagonal) keeps its coefficient moderate: without it,
  // alpha_t = (b_t - A_tB alpha_B) / A_tt with A_tt ~ 1e-6 of the others.
  SparseSolveParams noRidge;
  noRidge.ridge = 0.0;
  SparseCellSolution unregularised = solveSparseCell(cell, noRidge);
  EXPECT_LT(maxAbs(kept.alpha.back()), 1e-2 * maxAbs(unregularised.alpha.back()));
  // With a minimum of 2 samples per technique it is dropped, as if the pair did not exist.
  SparseSolveParams two;
  two.minTechniqueSamples = 2;
  SparseCellStatistics without = cell;
  without.pairs.pop_back();
  SparseCellSolution dropped = solveSparseCell(cell, two);
  SparseCellSolution absent = solveSparseCell(without, two);
  EXPECT_FALSE(dropped.inSystem.back());
  EXPECT_EQ(maxAbs(dropped.alpha.back()), 0.0);
  EXPECT_EQ(dropped.alphaB, absent.alphaB);
  EXPECT_EQ(dropped.alphaSum, absent.alphaSum);
}

TEST(SparseSolve, ClusterSumsOfAlpha) {
  SparseStatisticsTable table = randomTable(6, 10, 16);
  TechniqueClusters clusters;
  clusters.clusterOf = {0, 0, 2, 1, 2, 2};
  clusters.clusterCount = 3;
  SparseCellSolution s = solveSparseCell(*table.cell(0), SparseSolveParams{}, &clusters);
  ASSERT_TRUE(s.valid);
  std::vector<Vec> expected(3, Vec(0.0));
  for (size_t i = 0; i < s.alpha.size(); ++i) expected[clusters.clusterOf[table.cell(0)->pairs[i].technique]] += s.alpha[i];
  ASSERT_EQ(s.clusterAlpha.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_LE(maxAbs(s.clusterAlpha[k] - expected[k]), 1e-12 * maxAbs(expected[k]));
  clusters.clusterOf = {0, 0, 2};   // techniques 3..5 unmapped: a caller's bug, not silence
  EXPECT_THROW(solveSparseCell(*table.cell(0), SparseSolveParams{}, &clusters), std::out_of_range);
}

// --- (d) convergence to the true optimum of a 1-D integral
//
// On [0, 1], three light "triangles" are the intervals [0, .2), [.2, .5), [.5, 1] (p_t uniform on
// each, selected with c = .5, .3, .2), BSDF sampling has p_B(z) = 2z, and f(z) = (1 + z^2,
// exp(-3z), 4 z (1 - z)). A and b are integrals of smooth functions on each interval, computed by
// Gauss-Legendre quadrature; the exact optimum is A^-1 b (dense solve). Samples are drawn as the
// renderer draws them: per vertex one light sample from the mixture and one BSDF sample.
struct Interval1D {
  double lo, hi, c;
};
const Interval1D kIntervals[3] = {{0.0, 0.2, 0.5}, {0.2, 0.5, 0.3}, {0.5, 1.0, 0.2}};

uint32_t techniqueOf(double z) { return z < 0.2 ? 0u : (z < 0.5 ? 1u : 2u); }
double pT1D(uint32_t t) { return 1.0 / (kIntervals[t].hi - kIntervals[t].lo); }
double pB1D(double z) { return 2.0 * z; }
double pEff1D(double z) {
  uint32_t t = techniqueOf(z);
  return kIntervals[t].c * pT1D(t) + pB1D(z);
}
Vec f1D(double z) { return Vec(1.0 + z * z, std::exp(-3.0 * z), 4.0 * z * (1.0 - z)); }

SparseSample sample1D(double z) {
  SparseSample s;
  s.technique = techniqueOf(z);
  s.pT = pT1D(s.technique);
  s.pB = pB1D(z);
  s.pEff = pEff1D(z);
  s.f = f1D(z);
  return s;
}

SparseCellStatistics exactStatistics1D() {
  // 5-point Gauss-Legendre on 2000 sub-intervals of each interval: far below the MC error.
  const double x[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
  const double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891,
                       0.2369268850561891};
  SparseCellStatistics cell;
  cell.totals.samples = 1u << 30;
  for (uint32_t t = 0; t < 3; ++t) {
    SparsePairStatistics p;
    p.technique = t;
    p.samples = 1u << 30;
    const int n = 2000;
    const double h = (kIntervals[t].hi - kIntervals[t].lo) / n;
    for (int i = 0; i < n; ++i)
      for (int q = 0; q < 5; ++q) {
        double z = kIntervals[t].lo + h * (i + 0.5 + 0.5 * x[q]);
        double wq = 0.5 * h * w[q] / pEff1D(z);
        double pt = pT1D(t), pb = pB1D(z);
        p.aTT += wq * pt * pt;
        p.aTB += wq * pt * pb;
        p.bT += wq * pt * f1D(z);
        cell.totals.aBB += wq * pb * pb;
        cell.totals.bB += wq * pb * f1D(z);
      }
    cell.pairs.push_back(p);
  }
  return cell;
}

SparseCellStatistics sampled1D(uint32_t vertices, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  SparseStatisticsTable table(8);
  for (uint32_t v = 0; v < vertices; ++v) {
    double pick = u(rng);
    uint32_t t = pick < 0.5 ? 0u : (pick < 0.8 ? 1u : 2u);
    double zL = kIntervals[t].lo + (kIntervals[t].hi - kIntervals[t].lo) * u(rng);
    double zB = std::sqrt(u(rng));   // inverts the cdf z^2 of p_B = 2z
    table.add(0, sample1D(zL));
    table.add(0, sample1D(zB));
  }
  // cells() order within pairs is the order of first sample: sort by technique for comparison.
  SparseCellStatistics cell = *table.cell(0);
  std::sort(cell.pairs.begin(), cell.pairs.end(),
            [](const SparsePairStatistics& a, const SparsePairStatistics& b) { return a.technique < b.technique; });
  return cell;
}

double alphaError(const SparseCellSolution& s, const DenseResult& exact) {
  double e = maxAbs(s.alphaB - exact.alphaB);
  for (int t = 0; t < 3; ++t) e = std::max(e, maxAbs(s.alpha[t] - exact.alpha[t]));
  return e;
}

TEST(SparseSolve, ConvergesToTheTrueOptimumOfA1DIntegral) {
  SparseCellStatistics exactCell = exactStatistics1D();
  DenseResult exact = denseSolve(exactCell, 0.0);
  // Sanity of the quadrature: the exact arrowhead solve of the exact statistics is A^-1 b.
  SparseSolveParams params;
  params.ridge = 0.0;
  SparseCellSolution fromExact = solveSparseCell(exactCell, params);
  ASSERT_TRUE(fromExact.valid);
  ASSERT_LE(alphaError(fromExact, exact), 1e-10);

  // Sample statistics are unbiased estimates of A and b: E[2 samples per vertex] / vertices.
  double previous = 0.0;
  for (uint32_t vertices : {4000u, 64000u, 1024000u}) {
    SparseCellStatistics cell = sampled1D(vertices, 99);
    ASSERT_EQ(cell.pairs.size(), 3u);
    SparseCellSolution s = solveSparseCell(cell, params);   // alpha is invariant to scaling A, b by 1/vertices
    ASSERT_TRUE(s.valid);
    double error = alphaError(s, exact);
    std::printf("%u vertices: max |alpha - alpha*| = %.2e\n", vertices, error);
    if (previous > 0.0) EXPECT_LT(error, 0.5 * previous) << vertices;   // 1/sqrt(N): 4x per 16x
    previous = error;
    if (vertices == 1024000u) EXPECT_LT(error, 0.02);
    if (vertices == 1024000u)
      for (int t = 0; t < 3; ++t) EXPECT_NEAR(cell.pairs[t].aTT / vertices, exactCell.pairs[t].aTT, 0.01 * exactCell.pairs[t].aTT);
  }
}

}  // namespace
}  // namespace mixtrace
