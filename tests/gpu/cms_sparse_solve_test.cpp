// The sparse per-triangle control-variate solve as the GPU runs it (shaders/cms/sparse_solve.comp
// through host/wavefront/passes/sparse_solve_pass, on the first Vulkan device: lavapipe here), held to the
// double-precision solveSparseCell (host/cms/sparse_solve.h) on the same float statistics: random
// cells of 1..200 pairs, the stability cases of the per-cluster solve (singular, zero rows,
// condition 1e12, 1 and 1e8 samples, scales 1e-8..1e8, NaN/Inf inputs), a full table, 10,000
// techniques in one cell, a technique reached by a single sample and the minimum technique
// samples; then the per-cluster solve's kSolveKeepControlVariate flag and the pair restart. Every
// output must be finite, and slots the solve must not write (empty slots, pairs of cells beyond
// cellCount, the other solution slots) keep their NaN sentinels.
#include <algorithm>
#include <array>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "wavefront/passes/solve_pass.h"
#include "wavefront/passes/sparse_solve_pass.h"
#include "cms/reference_solve.h"
#include "cms/sparse_solve.h"
#include "cms/sparse_statistics.h"
#include "shared/bindings.h"
#include "shared/cms_layouts.h"
#include "shared/cms_pair_layout.h"
#include "shared/cms_pair_state.h"
#include "shared/cms_state.h"
#include "vulkan/buffer.h"
#include "vulkan/context.h"
#include "vulkan/pass_timer.h"

using namespace mixtrace;
using Vec = glm::dvec3;

namespace {

const float kSentinel = std::nanf("");
const uint32_t kL = 2;   // clusters of the cell layout; the sparse solve reads only the BSDF row

uint32_t bitsOf(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}
double maxAbs(const Vec& v) { return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)}); }
bool finite3(const Vec& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// What the GPU holds: the statistics in float, so the double solve is given the same values.
SparseCellStatistics roundedToFloat(const SparseCellStatistics& in) {
  SparseCellStatistics out = in;
  auto f = [](double v) { return double(float(v)); };
  out.totals.aBB = f(in.totals.aBB);
  out.totals.bB = Vec(f(in.totals.bB.x), f(in.totals.bB.y), f(in.totals.bB.z));
  out.totals.samples = std::min<uint64_t>(in.totals.samples, 0xffffffffu);
  for (auto& p : out.pairs) {
    p.aTT = f(p.aTT);
    p.aTB = f(p.aTB);
    p.bT = Vec(f(p.bT.x), f(p.bT.y), f(p.bT.z));
    p.samples = std::min<uint64_t>(p.samples, 0xffffffffu);
  }
  return out;
}

// Cells 0..n-1 in a pair table, placed by the table's own hashing and probing (shared/
// cms_pair_layout.h), plus `ghost` cells whose pairs sit in the table but beyond cellCount.
struct Problem {
  std::vector<SparseCellStatistics> cells;    // float-rounded
  std::vector<SparseCellStatistics> ghosts;   // ids cells.size() + i
  uint32_t capacity = 0;
  SparseSolveSettings settings;
};

struct GpuResult {
  std::vector<uint64_t> keys;
  std::vector<float> pairStats, pairAlpha, solution, cellStats;
  std::vector<uint32_t> pairSamples, cellSamples;
  std::vector<std::vector<uint32_t>> slotOf;   // per cell (ghosts after the cells), per pair
  double gpuMs = -1.0;                         // timestamps, when the device has them
  std::string stageMs;                         // per stage
};

class CmsSparseSolve : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ctx_ = new VulkanContext(ContextOptions{"", true});
    solver_ = new GpuSparseSolver(*ctx_);
    cellSolver_ = new CellSolver(*ctx_);
  }
  static void TearDownTestSuite() {
    EXPECT_EQ(ctx_->validationErrors(), 0u);
    delete cellSolver_;
    delete solver_;
    delete ctx_;
  }

  // Uploads the problem. `solution` (optional) is the cell solution before the solve (else NaN).
  struct Uploaded {
    Buffer keys, pairStats, pairSamples, pairAlpha, occupied, cellStats, cellSamples, solution, defaults, techniques;
    std::vector<std::vector<uint32_t>> slotOf;
  };
  static Uploaded upload(const Problem& pr, const std::vector<float>* solution = nullptr) {
    const uint32_t cap = pr.capacity;
    std::vector<uint64_t> keys(cap, 0);
    // The occupied list (count, then slots), as the renderers' inserts fill it.
    std::vector<uint32_t> occupied(size_t(cap) + shared::kPairOccupiedFirst, 0);
    std::vector<float> pstats(size_t(cap) * shared::kPairStatsStride, kSentinel);
    std::vector<uint32_t> psamples(cap, 0xdeadbeefu);
    std::vector<float> palpha(size_t(cap) * shared::kPairAlphaStride, kSentinel);
    const uint32_t n = uint32_t(pr.cells.size()), total = n + uint32_t(pr.ghosts.size());
    std::vector<float> cstats(size_t(total) * shared::cellStatsStride(kL), 7.0f);
    std::vector<uint32_t> csamples(total, 0);
    // Each triangle technique's cluster and share, as its pairs state them (the renderers upload
    // them from the scene's light techniques).
    std::vector<shared::TechniqueClusterGpu> techniques(1, shared::TechniqueClusterGpu{0u, 1.0f});
    Uploaded u;
    u.slotOf.resize(total);
    for (uint32_t c = 0; c < total; ++c) {
      const SparseCellStatistics& cell = c < n ? pr.cells[c] : pr.ghosts[c - n];
      float* s = &cstats[size_t(c) * shared::cellStatsStride(kL)];
      s[shared::statsABB(kL)] = float(cell.totals.aBB);
      for (uint32_t ch = 0; ch < 3; ++ch) s[shared::statsBB(kL, ch)] = float(cell.totals.bB[ch]);
      csamples[c] = uint32_t(cell.totals.samples);
      for (const SparsePairStatistics& p : cell.pairs) {
        uint64_t key = shared::pairKey(c, p.technique);
        uint32_t slot = shared::hashPairKey(key) & (cap - 1), placed = shared::kNoPairSlot;
        for (uint32_t i = 0; i < cap; ++i) {   // the table's triangular probing, unbounded here
          if (keys[slot] == 0) {
            placed = slot;
            break;
          }
          slot = (slot + i + 1) & (cap - 1);
        }
        EXPECT_NE(placed, shared::kNoPairSlot) << "test table too small";
        keys[placed] = key;
        occupied[shared::kPairOccupiedFirst + occupied[shared::kPairOccupiedCount]++] = placed;
        pstats[shared::pairStatsAtt(placed)] = float(p.aTT);
        pstats[shared::pairStatsAtB(placed)] = float(p.aTB);
        for (uint32_t ch = 0; ch < 3; ++ch) pstats[shared::pairStatsBt(placed, ch)] = float(p.bT[ch]);
        psamples[placed] = uint32_t(p.samples);
        u.slotOf[c].push_back(placed);
        if (!shared::isRemainderTechnique(p.technique)) {
          if (techniques.size() <= p.technique) techniques.resize(p.technique + 1, shared::TechniqueClusterGpu{0u, 1.0f});
          techniques[p.technique] = shared::TechniqueClusterGpu{p.cluster, float(p.share)};
        }
      }
    }
    std::vector<float> sol(size_t(total) * shared::cellSolutionStride(kL), kSentinel);
    if (solution) std::copy(solution->begin(), solution->end(), sol.begin());
    u.keys = makeBuffer(*ctx_, keys, "pair keys");
    u.pairStats = makeBuffer(*ctx_, pstats, "pair stats");
    u.pairSamples = makeBuffer(*ctx_, psamples, "pair samples");
    u.pairAlpha = makeBuffer(*ctx_, palpha, "pair alpha");
    u.occupied = makeBuffer(*ctx_, occupied, "occupied pair slots");
    u.cellStats = makeBuffer(*ctx_, cstats, "cell stats");
    u.cellSamples = makeBuffer(*ctx_, csamples, "cell samples");
    u.solution = makeBuffer(*ctx_, sol, "cell solution");
    u.defaults = makeBuffer(*ctx_, std::vector<float>(kL, 1.0f / kL), "cluster defaults");
    u.techniques = makeBuffer(*ctx_, techniques, "technique clusters");
    return u;
  }

  static void bindSparse(Uploaded& u) {
    solver_->bind({{shared::BINDING_PAIR_KEYS, &u.keys},
                   {shared::BINDING_PAIR_STATS, &u.pairStats},
                   {shared::BINDING_PAIR_SAMPLES, &u.pairSamples},
                   {shared::BINDING_PAIR_ALPHA, &u.pairAlpha},
                   {shared::BINDING_PAIR_OCCUPIED, &u.occupied},
                   {shared::BINDING_CELL_STATS, &u.cellStats},
                   {shared::BINDING_CELL_SAMPLES, &u.cellSamples},
                   {shared::BINDING_CELL_SOLUTION, &u.solution},
                   {shared::BINDING_TECHNIQUE_CLUSTERS, &u.techniques}});
  }

  static GpuResult download(const Uploaded& u) {
    GpuResult r;
    r.keys = u.keys.downloadAll<uint64_t>();
    r.pairStats = u.pairStats.downloadAll<float>();
    r.pairSamples = u.pairSamples.downloadAll<uint32_t>();
    r.pairAlpha = u.pairAlpha.downloadAll<float>();
    r.solution = u.solution.downloadAll<float>();
    r.cellStats = u.cellStats.downloadAll<float>();
    r.cellSamples = u.cellSamples.downloadAll<uint32_t>();
    r.slotOf = u.slotOf;
    return r;
  }

  // The sparse solve of the problem on the GPU, timed with the renderer's pass timer.
  static GpuResult solve(const Problem& pr) {
    Uploaded u = upload(pr);
    solver_->reserve(uint32_t(pr.cells.size()));
    bindSparse(u);
    SparseSolveSettings s = pr.settings;
    s.cellCount = uint32_t(pr.cells.size());
    s.clusterCount = kL;
    s.pairCapacity = pr.capacity;
    PassTimer timer(*ctx_, 16);
    ctx_->submitAndWait([&](VkCommandBuffer cmd) {
      timer.begin(cmd);
      solver_->record(cmd, s, &timer);
    });
    timer.collect();
    GpuResult r = download(u);
    if (timer.enabled()) {
      r.gpuMs = 0.0;
      for (const auto& [label, ms] : timer.totalsMs()) {
        r.gpuMs += ms;
        r.stageMs += label + " " + std::to_string(ms) + " ms; ";
      }
    }
    return r;
  }

  static VulkanContext* ctx_;
  static GpuSparseSolver* solver_;
  static CellSolver* cellSolver_;
};

VulkanContext* CmsSparseSolve::ctx_ = nullptr;
GpuSparseSolver* CmsSparseSolve::solver_ = nullptr;
CellSolver* CmsSparseSolve::cellSolver_ = nullptr;

SparseSolveParams doubleParams(const SparseSolveSettings& s) {
  SparseSolveParams p;
  p.minCellSamples = s.minSamples;
  p.minTechniqueSamples = s.minTechniqueSamples;
  p.ridge = s.ridge;
  return p;
}

struct Comparison {
  double worstError = 0.0;   // the largest scaled error of a valid cell
  uint32_t valid = 0, invalid = 0;
};

// The GPU's solution of every cell against solveSparseCell's: validity equal; for a valid cell
// alpha (B and every pair) within `tolerance` in the Jacobi-scaled unknowns sqrt(A_ii) alpha_i,
// relative to the largest of them (the norm the solve works in, per-technique scales cancel), and
// the sum of alpha within tolerance of sum |alpha|; an invalid cell all zeros. Everything finite,
// and nothing written that the solve does not own.
Comparison compare(const Problem& pr, const GpuResult& r, double tolerance) {
  Comparison out;
  const uint32_t n = uint32_t(pr.cells.size());
  const SparseSolveParams params = doubleParams(pr.settings);
  const bool cv = (pr.settings.flags & shared::kSolveControlVariate) != 0;
  const uint32_t stride = shared::cellSolutionStride(kL);
  for (uint32_t c = 0; c < n; ++c) {
    const SparseCellStatistics& cell = pr.cells[c];
    SparseCellSolution ref = solveSparseCell(cell, params);
    const float* sol = &r.solution[size_t(c) * stride];
    const std::string where = "cell " + std::to_string(c) + " (" + std::to_string(cell.pairs.size()) + " pairs)";
    for (uint32_t i = 0; i < stride; ++i) {
      bool owned = i == shared::solutionValid(kL) || (i >= shared::solutionAlphaB(kL, 0) && i < shared::solutionAlphaB(kL, 0) + 3) ||
                   (i >= shared::solutionAlphaSum(kL, 0) && i < shared::solutionAlphaSum(kL, 0) + 3);
      if (owned) EXPECT_TRUE(std::isfinite(sol[i])) << where << ": solution slot " << i;
      else EXPECT_EQ(bitsOf(sol[i]), bitsOf(kSentinel)) << where << ": wrote solution slot " << i;
    }
    Vec gB(sol[shared::solutionAlphaB(kL, 0)], sol[shared::solutionAlphaB(kL, 1)], sol[shared::solutionAlphaB(kL, 2)]);
    Vec gSum(sol[shared::solutionAlphaSum(kL, 0)], sol[shared::solutionAlphaSum(kL, 1)],
             sol[shared::solutionAlphaSum(kL, 2)]);
    bool gValid = sol[shared::solutionValid(kL)] == 1.0f;
    EXPECT_TRUE(gValid || sol[shared::solutionValid(kL)] == 0.0f) << where;
    std::vector<Vec> gAlpha;
    for (uint32_t slot : r.slotOf[c]) {
      Vec a(r.pairAlpha[shared::pairAlphaIndex(slot, 0)], r.pairAlpha[shared::pairAlphaIndex(slot, 1)],
            r.pairAlpha[shared::pairAlphaIndex(slot, 2)]);
      EXPECT_TRUE(finite3(a)) << where << ": pair alpha at slot " << slot;
      gAlpha.push_back(a);
    }
    const bool refValid = ref.valid && cv;
    EXPECT_EQ(gValid, refValid) << where;
    if (!gValid) {
      ++out.invalid;
      EXPECT_EQ(maxAbs(gB), 0.0) << where;
      EXPECT_EQ(maxAbs(gSum), 0.0) << where;
      for (const Vec& a : gAlpha) EXPECT_EQ(maxAbs(a), 0.0) << where << ": an invalid cell's pair alpha";
      for (uint32_t slot : r.slotOf[c])
        EXPECT_EQ(r.pairAlpha[shared::pairSolvedIndex(slot)], 0.0f) << where << ": an invalid cell's pair is not solved";
      continue;
    }
    if (!refValid) continue;
    ++out.valid;
    double size = std::sqrt(cell.totals.aBB > 0 && std::isfinite(cell.totals.aBB) ? cell.totals.aBB : 0.0) * maxAbs(ref.alphaB);
    double err = std::sqrt(cell.totals.aBB > 0 && std::isfinite(cell.totals.aBB) ? cell.totals.aBB : 0.0) * maxAbs(gB - ref.alphaB);
    double absSum = maxAbs(ref.alphaB);
    for (size_t i = 0; i < cell.pairs.size(); ++i) {
      double d = cell.pairs[i].aTT;
      double s = std::isfinite(d) && d > 0.0 ? std::sqrt(d) : 0.0;
      size = std::max(size, s * maxAbs(ref.alpha[i]));
      err = std::max(err, s * maxAbs(gAlpha[i] - ref.alpha[i]));
      if (!ref.inSystem[i]) EXPECT_EQ(maxAbs(gAlpha[i]), 0.0) << where << ": dropped technique " << i;
      if (!shared::isRemainderTechnique(cell.pairs[i].technique))   // the render's choice of alpha_t or alpha_R
        EXPECT_EQ(r.pairAlpha[shared::pairSolvedIndex(r.slotOf[c][i])], ref.inSystem[i] ? 1.0f : 0.0f)
            << where << ": solved flag of technique " << i;
      absSum += maxAbs(ref.alpha[i]);
    }
    double rel = size > 0.0 ? err / size : err;
    EXPECT_LE(rel, tolerance) << where;
    EXPECT_LE(maxAbs(gSum - ref.alphaSum), tolerance * absSum + 1e-30) << where;
    out.worstError = std::max(out.worstError, rel);
  }
  // Empty slots and the pairs of cells beyond cellCount: never written.
  std::vector<bool> solved(r.keys.size(), false);
  for (uint32_t c = 0; c < n; ++c)
    for (uint32_t slot : r.slotOf[c]) solved[slot] = true;
  size_t stray = 0;
  for (size_t slot = 0; slot < r.keys.size(); ++slot)
    if (!solved[slot])
      for (uint32_t ch = 0; ch < 3; ++ch) stray += bitsOf(r.pairAlpha[shared::pairAlphaIndex(uint32_t(slot), ch)]) != bitsOf(kSentinel);
  EXPECT_EQ(stray, 0u) << "alpha written to slots of no solved cell";
  return out;
}

// Samples as the renderer gathers them: light samples over the cell's techniques (some blocked:
// p_B = 0), BSDF samples hitting one of them or nothing; `perTechnique` samples on average.
void gatherRandomCell(SparseStatisticsTable& table, uint32_t cell, uint32_t techniques, uint32_t perTechnique,
                      std::mt19937_64& rng, uint32_t techniqueBase = 0) {
  std::uniform_real_distribution<double> u(0.1, 2.0);
  const uint32_t n = techniques * perTechnique + 70;
  for (uint32_t i = 0; i < n; ++i) {
    SparseSample s;
    s.technique = i % 5 == 4 ? kNoLightTechnique : techniqueBase + uint32_t(rng() % techniques);
    s.pT = s.technique == kNoLightTechnique ? 0.0 : u(rng);
    s.pB = i % 3 == 0 ? 0.0 : u(rng);
    s.pEff = 0.3 * s.pT + s.pB + (s.pT == 0 && s.pB == 0 ? 1.0 : 0.0);
    s.f = Vec(u(rng), u(rng), u(rng)) * (s.pT + s.pB) * (u(rng) - 0.5);
    s.weight = u(rng);
    table.add(cell, s);
  }
}

SparseCellStatistics randomCell(uint32_t techniques, uint32_t perTechnique, uint32_t seed) {
  std::mt19937_64 rng(seed);
  SparseStatisticsTable table(techniques + 1);
  gatherRandomCell(table, 0, techniques, perTechnique, rng);
  return roundedToFloat(*table.cell(0));
}

uint32_t pairsOf(const Problem& pr) {
  uint32_t n = 0;
  for (const auto& c : pr.cells) n += uint32_t(c.pairs.size());
  for (const auto& c : pr.ghosts) n += uint32_t(c.pairs.size());
  return n;
}

SparseSolveSettings cvSettings(uint32_t minSamples = 64, uint32_t minTechniqueSamples = 1, float ridge = 1e-3f) {
  SparseSolveSettings s;
  s.minSamples = minSamples;
  s.minTechniqueSamples = minTechniqueSamples;
  s.ridge = ridge;
  s.flags = shared::kSolveControlVariate;
  return s;
}

// A hand-made cell: B row and pairs (A_tt, A_tB, b_t), every pair `samples` samples.
SparseCellStatistics handCell(double aBB, Vec bB, uint64_t samples, std::vector<std::array<double, 5>> pairs,
                              uint64_t pairSamples = 100) {
  SparseCellStatistics c;
  c.totals.aBB = aBB;
  c.totals.bB = bB;
  c.totals.samples = samples;
  uint32_t t = 0;
  for (const auto& p : pairs) {
    SparsePairStatistics s;
    s.technique = t++;
    s.aTT = p[0];
    s.aTB = p[1];
    s.bT = Vec(p[2], p[3], p[4]);
    s.samples = pairSamples;
    c.pairs.push_back(s);
  }
  return roundedToFloat(c);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Agreement with the double solve

TEST_F(CmsSparseSolve, RandomCellsOf1To200PairsMatchTheDoubleSolve) {
  std::mt19937_64 rng(13);
  SparseStatisticsTable table(1u << 20);
  Problem pr;
  const uint32_t cells = 400;
  for (uint32_t c = 0; c < cells; ++c) {
    uint32_t T = 1 + uint32_t(rng() % 200);
    gatherRandomCell(table, c, T, 1 + uint32_t(rng() % 12), rng, uint32_t(rng() % 5000));
  }
  for (uint32_t c = 0; c < cells; ++c) pr.cells.push_back(roundedToFloat(*table.cell(c)));
  pr.ghosts.push_back(randomCell(30, 5, 99));   // in the table, beyond cellCount: untouched
  pr.capacity = shared::pairTableCapacityFor(pairsOf(pr));
  pr.settings = cvSettings(64, 2);
  GpuResult r = solve(pr);
  Comparison c = compare(pr, r, 2e-4);
  EXPECT_GT(c.valid, cells * 3 / 4);
  std::printf("random cells: %u valid, %u invalid, worst scaled error %.3g\n", c.valid, c.invalid, c.worstError);
}

// Remainder techniques (the table-full fallback, docs/estimator.md §4): cells whose triangles of
// kL clusters carry shares, plus one remainder pair per cluster, some triangle pairs dropped by
// the minimum sample count. The GPU's sum of alpha (alpha_R weighted by P_R = 1 - the shares of
// the solved pairs of its cluster) and its solved flags agree with the double solve's.
TEST_F(CmsSparseSolve, RemainderTechniquesGetTheMassOfTheirClustersUnsolvedTriangles) {
  std::mt19937_64 rng(29);
  SparseStatisticsTable table(1u << 20);
  Problem pr;
  const uint32_t cells = 200, trianglesPerCluster = 40;
  for (uint32_t c = 0; c < cells; ++c) {
    gatherRandomCell(table, c, kL * trianglesPerCluster, 1 + uint32_t(rng() % 10), rng);
    // Remainder samples: density p_k on the cluster's triangles that lost their pair.
    for (uint32_t k = 0; k < kL; ++k) {
      std::uniform_real_distribution<double> u(0.1, 2.0);
      for (uint32_t i = 0; i < 20 + rng() % 40; ++i) {
        SparseSample s;
        s.technique = shared::remainderTechnique(k);
        s.pT = u(rng);
        s.pB = i % 3 == 0 ? 0.0 : u(rng);
        s.pEff = 0.3 * s.pT + s.pB;
        s.f = Vec(u(rng), u(rng), u(rng)) * (s.pT + s.pB) * (u(rng) - 0.3);
        table.add(c, s);
      }
    }
  }
  // Shares: triangle t of cluster t % kL holds a random share of its cluster, normalised so that
  // the cluster's shares sum to 1 (P_R then lies in [0, 1] without the clamp).
  std::vector<double> share(kL * trianglesPerCluster);
  std::vector<double> clusterSum(kL, 0.0);
  for (uint32_t t = 0; t < share.size(); ++t) clusterSum[t % kL] += share[t] = 0.2 + double(rng() % 100) / 100.0;
  for (uint32_t t = 0; t < share.size(); ++t) share[t] = double(float(share[t] / clusterSum[t % kL]));
  uint32_t remainders = 0;
  for (uint32_t c = 0; c < cells; ++c) {
    SparseCellStatistics cell = roundedToFloat(*table.cell(c));
    for (SparsePairStatistics& p : cell.pairs) {
      if (shared::isRemainderTechnique(p.technique)) {
        ++remainders;
        continue;
      }
      p.cluster = p.technique % kL;
      p.share = share[p.technique];
    }
    pr.cells.push_back(cell);
  }
  pr.capacity = shared::pairTableCapacityFor(pairsOf(pr));
  pr.settings = cvSettings(64, 4);   // pairs of 1..3 samples are dropped: their mass is the remainder's
  GpuResult r = solve(pr);
  Comparison c = compare(pr, r, 2e-4);
  EXPECT_EQ(remainders, cells * kL);
  EXPECT_GT(c.valid, cells * 3 / 4);
  // The remainders' masses matter: without them the sums would differ by alpha_R (1 - P_R).
  double largestRemainderTerm = 0.0;
  uint32_t partial = 0;   // remainders whose cluster has solved triangles in the cell
  const SparseSolveParams params = doubleParams(pr.settings);
  for (const SparseCellStatistics& cell : pr.cells) {
    SparseCellSolution ref = solveSparseCell(cell, params);
    for (size_t i = 0; ref.valid && i < cell.pairs.size(); ++i)
      if (shared::isRemainderTechnique(cell.pairs[i].technique)) {
        EXPECT_GE(ref.mass[i], 0.0);
        EXPECT_LE(ref.mass[i], 1.0);
        partial += ref.mass[i] < 1.0;
        largestRemainderTerm = std::max(largestRemainderTerm, maxAbs(ref.alpha[i]) * (1.0 - ref.mass[i]));
      }
  }
  EXPECT_GT(largestRemainderTerm, 1e-3);
  EXPECT_GT(partial, remainders / 2);
  std::printf("remainder cells: %u valid, %u invalid, worst scaled error %.3g\n", c.valid, c.invalid, c.worstError);
}

TEST_F(CmsSparseSolve, WithoutTheControlVariateFlagEveryCellIsInvalidAndEveryAlphaZero) {
  Problem pr;
  for (uint32_t c = 0; c < 20; ++c) pr.cells.push_back(randomCell(1 + c * 7, 6, 200 + c));
  pr.capacity = shared::pairTableCapacityFor(pairsOf(pr));
  pr.settings = cvSettings();
  pr.settings.flags = 0;
  Comparison c = compare(pr, solve(pr), 2e-4);
  EXPECT_EQ(c.valid, 0u);
  EXPECT_EQ(c.invalid, 20u);
}

// ---------------------------------------------------------------------------------------------
// Stability (the per-cluster solve's cases, carried over)

TEST_F(CmsSparseSolve, StabilityCasesMatchTheDoubleSolveAndStayFinite) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  Problem pr;
  auto& c = pr.cells;
  // Singular: B identical to technique 0 (A_tB^2 = A_tt A_BB): the pivot drops B.
  c.push_back(handCell(4.0, Vec(2, 1, 0.5), 1000, {{4.0, 4.0, 2, 1, 0.5}, {1.0, 0.2, 0.3, 0.1, -0.2}}));
  // B a combination of the light techniques (sum of l_t^2 = 1).
  c.push_back(handCell(2.0, Vec(1, 1, 1), 1000, {{1.0, 1.0, 0.5, 0.5, 0.5}, {1.0, 1.0, 0.5, 0.5, 0.5}}));
  // Zero rows: a technique with no samples' worth of statistics, and an all-zero cell.
  c.push_back(handCell(3.0, Vec(1, 2, 3), 1000, {{0.0, 0.0, 0, 0, 0}, {2.0, 0.5, 1, 1, 1}}, 0));
  c.push_back(handCell(3.0, Vec(1, 2, 3), 1000, {{0.0, 0.0, 0, 0, 0}, {2.0, 0.5, 1, 1, 1}}));
  c.push_back(handCell(0.0, Vec(0.0), 1000, {{0.0, 0.0, 0, 0, 0}, {0.0, 0.0, 0, 0, 0}}));
  // Condition 1e12: diagonals from 1e-6 to 1e6 (Jacobi scaling removes it).
  c.push_back(handCell(1.0, Vec(0.3, 0.2, 0.1), 1000,
                       {{1e-6, 1e-7, 1e-6, 2e-6, 3e-6}, {1e6, 1e2, 1e6, -1e6, 5e5}, {1.0, 0.1, 0.5, 0.4, 0.3}}));
  // 1 sample (below and at the minimum) and 1e8 samples.
  c.push_back(randomCell(1, 0, 7));
  c.back().totals.samples = 1;
  c.push_back(randomCell(3, 10, 8));
  c.back().totals.samples = 100000000;
  // Scales 1e-8 .. 1e8 of A and b together (alpha unchanged) and of b alone.
  for (double s : {1e-8, 1e-4, 1.0, 1e4, 1e8}) {
    SparseCellStatistics base = randomCell(20, 8, 11);
    SparseCellStatistics scaled = base;
    scaled.totals.aBB *= s;
    scaled.totals.bB *= s;
    for (auto& p : scaled.pairs) {
      p.aTT *= s;
      p.aTB *= s;
      p.bT *= s;
    }
    c.push_back(roundedToFloat(scaled));
    SparseCellStatistics bOnly = base;
    bOnly.totals.bB *= s;
    for (auto& p : bOnly.pairs) p.bT *= s;
    c.push_back(roundedToFloat(bOnly));
  }
  // NaN/Inf in a pair (dropped), in the BSDF row (B dropped), everywhere (invalid).
  for (double bad : {nan, inf, -inf}) {
    c.push_back(handCell(2.0, Vec(1, 1, 1), 1000, {{bad, 0.5, 1, 1, 1}, {2.0, 0.5, 1, 1, 1}}));
    c.push_back(handCell(2.0, Vec(1, 1, 1), 1000, {{1.0, bad, 1, 1, 1}, {2.0, 0.5, 1, 1, 1}}));
    c.push_back(handCell(2.0, Vec(1, 1, 1), 1000, {{1.0, 0.5, 1, bad, 1}, {2.0, 0.5, 1, 1, 1}}));
    c.push_back(handCell(bad, Vec(1, 1, 1), 1000, {{1.0, 0.5, 1, 1, 1}, {2.0, 0.5, 1, 1, 1}}));
    c.push_back(handCell(2.0, Vec(1, bad, 1), 1000, {{1.0, 0.5, 1, 1, 1}, {2.0, 0.5, 1, 1, 1}}));
    c.push_back(handCell(bad, Vec(bad), 1000, {{bad, bad, bad, bad, bad}}));
  }
  // Extremes: diagonals at the smallest normal float and near FLT_MAX, alpha beyond float range,
  // a sum of alpha beyond kSolveMaxAlphaSum.
  c.push_back(handCell(1.2e-38, Vec(1e-38), 1000, {{1.2e-38, 1e-39, 1e-38, 1e-38, 1e-38}, {3e38, 1e38, 3e38, 3e38, 3e38}}));
  c.push_back(handCell(1.0, Vec(1.0), 1000, {{2e-38, 0.0, 3e38, 3e38, 3e38}}));
  c.push_back(handCell(1.0, Vec(1.0), 1000, {{1e-10, 0.0, 1e21, 1e21, 1e21}}));
  // The largest diagonal near FLT_MAX (its reciprocal is denormal): the ridge still counts it.
  c.push_back(handCell(1.0, Vec(1.0), 1000, {{3e38, 1e19, 3e38, 1e38, 2e38}, {1.0, 0.1, 0.5, 0.5, 0.5}}));
  c.push_back(handCell(3e38, Vec(3e38), 1000, {{3e38, 1e38, 1e38, 1e38, 1e38}, {2e38, 1e37, 1e38, 2e38, 3e38}}));
  pr.capacity = shared::pairTableCapacityFor(pairsOf(pr));
  pr.settings = cvSettings(2);
  Comparison cmp = compare(pr, solve(pr), 2e-4);
  std::printf("stability: %u valid, %u invalid, worst scaled error %.3g\n", cmp.valid, cmp.invalid, cmp.worstError);
  EXPECT_GT(cmp.valid, 20u);
  EXPECT_GT(cmp.invalid, 4u);
}

TEST_F(CmsSparseSolve, AFullTableIsSolvedWhole) {
  // 64 cells x 64 pairs in 4096 slots: every slot occupied, long probe chains.
  Problem pr;
  for (uint32_t c = 0; c < 64; ++c) pr.cells.push_back(randomCell(64, 30, 300 + c));
  for (auto& cell : pr.cells) ASSERT_EQ(cell.pairs.size(), 64u);
  pr.capacity = 4096;
  ASSERT_EQ(pairsOf(pr), pr.capacity);
  pr.settings = cvSettings();
  Comparison c = compare(pr, solve(pr), 2e-4);
  EXPECT_EQ(c.valid, 64u);
}

TEST_F(CmsSparseSolve, TenThousandTechniquesInOneCell) {
  Problem pr;
  pr.cells.push_back(randomCell(10000, 12, 17));
  ASSERT_EQ(pr.cells[0].pairs.size(), 10000u);
  pr.cells.push_back(randomCell(5, 10, 18));   // a small neighbour keeps its own solution
  pr.capacity = shared::pairTableCapacityFor(pairsOf(pr));
  pr.settings = cvSettings();
  GpuResult r = solve(pr);
  Comparison c = compare(pr, r, 1e-3);
  EXPECT_EQ(c.valid, 2u);
  std::printf("10,000 techniques: worst scaled error %.3g, sparse solve %.3f ms (GPU timestamps, %u slots)\n",
              c.worstError, r.gpuMs, pr.capacity);
  std::printf("  %s\n", r.stageMs.c_str());
}

TEST_F(CmsSparseSolve, ATechniqueReachedByASingleSampleAndTheMinimumTechniqueSamples) {
  // Technique 7 gets one light sample on top of a well-sampled cell.
  std::mt19937_64 rng(5);
  SparseStatisticsTable table(64);
  gatherRandomCell(table, 0, 6, 20, rng);
  SparseSample s;
  s.technique = 7;
  s.pT = 1.5;
  s.pB = 0.2;
  s.pEff = 0.3 * 1.5 + 0.2;
  s.f = Vec(0.4, 0.5, 0.6);
  ASSERT_EQ(table.add(0, s), SparseAddResult::Added);
  SparseCellStatistics cell = roundedToFloat(*table.cell(0));
  size_t single = 0;
  for (size_t i = 0; i < cell.pairs.size(); ++i)
    if (cell.pairs[i].technique == 7) single = i;
  ASSERT_EQ(cell.pairs[single].samples, 1u);
  for (uint32_t minTechnique : {1u, 2u}) {
    Problem pr;
    pr.cells = {cell};
    pr.capacity = 16;
    pr.settings = cvSettings(64, minTechnique);
    GpuResult r = solve(pr);
    compare(pr, r, 2e-4);
    uint32_t slot = r.slotOf[0][single];
    float a = r.pairAlpha[shared::pairAlphaIndex(slot, 0)];
    if (minTechnique == 1) EXPECT_NE(a, 0.0f) << "a single sample still takes part";
    else EXPECT_EQ(a, 0.0f) << "below the minimum technique samples: dropped";
  }
}

// ---------------------------------------------------------------------------------------------
// The per-cluster solve's kSolveKeepControlVariate and the pair restart

TEST_F(CmsSparseSolve, KeepControlVariateLeavesTheSparseSolutionAndAgreesWithTheReference) {
  // Per-cluster statistics of L = 2 for cells with a learned selection; the solution's alpha_B,
  // valid and sum slots hold markers (as the sparse solve wrote them) that must survive.
  const uint32_t L = kL, cells = 40, statsStride = shared::cellStatsStride(L), solStride = shared::cellSolutionStride(L);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.1f, 2.0f);
  std::vector<float> stats(size_t(cells) * statsStride), solution(size_t(cells) * solStride, kSentinel);
  std::vector<uint32_t> samples(cells);
  for (uint32_t c = 0; c < cells; ++c) {
    float* s = &stats[size_t(c) * statsStride];
    for (uint32_t k = 0; k < L; ++k) {
      s[shared::statsAkk(L, k)] = 2.0f * u(rng);
      s[shared::statsAkB(L, k)] = 0.5f * u(rng);
      for (uint32_t ch = 0; ch < 3; ++ch) s[shared::statsBk(L, k, ch)] = u(rng) * (c % 3 == 0 ? -1.0f : 1.0f);
    }
    s[shared::statsABB(L)] = 2.0f * u(rng);
    for (uint32_t ch = 0; ch < 3; ++ch) s[shared::statsBB(L, ch)] = u(rng);
    samples[c] = c % 4 == 0 ? 3u : 500u;   // some below the minimum
    float* o = &solution[size_t(c) * solStride];
    for (uint32_t k = 0; k < L; ++k) o[shared::solutionSelect(L, k)] = c % 2 ? 0.5f : (k == 0 ? 0.9f : 0.1f);
    for (uint32_t ch = 0; ch < 3; ++ch) {
      o[shared::solutionAlphaB(L, ch)] = 10.0f + c + ch;
      o[shared::solutionAlphaSum(L, ch)] = -20.0f - c - ch;
    }
    o[shared::solutionValid(L)] = c % 5 == 0 ? 0.0f : 1.0f;
  }
  std::vector<float> defaults = {0.25f, 0.75f};
  for (uint32_t flags : {shared::kSolveKeepControlVariate | shared::kSolveLearnSelection,
                         shared::kSolveKeepControlVariate | shared::kSolveLearnSelection | shared::kSolveControlVariate,
                         shared::kSolveKeepControlVariate}) {
    shared::SolveParams p{};
    p.cellCount = cells;
    p.clusterCount = L;
    p.minSamples = 64;
    p.flags = flags;
    p.ridge = 1e-3f;
    p.defensive = 0.1f;
    Buffer statsBuf = makeBuffer(*ctx_, stats, "cell stats");
    Buffer samplesBuf = makeBuffer(*ctx_, samples, "cell samples");
    Buffer solBuf = makeBuffer(*ctx_, solution, "cell solution");
    Buffer defBuf = makeBuffer(*ctx_, defaults, "cluster defaults");
    cellSolver_->bind({{shared::BINDING_CELL_STATS, &statsBuf},
                       {shared::BINDING_CELL_SAMPLES, &samplesBuf},
                       {shared::BINDING_CELL_SOLUTION, &solBuf},
                       {shared::BINDING_CLUSTER_DEFAULTS, &defBuf}});
    ctx_->submitAndWait([&](VkCommandBuffer cmd) { cellSolver_->record(cmd, p); });
    std::vector<float> out = solBuf.downloadAll<float>();
    std::vector<uint32_t> samplesAfter = samplesBuf.downloadAll<uint32_t>();
    uint32_t restarted = 0;
    for (uint32_t c = 0; c < cells; ++c) {
      const float* before = &solution[size_t(c) * solStride];
      const float* o = &out[size_t(c) * solStride];
      CellSolution ref = solveCellReference(&stats[size_t(c) * statsStride], samples[c], L, p, defaults.data(),
                                            before + shared::solutionSelect(L, 0));
      EXPECT_TRUE(ref.keepControlVariate);
      EXPECT_FALSE(ref.valid);
      for (uint32_t ch = 0; ch < 3; ++ch) {
        EXPECT_EQ(bitsOf(o[shared::solutionAlphaB(L, ch)]), bitsOf(before[shared::solutionAlphaB(L, ch)])) << c;
        EXPECT_EQ(bitsOf(o[shared::solutionAlphaSum(L, ch)]), bitsOf(before[shared::solutionAlphaSum(L, ch)])) << c;
        EXPECT_EQ(maxAbs(ref.alphaB), 0.0);
      }
      EXPECT_EQ(bitsOf(o[shared::solutionValid(L)]), bitsOf(before[shared::solutionValid(L)])) << c;
      for (uint32_t k = 0; k < L; ++k) {
        EXPECT_NEAR(o[shared::solutionSelect(L, k)], ref.select[k], 1e-5) << "cell " << c << " cluster " << k;
        EXPECT_EQ(o[shared::solutionAlpha(L, k, 0)], 0.0f) << "alpha_k end as without the control variate";
      }
      EXPECT_EQ(samplesAfter[c] == 0u, ref.resetStatistics) << c;
      restarted += ref.resetStatistics;
    }
    if (flags & shared::kSolveLearnSelection) EXPECT_GT(restarted, 0u);
  }
}

TEST_F(CmsSparseSolve, PairRestartZeroesExactlyThePairsOfCellsWithoutSamples) {
  Problem pr;
  for (uint32_t c = 0; c < 30; ++c) {
    pr.cells.push_back(randomCell(1 + c * 3, 5, 400 + c));
    if (c % 3 == 1) pr.cells.back().totals.samples = 0;   // restarted by the cluster solve
  }
  pr.ghosts.push_back(randomCell(10, 5, 77));
  pr.ghosts.back().totals.samples = 0;   // beyond cellCount: untouched even with 0 samples
  pr.capacity = shared::pairTableCapacityFor(pairsOf(pr));
  pr.settings = cvSettings();
  Uploaded u = upload(pr);
  solver_->reserve(uint32_t(pr.cells.size()));
  bindSparse(u);
  SparseSolveSettings s = pr.settings;
  s.cellCount = uint32_t(pr.cells.size());
  s.clusterCount = kL;
  s.pairCapacity = pr.capacity;
  GpuResult before = download(u);
  ctx_->submitAndWait([&](VkCommandBuffer cmd) { solver_->recordRestart(cmd, s); });
  GpuResult after = download(u);
  EXPECT_EQ(after.keys, before.keys) << "keys stay";
  std::vector<int> cellOfSlot(pr.capacity, -1);
  for (size_t c = 0; c < u.slotOf.size(); ++c)
    for (uint32_t slot : u.slotOf[c]) cellOfSlot[slot] = int(c);
  size_t zeroed = 0;
  for (uint32_t slot = 0; slot < pr.capacity; ++slot) {
    int c = cellOfSlot[slot];
    bool restart = c >= 0 && c < int(pr.cells.size()) && pr.cells[c].totals.samples == 0;
    for (uint32_t i = 0; i < shared::kPairStatsStride; ++i) {
      float a = after.pairStats[shared::kPairStatsStride * slot + i];
      if (restart) EXPECT_EQ(bitsOf(a), 0u) << "slot " << slot;
      else EXPECT_EQ(bitsOf(a), bitsOf(before.pairStats[shared::kPairStatsStride * slot + i])) << "slot " << slot;
    }
    if (restart) EXPECT_EQ(after.pairSamples[slot], 0u);
    else EXPECT_EQ(after.pairSamples[slot], before.pairSamples[slot]);
    zeroed += restart;
  }
  EXPECT_GT(zeroed, 50u);
}

// ---------------------------------------------------------------------------------------------
// Cost (printed for the report; asserted only to agree)

TEST_F(CmsSparseSolve, TimingOf4096CellsOf50Pairs) {
  std::mt19937_64 rng(21);
  SparseStatisticsTable table(1u << 20);
  Problem pr;
  const uint32_t cells = 4096;
  for (uint32_t c = 0; c < cells; ++c) gatherRandomCell(table, c, 50, 10, rng, uint32_t(rng() % 10000));
  for (uint32_t c = 0; c < cells; ++c) pr.cells.push_back(roundedToFloat(*table.cell(c)));
  pr.capacity = shared::pairTableCapacityFor(pairsOf(pr));
  pr.settings = cvSettings();
  GpuResult r = solve(pr);
  Comparison c = compare(pr, r, 2e-4);
  EXPECT_GT(c.valid, cells * 3 / 4);
  std::printf("4096 cells, %u pairs, %u slots: sparse solve %.3f ms (GPU timestamps), worst scaled error %.3g\n  %s\n",
              pairsOf(pr), pr.capacity, r.gpuMs, c.worstError, r.stageMs.c_str());
}
