// The CMS per-cell solve as the GPU runs it (shaders/cms/solve.comp through host/wavefront/passes/solve_pass,
// on whatever Vulkan device is first: lavapipe here) fed synthetic cell statistics, held to the
// independent double-precision solve (host/cms/reference_solve) and, where the exact answer is
// known, to that: well-conditioned systems from simulated samples, singular, nearly singular and
// one-sample systems, unreached clusters, counts past 2^24, entries over 16 orders of magnitude,
// NaN/Inf entries, L = 0, 1 and 32, the minimum-sample rule, learned selection and every flag
// combination. Every output of every cell must be finite; every dispatch also checks that exactly
// the cells asked for are written (sentinels before the solve and past the last cell).
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cms/cms_setup.h"
#include "wavefront/passes/solve_pass.h"
#include "cms/method_lights.h"
#include "cms/reference_solve.h"
#include "wavefront/wavefront_renderer.h"
#include "gltf/gltf_loader.h"
#include "scene/prepared_scene.h"
#include "shared/bindings.h"
#include "shared/cms_layouts.h"
#include "shared/layouts.h"
#include "util/error.h"
#include "vulkan/buffer.h"
#include "vulkan/context.h"
#include "vulkan/pipeline.h"

// The solve pass's own source, compiled as C++ over plain arrays (shared dialect): checks it stays
// valid C++ and lets it be compared with its GPU run.
namespace cpu_float_solve {
float* gStats = nullptr;      // the solve resets a cell's statistics when its selection changes
uint32_t* gSamples = nullptr;
float* gSolution = nullptr;
const float* gDefaults = nullptr;
}  // namespace cpu_float_solve
#define CELL_STATS(i) (::cpu_float_solve::gStats[i])
#define CELL_SAMPLES(i) (::cpu_float_solve::gSamples[i])
#define CELL_SOLUTION(i) (::cpu_float_solve::gSolution[i])
#define CLUSTER_DEFAULT(i) (::cpu_float_solve::gDefaults[i])
#include "shared/cms_solve.h"

using namespace mixtrace;
using shared::SolveParams;

namespace {

const uint32_t kBoth = shared::kSolveControlVariate | shared::kSolveLearnSelection;

SolveParams makeParams(uint32_t L, uint32_t flags = kBoth, float ridge = 0.0f, uint32_t minSamples = 0,
                       float defensive = 0.1f) {
  SolveParams p{};
  p.clusterCount = L;
  p.minSamples = minSamples;
  p.flags = flags;
  p.ridge = ridge;
  p.defensive = defensive;
  return p;
}

// Cells that share a cluster count (one dispatch).
struct Batch {
  uint32_t L;
  std::vector<float> stats;
  std::vector<uint32_t> samples;
  std::vector<float> defaults;

  explicit Batch(uint32_t clusters) : L(clusters), defaults(clusters, clusters ? 1.0f / clusters : 0.0f) {}
  uint32_t cells() const { return uint32_t(samples.size()); }
  uint32_t stride() const { return shared::cellStatsStride(L); }
  const float* cell(uint32_t i) const { return &stats[size_t(i) * stride()]; }
  void add(const std::vector<float>& cellStats, uint32_t sampleCount) {
    stats.insert(stats.end(), cellStats.begin(), cellStats.end());
    samples.push_back(sampleCount);
  }
};

// The solution of one cell as the GPU wrote it.
struct GpuCell {
  const float* s;
  uint32_t L;
  glm::dvec3 alpha(uint32_t k) const { return read3(shared::solutionAlpha(L, k, 0)); }
  glm::dvec3 alphaB() const { return read3(shared::solutionAlphaB(L, 0)); }
  double select(uint32_t k) const { return s[shared::solutionSelect(L, k)]; }
  float valid() const { return s[shared::solutionValid(L)]; }
  glm::dvec3 read3(uint32_t i) const { return glm::dvec3(s[i], s[i + 1], s[i + 2]); }
};

uint32_t bitsOf(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

const float kSentinel = std::nanf("");   // every solution slot starts as NaN: unwritten slots show

// One Vulkan context, descriptor set and solver for the whole suite (validation on).
class CmsSolve : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ctx_ = new VulkanContext(ContextOptions{"", true});
    solver_ = new CellSolver(*ctx_);
  }
  static void TearDownTestSuite() {
    EXPECT_EQ(ctx_->validationErrors(), 0u);
    delete solver_;
    delete ctx_;
  }

  // Solves the batch on the GPU; returns cells * cellSolutionStride(L) floats. One more cell of
  // statistics than asked for is uploaded, and its solution slots must stay untouched.
  // `initial` (optional): the solution buffer before the solve (the cells' previous selections);
  // `statsAfter`/`samplesAfter` (optional) receive the statistics after it (cells it reset).
  static std::vector<float> solveOnGpu(const Batch& batch, SolveParams params, const std::vector<float>* initial = nullptr,
                                       std::vector<float>* statsAfter = nullptr,
                                       std::vector<uint32_t>* samplesAfter = nullptr) {
    params.clusterCount = batch.L;
    params.cellCount = batch.cells();
    uint32_t solStride = shared::cellSolutionStride(batch.L);
    std::vector<float> stats = batch.stats;
    stats.resize(stats.size() + batch.stride(), 1.0f);
    std::vector<uint32_t> samples = batch.samples;
    samples.push_back(1000u);
    std::vector<float> solution(size_t(batch.cells() + 1) * solStride, kSentinel);
    if (initial) std::copy(initial->begin(), initial->end(), solution.begin());
    std::vector<float> defaults = batch.defaults;
    Buffer statsBuf = makeBuffer(*ctx_, stats, "cell stats");
    Buffer samplesBuf = makeBuffer(*ctx_, samples, "cell samples");
    Buffer solutionBuf = makeBuffer(*ctx_, solution, "cell solution");
    Buffer defaultsBuf = makeBuffer(*ctx_, defaults, "cluster defaults");
    solver_->bind({{shared::BINDING_CELL_STATS, &statsBuf},
                   {shared::BINDING_CELL_SAMPLES, &samplesBuf},
                   {shared::BINDING_CELL_SOLUTION, &solutionBuf},
                   {shared::BINDING_CLUSTER_DEFAULTS, &defaultsBuf}});
    ctx_->submitAndWait([&](VkCommandBuffer cmd) { solver_->record(cmd, params); });
    std::vector<float> out = solutionBuf.downloadAll<float>();
    out.resize(solution.size());
    if (statsAfter) {
      *statsAfter = statsBuf.downloadAll<float>();
      statsAfter->resize(batch.stats.size());
    }
    if (samplesAfter) {
      *samplesAfter = samplesBuf.downloadAll<uint32_t>();
      samplesAfter->resize(batch.samples.size());
    }
    size_t beyond = 0;
    for (size_t i = size_t(batch.cells()) * solStride; i < out.size(); ++i) beyond += bitsOf(out[i]) != bitsOf(kSentinel);
    EXPECT_EQ(beyond, 0u) << "the solve wrote past its last cell";
    out.resize(size_t(batch.cells()) * solStride);
    return out;
  }

  static GpuCell gpuCell(const std::vector<float>& solution, uint32_t L, uint32_t i) {
    return GpuCell{&solution[size_t(i) * shared::cellSolutionStride(L)], L};
  }

  static VulkanContext* ctx_;
  static CellSolver* solver_;
};

VulkanContext* CmsSolve::ctx_ = nullptr;
CellSolver* CmsSolve::solver_ = nullptr;

// ---------------------------------------------------------------------------------------------
// Synthetic statistics

// Statistics gathered the way the shade pass gathers them (docs/estimator.md §4): per vertex one light
// sample (a cluster picked uniformly among `reached`) and one BSDF sample (hitting a reached
// cluster or nothing), each adding p p^T / p_eff^2 to A. Random densities make A SPD and well
// conditioned after Jacobi scaling. b = A alpha_true, so alpha_true is the exact solution.
struct Synthetic {
  std::vector<double> A;   // (L+1)^2, technique L = B
  std::vector<glm::dvec3> alphaTrue;   // L+1
  uint32_t L;
  double& at(uint32_t i, uint32_t j) { return A[i * (L + 1) + j]; }
  double at(uint32_t i, uint32_t j) const { return A[i * (L + 1) + j]; }

  std::vector<float> stats(double noise = 0.0, std::mt19937* rng = nullptr) const {
    std::vector<float> s(shared::cellStatsStride(L), 0.0f);
    std::normal_distribution<double> n(0.0, 1.0);
    for (uint32_t k = 0; k < L; ++k) {
      s[shared::statsAkk(L, k)] = float(at(k, k));
      s[shared::statsAkB(L, k)] = float(at(k, L));
    }
    s[shared::statsABB(L)] = float(at(L, L));
    for (uint32_t i = 0; i <= L; ++i) {
      glm::dvec3 b(0.0);
      for (uint32_t j = 0; j <= L; ++j) b += at(i, j) * alphaTrue[j];
      for (int c = 0; c < 3; ++c) {
        double v = b[c] * (1.0 + (rng ? noise * n(*rng) : 0.0));
        s[i == L ? shared::statsBB(L, c) : shared::statsBk(L, i, c)] = float(v);
      }
    }
    return s;
  }
};

Synthetic sampledSystem(std::mt19937& rng, uint32_t L, uint32_t vertices, const std::vector<bool>& reached) {
  Synthetic sys{std::vector<double>((L + 1) * (L + 1), 0.0), std::vector<glm::dvec3>(L + 1), L};
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<uint32_t> live;
  for (uint32_t k = 0; k < L; ++k)
    if (reached[k]) live.push_back(k);
  double select = live.empty() ? 0.0 : 1.0 / live.size();
  auto add = [&](int k, double pk, double pB) {
    double pe = select * pk + pB;
    if (k >= 0) {
      sys.at(k, k) += pk * pk / (pe * pe);
      sys.at(k, L) += pk * pB / (pe * pe);
      sys.at(L, k) = sys.at(k, L);
    }
    sys.at(L, L) += pB * pB / (pe * pe);
  };
  for (uint32_t v = 0; v < vertices; ++v) {
    if (!live.empty()) {   // light sample: the BSDF density there is 0 now and then (below the horizon)
      int k = int(live[size_t(u(rng) * live.size()) % live.size()]);
      add(k, 0.05 + 20.0 * u(rng), u(rng) < 0.3 ? 0.0 : 5.0 * u(rng));
    }
    double pB = 0.05 + 5.0 * u(rng);   // BSDF sample: hits a reached cluster or nothing
    if (!live.empty() && u(rng) < 0.6) add(int(live[size_t(u(rng) * live.size()) % live.size()]), 0.05 + 20.0 * u(rng), pB);
    else add(-1, 0.0, pB);
  }
  for (uint32_t t = 0; t <= L; ++t) {
    bool in = sys.at(t, t) > 0.0;   // a technique no sample reached has no say in b
    sys.alphaTrue[t] = in ? glm::dvec3(4.0 * u(rng) - 1.0, 4.0 * u(rng) - 1.0, 4.0 * u(rng) - 1.0) : glm::dvec3(0.0);
  }
  return sys;
}

Synthetic sampledSystem(std::mt19937& rng, uint32_t L, uint32_t vertices) {
  return sampledSystem(rng, L, vertices, std::vector<bool>(L, true));
}

// ---------------------------------------------------------------------------------------------
// Checks

double diagOf(const float* stats, uint32_t L, uint32_t t) {
  return t == L ? stats[shared::statsABB(L)] : stats[shared::statsAkk(L, t)];
}

double maxAbs(const glm::dvec3& v) { return std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z))); }

// Error of `alpha` against `expected` in the Jacobi-scaled unknowns y_t = sqrt(A_tt) alpha_t (the
// norm the solve works in: per-technique scales cancel), relative to the largest expected y.
double scaledError(const float* stats, uint32_t L, const std::vector<glm::dvec3>& alpha,
                   const std::vector<glm::dvec3>& expected) {
  double err = 0.0, size = 0.0;
  for (uint32_t t = 0; t <= L; ++t) {
    double d = diagOf(stats, L, t);
    double s = std::isfinite(d) && d > 0.0 ? std::sqrt(d) : 1.0;
    err = std::max(err, s * maxAbs(alpha[t] - expected[t]));
    size = std::max(size, s * maxAbs(expected[t]));
  }
  return size > 0.0 ? err / size : err;
}

// Normwise backward error of alpha in the reference's final scaled system (ridge included):
// |M y - b|_inf / (|M|_inf |y|_inf + |b|_inf). A backward-stable float solve keeps it at a small
// multiple of float epsilon however ill-conditioned M is.
double backwardError(const float* stats, uint32_t L, float ridge, const std::vector<bool>& inSystem,
                     const std::vector<glm::dvec3>& alpha) {
  // The ridge of shared/cms_solve.h: ridge times the mean diagonal entry of the techniques with
  // usable samples (before a singular B is dropped), added to the diagonal before scaling.
  auto finite3 = [](const float* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); };
  auto usable = [&](uint32_t t) {
    double d = diagOf(stats, L, t);
    if (!(std::isfinite(d) && d >= double(FLT_MIN))) return false;
    if (t == L) return finite3(&stats[shared::statsBB(L, 0)]);
    return std::isfinite(stats[shared::statsAkB(L, t)]) && finite3(&stats[shared::statsBk(L, t, 0)]);
  };
  double mean = 0.0, count = 0.0;
  for (uint32_t t = 0; t <= L; ++t)
    if (usable(t)) {
      mean += diagOf(stats, L, t);
      count += 1.0;
    }
  const double r = count > 0.0 ? double(ridge) * mean / count : 0.0;
  auto scale = [&](uint32_t t) { return 1.0 / std::sqrt(diagOf(stats, L, t) + r); };
  auto entry = [&](uint32_t i, uint32_t j) {
    if (i == j) return 1.0;
    if (i == L) return stats[shared::statsAkB(L, j)] * scale(i) * scale(j);
    if (j == L) return stats[shared::statsAkB(L, i)] * scale(i) * scale(j);
    return 0.0;
  };
  double residual = 0.0, normM = 0.0, normY = 0.0, normB = 0.0;
  for (uint32_t i = 0; i <= L; ++i) {
    if (!inSystem[i]) continue;
    const float* b = i == L ? &stats[shared::statsBB(L, 0)] : &stats[shared::statsBk(L, i, 0)];
    glm::dvec3 r = -glm::dvec3(b[0], b[1], b[2]) * scale(i);
    normB = std::max(normB, maxAbs(r));
    normY = std::max(normY, maxAbs(alpha[i] / scale(i)));
    double rowSum = 0.0;
    for (uint32_t j = 0; j <= L; ++j) {
      if (!inSystem[j]) continue;
      r += entry(i, j) * (alpha[j] / scale(j));
      rowSum += std::abs(entry(i, j));
    }
    normM = std::max(normM, rowSum);
    residual = std::max(residual, maxAbs(r));
  }
  double size = normM * normY + normB;
  return size > 0.0 ? residual / size : residual;
}

std::vector<glm::dvec3> gpuAlphas(const GpuCell& g) {
  std::vector<glm::dvec3> a(g.L + 1);
  for (uint32_t k = 0; k < g.L; ++k) a[k] = g.alpha(k);
  a[g.L] = g.alphaB();
  return a;
}

std::vector<glm::dvec3> refAlphas(const CellSolution& r) {
  std::vector<glm::dvec3> a = r.alpha;
  a.push_back(r.alphaB);
  return a;
}

// Properties every solved or unsolved cell must have, whatever its input. With the BVH defaults
// (kSolveBvhDefaults) the selection slots hold only the learned part: they sum to at most 1 - eps,
// and the rest, the defaults' share, keeps every light selectable.
void expectWellFormed(const GpuCell& g, const float* defaults, const std::string& where, bool bvhDefaults = false) {
  for (uint32_t i = 0; i < shared::cellSolutionStride(g.L); ++i)
    ASSERT_TRUE(std::isfinite(g.s[i])) << where << ": solution slot " << i << " = " << g.s[i];
  ASSERT_TRUE(g.valid() == 0.0f || g.valid() == 1.0f) << where;
  // The stored integral of the control variate is the sum of the coefficients.
  // (Float sums of up to 33 terms: the tolerance is relative to the terms, not the sum.)
  glm::dvec3 alphaSum = g.alphaB(), magnitude = glm::abs(g.alphaB());
  for (uint32_t k = 0; k < g.L; ++k) {
    alphaSum += g.alpha(k);
    magnitude += glm::abs(g.alpha(k));
  }
  glm::dvec3 stored = g.read3(shared::solutionAlphaSum(g.L, 0));
  for (int c = 0; c < 3; ++c)
    ASSERT_NEAR(stored[c], alphaSum[c], 1e-5 * (1.0 + magnitude[c])) << where << ": alpha sum";
  if (g.valid() == 0.0f) {
    for (uint32_t k = 0; k < g.L; ++k) ASSERT_EQ(g.alpha(k), glm::dvec3(0.0)) << where;
    ASSERT_EQ(g.alphaB(), glm::dvec3(0.0)) << where;
  }
  if (g.L == 0) return;
  double sum = 0.0;
  bool anyDefault = false;
  for (uint32_t k = 0; k < g.L; ++k) anyDefault = anyDefault || (std::isfinite(defaults[k]) && defaults[k] > 0.0f);
  for (uint32_t k = 0; k < g.L; ++k) {
    sum += g.select(k);
    ASSERT_GE(g.select(k), 0.0) << where;
    bool positiveDefault = anyDefault ? (std::isfinite(defaults[k]) && defaults[k] > 0.0f) : true;
    if (positiveDefault && !bvhDefaults) ASSERT_GT(g.select(k), 0.0) << where << ": cluster " << k << " can never be selected";
  }
  if (bvhDefaults) {
    ASSERT_LE(sum, 1.0 - 0.5 * shared::kSolveMinDefensive) << where << ": the defaults keep a share";
  } else {
    ASSERT_NEAR(sum, 1.0, 1e-5) << where;
  }
}

// The GPU cell against the reference: the same decisions (valid, techniques in the system), alpha
// within `tol` in the scaled norm (loose for ill-conditioned systems, where float rounding of the
// inputs alone moves alpha), with `backwardTol` > 0 also a backward error within it (the
// criterion of a stable solve at any conditioning), and the same selection.
void expectMatchesReference(const GpuCell& g, const float* stats, uint32_t samples, const SolveParams& params,
                            const float* defaults, double tol, const std::string& where, double backwardTol = 0.0) {
  expectWellFormed(g, defaults, where, (params.flags & shared::kSolveBvhDefaults) != 0);
  CellSolution ref = solveCellReference(stats, samples, g.L, params, defaults);
  ASSERT_EQ(g.valid() == 1.0f, ref.valid) << where;
  for (uint32_t t = 0; t <= g.L; ++t)
    if (!ref.inSystem[t]) {
      glm::dvec3 a = t == g.L ? g.alphaB() : g.alpha(t);
      ASSERT_EQ(a, glm::dvec3(0.0)) << where << ": technique " << t << " has no usable samples";
    }
  if (ref.valid) {
    if (backwardTol > 0.0) {
      double r = backwardError(stats, g.L, params.ridge, ref.inSystem, gpuAlphas(g));
      EXPECT_LE(r, backwardTol) << where;
    }
    double e = scaledError(stats, g.L, gpuAlphas(g), refAlphas(ref));
    EXPECT_LE(e, tol) << where;
  }
  for (uint32_t k = 0; k < g.L; ++k) EXPECT_NEAR(g.select(k), ref.select[k], std::max(tol, 1e-5)) << where << " c_" << k;
}

// ---------------------------------------------------------------------------------------------

TEST_F(CmsSolve, WellConditionedCellsRecoverTheTrueAlpha) {
  std::mt19937 rng(1);
  const uint32_t L = 8;
  Batch batch(L);
  std::vector<Synthetic> systems;
  for (uint32_t i = 0; i < 1000; ++i) {
    systems.push_back(sampledSystem(rng, L, 20 + i % 200));
    batch.add(systems.back().stats(), 40 + 2 * (i % 200));
  }
  SolveParams params = makeParams(L);
  std::vector<float> gpu = solveOnGpu(batch, params);
  double worstTrue = 0.0;
  for (uint32_t i = 0; i < batch.cells(); ++i) {
    GpuCell g = gpuCell(gpu, L, i);
    expectMatchesReference(g, batch.cell(i), batch.samples[i], params, batch.defaults.data(), 1e-4, "cell " + std::to_string(i));
    ASSERT_EQ(g.valid(), 1.0f);
    CellSolution ref = solveCellReference(batch.cell(i), batch.samples[i], L, params, batch.defaults.data());
    EXPECT_LE(scaledError(batch.cell(i), L, refAlphas(ref), systems[i].alphaTrue), 1e-5) << "reference, cell " << i;
    worstTrue = std::max(worstTrue, scaledError(batch.cell(i), L, gpuAlphas(g), systems[i].alphaTrue));
  }
  std::printf("worst scaled error of the GPU solve against the exact alpha: %.2e\n", worstTrue);
  EXPECT_LE(worstTrue, 1e-4);
}

TEST_F(CmsSolve, NoisyRightHandSidesMatchTheReference) {
  std::mt19937 rng(2);
  const uint32_t L = 5;
  Batch batch(L);
  for (uint32_t i = 0; i < 300; ++i) batch.add(sampledSystem(rng, L, 10 + i).stats(0.2, &rng), 100);
  for (float ridge : {0.0f, 1e-3f, 0.1f}) {
    SolveParams params = makeParams(L, kBoth, ridge);
    std::vector<float> gpu = solveOnGpu(batch, params);
    for (uint32_t i = 0; i < batch.cells(); ++i)
      expectMatchesReference(gpuCell(gpu, L, i), batch.cell(i), 100, params, batch.defaults.data(), 1e-4,
                             "ridge " + std::to_string(ridge) + " cell " + std::to_string(i));
  }
}

TEST_F(CmsSolve, OneAndThirtyTwoClusters) {
  for (uint32_t L : {1u, 32u}) {
    std::mt19937 rng(3 + L);
    Batch batch(L);
    std::vector<Synthetic> systems;
    for (uint32_t i = 0; i < 400; ++i) {
      systems.push_back(sampledSystem(rng, L, 5 * L + 20 + i % 50));
      batch.add(systems.back().stats(), 100);
    }
    SolveParams params = makeParams(L);
    std::vector<float> gpu = solveOnGpu(batch, params);
    for (uint32_t i = 0; i < batch.cells(); ++i) {
      std::string where = "L " + std::to_string(L) + " cell " + std::to_string(i);
      GpuCell g = gpuCell(gpu, L, i);
      expectMatchesReference(g, batch.cell(i), 100, params, batch.defaults.data(), 2e-4, where);
      EXPECT_LE(scaledError(batch.cell(i), L, gpuAlphas(g), systems[i].alphaTrue), 2e-4) << where;
    }
  }
}

TEST_F(CmsSolve, NoClustersSolvesTheBsdfTechniqueAlone) {
  Batch batch(0);
  for (uint32_t i = 0; i < 200; ++i) {
    std::vector<float> s(shared::cellStatsStride(0), 0.0f);
    s[shared::statsABB(0)] = 0.5f + float(i);
    for (int c = 0; c < 3; ++c) s[shared::statsBB(0, c)] = float(i) - 100.0f + c;
    batch.add(s, 10);
  }
  std::vector<float> gpu = solveOnGpu(batch, makeParams(0));
  for (uint32_t i = 0; i < batch.cells(); ++i) {
    GpuCell g = gpuCell(gpu, 0, i);
    expectWellFormed(g, nullptr, "cell " + std::to_string(i));
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(g.alphaB()[c], (double(i) - 100.0 + c) / (0.5 + i), 1e-6 * (1.0 + std::abs(g.alphaB()[c])));
    EXPECT_EQ(g.valid(), 1.0f);
  }
}

TEST_F(CmsSolve, UnreachedClustersAreDroppedNotTheCell) {
  std::mt19937 rng(4);
  const uint32_t L = 6;
  Batch batch(L);
  std::vector<Synthetic> systems;
  for (uint32_t i = 0; i < 300; ++i) {
    std::vector<bool> reached(L);
    for (uint32_t k = 0; k < L; ++k) reached[k] = (i >> k) & 1;   // every pattern, none reached included
    systems.push_back(sampledSystem(rng, L, 80, reached));
    batch.add(systems.back().stats(), 80);
  }
  SolveParams params = makeParams(L);
  std::vector<float> gpu = solveOnGpu(batch, params);
  for (uint32_t i = 0; i < batch.cells(); ++i) {
    std::string where = "cell " + std::to_string(i);
    GpuCell g = gpuCell(gpu, L, i);
    expectMatchesReference(g, batch.cell(i), 80, params, batch.defaults.data(), 1e-4, where);
    EXPECT_EQ(g.valid(), 1.0f) << where << ": B alone still has samples";
    EXPECT_LE(scaledError(batch.cell(i), L, gpuAlphas(g), systems[i].alphaTrue), 1e-4) << where;
    for (uint32_t k = 0; k < L; ++k)
      if (!((i >> k) & 1)) EXPECT_EQ(g.alpha(k), glm::dvec3(0.0)) << where;
  }
  // A cell that nothing reached at all, the BSDF technique included, uses no control variate.
  Batch empty(L);
  empty.add(std::vector<float>(shared::cellStatsStride(L), 0.0f), 0);
  empty.add(std::vector<float>(shared::cellStatsStride(L), 0.0f), 500);
  std::vector<float> gpuEmpty = solveOnGpu(empty, params);
  for (uint32_t i = 0; i < 2; ++i) {
    GpuCell g = gpuCell(gpuEmpty, L, i);
    expectWellFormed(g, empty.defaults.data(), "empty cell");
    EXPECT_EQ(g.valid(), 0.0f);
    for (uint32_t k = 0; k < L; ++k) EXPECT_FLOAT_EQ(g.select(k), 1.0f / L);
  }
}

TEST_F(CmsSolve, IdenticalClustersGetIdenticalCoefficients) {
  std::mt19937 rng(5);
  const uint32_t L = 4;
  Batch batch(L);
  for (uint32_t i = 0; i < 100; ++i) {
    std::vector<float> s = sampledSystem(rng, L, 60).stats();
    // Cluster 2 becomes an exact copy of cluster 1 (as seen from this cell).
    s[shared::statsAkk(L, 2)] = s[shared::statsAkk(L, 1)];
    s[shared::statsAkB(L, 2)] = s[shared::statsAkB(L, 1)];
    for (int c = 0; c < 3; ++c) s[shared::statsBk(L, 2, c)] = s[shared::statsBk(L, 1, c)];
    batch.add(s, 60);
  }
  SolveParams params = makeParams(L);
  std::vector<float> gpu = solveOnGpu(batch, params);
  for (uint32_t i = 0; i < batch.cells(); ++i) {
    GpuCell g = gpuCell(gpu, L, i);
    expectMatchesReference(g, batch.cell(i), 60, params, batch.defaults.data(), 1e-4, "cell " + std::to_string(i));
    EXPECT_EQ(g.alpha(1), g.alpha(2));
  }
}

// B sampling exactly like cluster 0 (p_B = p_0 on every sample): A is singular. Without a ridge
// B is dropped (its pivot is 0) and cluster 0 alone explains b; with a ridge the regularised
// system is regular and both keep coefficients.
TEST_F(CmsSolve, SingularSystemDropsTheDependentTechnique) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (uint32_t L : {1u, 3u}) {
    Batch batch(L);
    for (uint32_t i = 0; i < 100; ++i) {
      std::vector<float> s(shared::cellStatsStride(L), 0.0f);
      for (uint32_t k = 0; k < L; ++k) {
        float a = float(0.1 + 10.0 * u(rng));
        s[shared::statsAkk(L, k)] = a;
        if (k == 0) {
          s[shared::statsAkB(L, 0)] = a;
          s[shared::statsABB(L)] = a;
        }
        for (int c = 0; c < 3; ++c) s[shared::statsBk(L, k, c)] = float(u(rng) * a);
      }
      for (int c = 0; c < 3; ++c) s[shared::statsBB(L, c)] = s[shared::statsBk(L, 0, c)];
      batch.add(s, 50);
    }
    for (float ridge : {0.0f, 1e-3f}) {
      SolveParams params = makeParams(L, kBoth, ridge);
      std::vector<float> gpu = solveOnGpu(batch, params);
      for (uint32_t i = 0; i < batch.cells(); ++i) {
        std::string where = "L " + std::to_string(L) + " ridge " + std::to_string(ridge) + " cell " + std::to_string(i);
        GpuCell g = gpuCell(gpu, L, i);
        expectMatchesReference(g, batch.cell(i), 50, params, batch.defaults.data(), 1e-3, where, 1e-5);
        ASSERT_EQ(g.valid(), 1.0f) << where;
        if (ridge == 0.0f) {
          EXPECT_EQ(g.alphaB(), glm::dvec3(0.0)) << where;
          const float* s = batch.cell(i);
          for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(g.alpha(0)[c], s[shared::statsBk(L, 0, c)] / s[shared::statsAkk(L, 0)], 1e-6) << where;
        } else {
          EXPECT_NE(g.alphaB(), glm::dvec3(0.0)) << where;
        }
      }
    }
  }
}

// Scaled Schur pivot delta: 1e-12 (condition ~1e12, below float resolution), 1e-3 (ill
// conditioned but solvable in float). Diagonal entries of different magnitudes on top.
TEST_F(CmsSolve, NearlySingularSystems) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const uint32_t L = 3;
  for (double delta : {1e-12, 1e-3}) {
    Batch batch(L);
    for (uint32_t i = 0; i < 200; ++i) {
      std::vector<double> dir(L);
      double norm = 0.0;
      for (double& d : dir) { d = u(rng) - 0.3; norm += d * d; }
      std::vector<float> s(shared::cellStatsStride(L), 0.0f);
      double aBB = std::pow(10.0, 4.0 * u(rng) - 2.0);
      s[shared::statsABB(L)] = float(aBB);
      for (uint32_t k = 0; k < L; ++k) {
        double akk = std::pow(10.0, 4.0 * u(rng) - 2.0);
        double scaled = dir[k] / std::sqrt(norm) * std::sqrt(1.0 - delta);   // sum of squares = 1 - delta
        s[shared::statsAkk(L, k)] = float(akk);
        s[shared::statsAkB(L, k)] = float(scaled * std::sqrt(akk * aBB));
        for (int c = 0; c < 3; ++c) s[shared::statsBk(L, k, c)] = float((u(rng) - 0.5) * akk);
      }
      for (int c = 0; c < 3; ++c) s[shared::statsBB(L, c)] = float((u(rng) - 0.5) * aBB);
      batch.add(s, 1000);
    }
    for (float ridge : {0.0f, 1e-3f}) {
      SolveParams params = makeParams(L, kBoth, ridge);
      std::vector<float> gpu = solveOnGpu(batch, params);
      for (uint32_t i = 0; i < batch.cells(); ++i) {
        std::string where = "delta " + std::to_string(delta) + " ridge " + std::to_string(ridge) + " cell " + std::to_string(i);
        GpuCell g = gpuCell(gpu, L, i);
        // Float rounding of the inputs alone moves alpha by ~cond * 6e-8: compare the residual
        // tightly and alpha to within that.
        expectMatchesReference(g, batch.cell(i), 1000, params, batch.defaults.data(), 5e-3, where, 2e-5);
        EXPECT_EQ(g.valid(), 1.0f) << where;
        if (delta < 1e-6 && ridge == 0.0f) EXPECT_EQ(g.alphaB(), glm::dvec3(0.0)) << where;
      }
    }
  }
}

// One vertex: A = p p^T / p_eff^2 has rank 1.
TEST_F(CmsSolve, OneSample) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const uint32_t L = 4;
  Batch batch(L);
  for (uint32_t i = 0; i < 200; ++i) {
    std::vector<float> s(shared::cellStatsStride(L), 0.0f);
    uint32_t k = i % L;
    double pk = 0.1 + 10.0 * u(rng), pB = i % 3 == 0 ? 0.0 : 0.1 + 3.0 * u(rng), pe = pk / L + pB;
    double f = u(rng);
    s[shared::statsAkk(L, k)] = float(pk * pk / (pe * pe));
    s[shared::statsAkB(L, k)] = float(pk * pB / (pe * pe));
    s[shared::statsABB(L)] = float(pB * pB / (pe * pe));
    for (int c = 0; c < 3; ++c) {
      s[shared::statsBk(L, k, c)] = float(f * (c + 1) * pk / (pe * pe));
      s[shared::statsBB(L, c)] = float(f * (c + 1) * pB / (pe * pe));
    }
    batch.add(s, 1);
  }
  for (float ridge : {0.0f, 1e-3f}) {
    for (uint32_t minSamples : {1u, 2u}) {
      SolveParams params = makeParams(L, kBoth, ridge, minSamples);
      std::vector<float> gpu = solveOnGpu(batch, params);
      for (uint32_t i = 0; i < batch.cells(); ++i) {
        std::string where = "ridge " + std::to_string(ridge) + " min " + std::to_string(minSamples) + " cell " + std::to_string(i);
        GpuCell g = gpuCell(gpu, L, i);
        expectMatchesReference(g, batch.cell(i), 1, params, batch.defaults.data(), 1e-3, where, 1e-5);
        EXPECT_EQ(g.valid(), minSamples == 1 ? 1.0f : 0.0f) << where;
      }
    }
  }
}

// The sample count is a uint: thresholds past 2^24 (where float counts stop being exact) hold.
TEST_F(CmsSolve, SampleCountsPast2To24) {
  std::mt19937 rng(9);
  const uint32_t L = 2;
  Batch batch(L);
  const uint32_t counts[] = {99999999u, 100000000u, 100000001u, 4000000000u};
  for (uint32_t n : counts) batch.add(sampledSystem(rng, L, 50).stats(), n);
  for (uint32_t minSamples : {100000000u, 100000001u}) {
    SolveParams params = makeParams(L, kBoth, 0.0f, minSamples);
    std::vector<float> gpu = solveOnGpu(batch, params);
    for (uint32_t i = 0; i < batch.cells(); ++i) {
      std::string where = "min " + std::to_string(minSamples) + " samples " + std::to_string(counts[i]);
      expectMatchesReference(gpuCell(gpu, L, i), batch.cell(i), counts[i], params, batch.defaults.data(), 1e-4, where);
      EXPECT_EQ(gpuCell(gpu, L, i).valid(), counts[i] >= minSamples ? 1.0f : 0.0f) << where;
    }
  }
}

// Each technique's row and column scaled by 10^[-4, 4]: entries span 1e-8 .. 1e8 while the
// scaled system stays the well-conditioned one; Jacobi scaling must make this harmless.
TEST_F(CmsSolve, EntriesSpanningSixteenOrdersOfMagnitude) {
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const uint32_t L = 6;
  Batch batch(L);
  std::vector<Synthetic> systems;
  for (uint32_t i = 0; i < 300; ++i) {
    Synthetic sys = sampledSystem(rng, L, 60);
    std::vector<double> scale(L + 1);
    for (double& s : scale) s = std::pow(10.0, 8.0 * u(rng) - 4.0);
    for (uint32_t a = 0; a <= L; ++a) {
      for (uint32_t b = 0; b <= L; ++b) sys.at(a, b) *= scale[a] * scale[b];
      sys.alphaTrue[a] /= scale[a];
    }
    systems.push_back(sys);
    batch.add(sys.stats(), 60);
  }
  SolveParams params = makeParams(L, kBoth, 0.0f);   // no ridge: it would (rightly) shrink the small ones
  std::vector<float> gpu = solveOnGpu(batch, params);
  for (uint32_t i = 0; i < batch.cells(); ++i) {
    std::string where = "cell " + std::to_string(i);
    GpuCell g = gpuCell(gpu, L, i);
    expectMatchesReference(g, batch.cell(i), 60, params, batch.defaults.data(), 1e-4, where);
    EXPECT_LE(scaledError(batch.cell(i), L, gpuAlphas(g), systems[i].alphaTrue), 2e-4) << where;
  }
}

// NaN and Inf (and other garbage) in single entries drop the affected technique; the rest of the
// cell is still solved. Overflowing solutions invalidate the cell.
TEST_F(CmsSolve, NonFiniteEntriesDropTheirTechnique) {
  std::mt19937 rng(11);
  const uint32_t L = 4;
  const float nan = std::nanf(""), inf = INFINITY;
  struct Corruption {
    const char* name;
    int slot;        // -1: every slot
    float value;
    bool cellValid;  // expected
  };
  const Corruption corruptions[] = {
      {"A_00 NaN", int(shared::statsAkk(L, 0)), nan, true},
      {"A_00 Inf", int(shared::statsAkk(L, 0)), inf, true},
      {"A_00 negative", int(shared::statsAkk(L, 0)), -2.0f, true},
      {"A_00 denormal", int(shared::statsAkk(L, 0)), 1e-40f, true},
      {"A_0B NaN", int(shared::statsAkB(L, 0)), nan, true},
      {"A_1B -Inf", int(shared::statsAkB(L, 1)), -inf, true},
      {"b_2 green Inf", int(shared::statsBk(L, 2, 1)), inf, true},
      {"b_3 blue NaN", int(shared::statsBk(L, 3, 2)), nan, true},
      {"A_BB NaN", int(shared::statsABB(L)), nan, true},
      {"A_BB Inf", int(shared::statsABB(L)), inf, true},
      {"b_B red -Inf", int(shared::statsBB(L, 0)), -inf, true},
      {"everything NaN", -1, nan, false},
      {"everything Inf", -1, inf, false},
      {"everything FLT_MAX", -1, FLT_MAX, true},
  };
  Batch batch(L);
  std::vector<std::string> names;
  for (const Corruption& c : corruptions)
    for (int rep = 0; rep < 10; ++rep) {
      std::vector<float> s = sampledSystem(rng, L, 40).stats();
      if (c.slot < 0) std::fill(s.begin(), s.end(), c.value);
      else s[c.slot] = c.value;
      batch.add(s, 40);
      names.push_back(c.name);
    }
  // Overflow: b_0 near FLT_MAX over a tiny A_00 gives alpha ~1e68.
  for (int rep = 0; rep < 5; ++rep) {
    std::vector<float> s = sampledSystem(rng, L, 40).stats();
    s[shared::statsAkk(L, 0)] = 1e-30f;
    s[shared::statsAkB(L, 0)] = 0.0f;
    s[shared::statsBk(L, 0, 0)] = 3e38f;
    batch.add(s, 40);
    names.push_back("overflowing alpha");
  }
  for (float ridge : {0.0f, 1e-3f}) {
    SolveParams params = makeParams(L, kBoth, ridge);
    std::vector<float> gpu = solveOnGpu(batch, params);
    for (uint32_t i = 0; i < batch.cells(); ++i) {
      std::string where = names[i] + " #" + std::to_string(i) + " ridge " + std::to_string(ridge);
      GpuCell g = gpuCell(gpu, L, i);
      expectMatchesReference(g, batch.cell(i), 40, params, batch.defaults.data(), 1e-3, where, 1e-4);
      bool expectValid = i < 10 * std::size(corruptions) ? corruptions[i / 10].cellValid : false;
      EXPECT_EQ(g.valid(), expectValid ? 1.0f : 0.0f) << where;
    }
  }
}

// Random garbage: entries from a palette of extremes, random sample counts, defaults and
// parameters (NaN ridge, negative defensive fraction, ...). Only the guarantees: every output
// finite, a proper pmf that keeps every cluster with a positive default selectable, alpha = 0
// wherever valid = 0, and agreement with the reference on validity.
TEST_F(CmsSolve, GarbageInFiniteOut) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const float palette[] = {0.0f, -0.0f, 1e-45f, 1e-38f, 1e-30f, -1e-30f, 1.0f, -1.0f, 1e30f, FLT_MAX, -FLT_MAX,
                           INFINITY, -INFINITY, std::nanf("")};
  auto entry = [&]() -> float {
    if (u(rng) < 0.5) return float(std::pow(10.0, 60.0 * u(rng) - 30.0) * (u(rng) < 0.2 ? -1.0 : 1.0));
    return palette[size_t(u(rng) * std::size(palette)) % std::size(palette)];
  };
  const float ridges[] = {0.0f, 1e-3f, -1.0f, std::nanf(""), INFINITY};
  const float defensives[] = {0.0f, 0.1f, 1.0f, -1.0f, 2.0f, std::nanf("")};
  for (uint32_t L : {1u, 7u, 32u}) {
    Batch batch(L);
    for (uint32_t k = 0; k < L; ++k) batch.defaults[k] = L > 1 && k % 3 == 1 ? entry() : float(u(rng));
    for (uint32_t i = 0; i < 400; ++i) {
      std::vector<float> s(shared::cellStatsStride(L));
      for (float& v : s) v = entry();
      batch.add(s, uint32_t(u(rng) * 100.0));
    }
    // Trials 4-7: the same flags with the BVH defaults (only the learned part stored).
    for (int trial = 0; trial < 8; ++trial) {
      const uint32_t flags = uint32_t(trial % 4) | (trial >= 4 ? shared::kSolveBvhDefaults : 0u);
      SolveParams params = makeParams(L, flags, ridges[size_t(u(rng) * 5) % 5], 10, defensives[size_t(u(rng) * 6) % 6]);
      std::vector<float> gpu = solveOnGpu(batch, params);
      uint32_t disagreements = 0;
      for (uint32_t i = 0; i < batch.cells(); ++i) {
        GpuCell g = gpuCell(gpu, L, i);
        expectWellFormed(g, batch.defaults.data(), "L " + std::to_string(L) + " cell " + std::to_string(i), trial >= 4);
        CellSolution ref = solveCellReference(batch.cell(i), batch.samples[i], L, params, batch.defaults.data());
        disagreements += (g.valid() == 1.0f) != ref.valid;
      }
      EXPECT_EQ(disagreements, 0u) << "L " << L << " trial " << trial;
    }
  }
}

TEST_F(CmsSolve, MinimumSampleThreshold) {
  std::mt19937 rng(13);
  const uint32_t L = 3;
  Batch batch(L);
  batch.defaults = {0.5f, 0.3f, 0.2f};
  for (uint32_t n = 0; n < 40; ++n) batch.add(sampledSystem(rng, L, 30).stats(), n);
  SolveParams params = makeParams(L, kBoth, 0.0f, 17);
  std::vector<float> gpu = solveOnGpu(batch, params);
  for (uint32_t n = 0; n < batch.cells(); ++n) {
    std::string where = "samples " + std::to_string(n);
    GpuCell g = gpuCell(gpu, L, n);
    expectMatchesReference(g, batch.cell(n), n, params, batch.defaults.data(), 1e-4, where);
    EXPECT_EQ(g.valid(), n >= 17 ? 1.0f : 0.0f) << where;
    if (n < 17)
      for (uint32_t k = 0; k < L; ++k) EXPECT_FLOAT_EQ(g.select(k), batch.defaults[k]) << where;
  }
}

// Diagonal cells (B absent, A_kk = 1, b_k = alpha_k) so alpha is known exactly and the selection
// can be checked against the formula of docs/estimator.md §7 directly.
// The learned-selection tests' cells: L = 4 clusters with A = identity, so alpha_k = b_k; one
// with weights of both signs and one with none positive.
constexpr uint32_t kSelectionL = 4;
std::vector<float> diagonalCell(const std::vector<glm::vec3>& alpha) {
  const uint32_t L = kSelectionL;
  std::vector<float> s(shared::cellStatsStride(L), 0.0f);
  for (uint32_t k = 0; k < L; ++k) {
    s[shared::statsAkk(L, k)] = 1.0f;
    for (int c = 0; c < 3; ++c) s[shared::statsBk(L, k, c)] = alpha[k][c];
  }
  return s;
}
double lum(glm::vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }
const std::vector<glm::vec3> kMixedAlpha = {{2, 1, 0.5f}, {-1, -2, -1}, {0, 0, 0}, {0.5f, 3, 9}};
const std::vector<glm::vec3> kNegativeAlpha = {{-1, -1, -1}, {0, 0, 0}, {-2, 0, 0}, {0, -0.5f, 0}};

TEST_F(CmsSolve, LearnedSelection) {
  const uint32_t L = kSelectionL;
  const std::vector<glm::vec3>& mixed = kMixedAlpha;
  const std::vector<glm::vec3>& negative = kNegativeAlpha;
  struct Case {
    std::vector<float> defaults;
    float defensive;
  };
  const Case cases[] = {
      {{0.1f, 0.2f, 0.0f, 0.7f}, 0.2f},
      {{0.1f, 0.2f, 0.0f, 0.7f}, 0.0f},    // clamped to kSolveMinDefensive: cluster 1 stays selectable
      {{1.0f, 2.0f, 0.0f, 7.0f}, 0.2f},    // unnormalised defaults: same as the first
      {{0.0f, 0.0f, 0.0f, 0.0f}, 0.5f},    // no usable defaults: uniform
      {{0.25f, NAN, -1.0f, 0.75f}, 0.3f},  // garbage defaults count as 0
      {{1.0f, 1e-37f, 1.0f, 1.0f}, 0.0f},  // eps * d_1 is a denormal (flushed on many GPUs): still > 0
  };
  for (const Case& cs : cases) {
    Batch batch(L);
    batch.defaults = cs.defaults;
    batch.add(diagonalCell(mixed), 100);
    batch.add(diagonalCell(negative), 100);   // no positive weight: defaults
    batch.add(diagonalCell(mixed), 5);        // below minSamples: defaults
    SolveParams params = makeParams(L, kBoth, 0.0f, 10, cs.defensive);
    std::vector<float> gpu = solveOnGpu(batch, params);

    std::vector<double> d(L, 0.0);
    double dSum = 0.0;
    for (uint32_t k = 0; k < L; ++k) dSum += d[k] = std::isfinite(cs.defaults[k]) && cs.defaults[k] > 0 ? cs.defaults[k] : 0.0;
    for (uint32_t k = 0; k < L; ++k) d[k] = dSum > 0 ? d[k] / dSum : 1.0 / L;
    double eps = std::max(double(cs.defensive), 1e-3), wSum = 0.0;
    for (uint32_t k = 0; k < L; ++k) wSum += std::max(lum(mixed[k]), 0.0);
    for (uint32_t i = 0; i < 3; ++i) {
      std::string where = "defensive " + std::to_string(cs.defensive) + " cell " + std::to_string(i);
      GpuCell g = gpuCell(gpu, L, i);
      expectMatchesReference(g, batch.cell(i), batch.samples[i], params, batch.defaults.data(), 1e-6, where);
      for (uint32_t k = 0; k < L; ++k) {
        double expected = i == 0 ? (1.0 - eps) * std::max(lum(mixed[k]), 0.0) / wSum + eps * d[k] : d[k];
        EXPECT_NEAR(g.select(k), expected, 1e-6) << where << " c_" << k;
        if (d[k] > 0.0) EXPECT_GT(g.select(k), 0.0) << where;
      }
    }
  }
}

// The light BVH as the defaults (kSolveBvhDefaults, learned and cms): the cell stores only the
// learned part, c_k = (1 - eps) w_k / sum w, and nothing where it learns nothing (no positive
// weight, too few samples): the defaults' share 1 - sum c_k is then 1. GPU and reference agree.
TEST_F(CmsSolve, LearnedSelectionWithBvhDefaults) {
  const uint32_t L = kSelectionL;
  const std::vector<glm::vec3>& mixed = kMixedAlpha;
  const std::vector<glm::vec3>& negative = kNegativeAlpha;
  for (float defensive : {0.2f, 0.0f, 1.0f}) {
    Batch batch(L);
    batch.defaults = {0.1f, 0.2f, 0.0f, 0.7f};
    batch.add(diagonalCell(mixed), 100);
    batch.add(diagonalCell(negative), 100);
    batch.add(diagonalCell(mixed), 5);   // below minSamples
    SolveParams params = makeParams(L, kBoth | shared::kSolveBvhDefaults, 0.0f, 10, defensive);
    std::vector<float> gpu = solveOnGpu(batch, params);
    const double eps = std::max(double(defensive), 1e-3);
    double wSum = 0.0;
    for (uint32_t k = 0; k < L; ++k) wSum += std::max(lum(mixed[k]), 0.0);
    for (uint32_t i = 0; i < 3; ++i) {
      std::string where = "defensive " + std::to_string(defensive) + " cell " + std::to_string(i);
      GpuCell g = gpuCell(gpu, L, i);
      expectWellFormed(g, batch.defaults.data(), where, true);
      expectMatchesReference(g, batch.cell(i), batch.samples[i], params, batch.defaults.data(), 1e-6, where);
      double sum = 0.0;
      for (uint32_t k = 0; k < L; ++k) {
        double expected = i == 0 ? (1.0 - eps) * std::max(lum(mixed[k]), 0.0) / wSum : 0.0;
        EXPECT_NEAR(g.select(k), expected, 1e-6) << where << " c_" << k;
        sum += g.select(k);
      }
      EXPECT_NEAR(1.0 - sum, i == 0 ? eps : 1.0, 1e-6) << where << ": the defaults' share";
    }
  }
}

// Statistics persist across iterations: a cell keeps its previous selection (and its statistics)
// unless it has none yet or, solved, its new selection moved by more than
// kSelectionChangeThreshold in total variation; then it adopts it and its statistics restart.
TEST_F(CmsSolve, SelectionPersistsUnlessItMoves) {
  const uint32_t L = 4;
  std::vector<float> cell(shared::cellStatsStride(L), 0.0f);
  const glm::vec3 alpha[L] = {{2, 1, 0.5f}, {1, 1, 1}, {0.1f, 0.1f, 0.1f}, {0.5f, 3, 9}};
  for (uint32_t k = 0; k < L; ++k) {
    cell[shared::statsAkk(L, k)] = 1.0f;
    for (int c = 0; c < 3; ++c) cell[shared::statsBk(L, k, c)] = alpha[k][c];
  }
  const SolveParams params = makeParams(L, kBoth, 0.0f, 10, 0.2f);
  // The selection these statistics learn, from a cell without history.
  Batch probe(L);
  probe.add(cell, 100);
  const std::vector<float> fresh = solveOnGpu(probe, params);
  std::vector<float> learned(L);
  for (uint32_t k = 0; k < L; ++k) learned[k] = fresh[shared::solutionSelect(L, k)];

  struct Case {
    const char* what;
    std::vector<float> previous;   // empty: no history (NaN)
    uint32_t samples;
    uint32_t flags;
    bool adopt;
  };
  std::vector<float> nearby = learned;   // moved by 0.02 in total variation
  nearby[0] += 0.02f;
  nearby[3] -= 0.02f;
  std::vector<float> far = {0.25f, 0.25f, 0.25f, 0.25f};
  const Case cases[] = {
      {"small move: keeps", nearby, 100, kBoth, false},
      {"large move: adopts", far, 100, kBoth, true},
      {"no history: adopts", {}, 100, kBoth, true},
      {"unsolved (too few samples): keeps", {0.7f, 0.1f, 0.1f, 0.1f}, 5, kBoth, false},
      {"fixed selection (cv): keeps", far, 100, shared::kSolveControlVariate, false},
      {"not normalised: adopts", {0.5f, 0.5f, 0.5f, 0.5f}, 100, kBoth, true},
  };
  Batch batch(L);
  std::vector<float> initial;
  for (const Case& cs : cases) {
    batch.add(cell, cs.samples);
    std::vector<float> s(shared::cellSolutionStride(L), kSentinel);
    for (uint32_t k = 0; k < cs.previous.size(); ++k) s[shared::solutionSelect(L, k)] = cs.previous[k];
    initial.insert(initial.end(), s.begin(), s.end());
  }
  // One flag set per dispatch: solve the cells of each flag set separately and keep their rows.
  for (uint32_t flags : {kBoth, uint32_t(shared::kSolveControlVariate)}) {
    SolveParams p = params;
    p.flags = flags;
    std::vector<float> statsAfter;
    std::vector<uint32_t> samplesAfter;
    std::vector<float> gpu = solveOnGpu(batch, p, &initial, &statsAfter, &samplesAfter);
    for (uint32_t i = 0; i < batch.cells(); ++i) {
      const Case& cs = cases[i];
      if (cs.flags != flags) continue;
      GpuCell g = gpuCell(gpu, L, i);
      const float* previous = cs.previous.empty() ? nullptr : &initial[size_t(i) * shared::cellSolutionStride(L) + shared::solutionSelect(L, 0)];
      CellSolution ref = solveCellReference(batch.cell(i), cs.samples, L, p, batch.defaults.data(), previous);
      EXPECT_EQ(ref.resetStatistics, cs.adopt) << cs.what;
      bool reset = samplesAfter[i] == 0;
      for (uint32_t j = 0; j < batch.stride(); ++j) reset = reset && statsAfter[size_t(i) * batch.stride() + j] == 0.0f;
      EXPECT_EQ(reset, cs.adopt) << cs.what << ": statistics " << (reset ? "reset" : "kept");
      for (uint32_t k = 0; k < L; ++k) {
        EXPECT_NEAR(g.select(k), ref.select[k], 1e-6) << cs.what << " c_" << k;
        if (!cs.adopt) EXPECT_EQ(g.select(k), cs.previous[k]) << cs.what << ": the previous selection stays, exactly";
      }
      if (cs.adopt && (flags & shared::kSolveLearnSelection))
        for (uint32_t k = 0; k < L; ++k) EXPECT_NEAR(g.select(k), learned[k], 1e-6) << cs.what;
    }
  }
}

// Every flag combination on the same cells: alpha and valid only with the control variate,
// learned selection only with its flag, and (documented) the learned selection is the same with
// or without the control variate: the solve runs either way.
TEST_F(CmsSolve, FlagCombinations) {
  std::mt19937 rng(14);
  const uint32_t L = 5;
  Batch batch(L);
  batch.defaults = {0.3f, 0.1f, 0.2f, 0.15f, 0.25f};
  for (uint32_t i = 0; i < 200; ++i) batch.add(sampledSystem(rng, L, 40).stats(0.1, &rng), i % 20);
  std::vector<float> results[4];
  for (uint32_t flags = 0; flags < 4; ++flags) {
    SolveParams params = makeParams(L, flags, 1e-4f, 5, 0.2f);
    results[flags] = solveOnGpu(batch, params);
    for (uint32_t i = 0; i < batch.cells(); ++i) {
      std::string where = "flags " + std::to_string(flags) + " cell " + std::to_string(i);
      GpuCell g = gpuCell(results[flags], L, i);
      expectMatchesReference(g, batch.cell(i), batch.samples[i], params, batch.defaults.data(), 1e-4, where);
      bool enough = batch.samples[i] >= 5;
      EXPECT_EQ(g.valid(), (flags & shared::kSolveControlVariate) && enough ? 1.0f : 0.0f) << where;
      if (!(flags & shared::kSolveLearnSelection) || !enough)
        for (uint32_t k = 0; k < L; ++k) EXPECT_NEAR(g.select(k), batch.defaults[k], 1e-6) << where;
    }
  }
  size_t learnedDiffers = 0;
  for (uint32_t i = 0; i < batch.cells(); ++i)
    for (uint32_t k = 0; k < L; ++k) {
      double withCv = gpuCell(results[kBoth], L, i).select(k);
      EXPECT_EQ(gpuCell(results[shared::kSolveLearnSelection], L, i).select(k), withCv);
      learnedDiffers += std::abs(withCv - batch.defaults[k]) > 1e-3;
      EXPECT_EQ(gpuCell(results[shared::kSolveControlVariate], L, i).alpha(k), gpuCell(results[kBoth], L, i).alpha(k));
    }
  EXPECT_GT(learnedDiffers, size_t(batch.cells())) << "learning should move the selection away from the defaults";
}

// shared/cms_solve.h compiled as C++ (float, like the GPU) agrees with the GPU run of the same code.
TEST_F(CmsSolve, SharedSolveCompiledAsCppAgreesWithTheGpu) {
  std::mt19937 rng(15);
  const uint32_t L = 6;
  Batch batch(L);
  for (uint32_t i = 0; i < 300; ++i) batch.add(sampledSystem(rng, L, 10 + i).stats(0.1, &rng), i % 50);
  SolveParams params = makeParams(L, kBoth, 1e-4f, 10, 0.1f);
  params.cellCount = batch.cells();
  std::vector<float> gpu = solveOnGpu(batch, params);
  std::vector<float> cpu(gpu.size(), kSentinel);
  std::vector<float> stats = batch.stats;
  std::vector<uint32_t> samples = batch.samples;
  cpu_float_solve::gStats = stats.data();
  cpu_float_solve::gSamples = samples.data();
  cpu_float_solve::gSolution = cpu.data();
  cpu_float_solve::gDefaults = batch.defaults.data();
  for (uint32_t i = 0; i < batch.cells(); ++i) shared::solveCell(i, params);
  for (uint32_t i = 0; i < batch.cells(); ++i) {
    GpuCell g = gpuCell(gpu, L, i), c = gpuCell(cpu, L, i);
    std::string where = "cell " + std::to_string(i);
    expectWellFormed(c, batch.defaults.data(), where);
    ASSERT_EQ(g.valid(), c.valid()) << where;
    EXPECT_LE(scaledError(batch.cell(i), L, gpuAlphas(g), gpuAlphas(c)), 1e-5) << where;
    for (uint32_t k = 0; k < L; ++k) EXPECT_NEAR(g.select(k), c.select(k), 1e-6) << where;
  }
}

// The cells after rendering `spp` samples of a shipped scene at 64x48 with `method` on `cells`.
WavefrontRenderer::CmsCellState renderedCells(VulkanContext& ctx, const std::string& scene, const std::string& method,
                                              uint32_t cells, uint32_t spp) {
  PreparedScene prepared = prepareScene(loadGltf(std::string(MIXTRACE_SOURCE_DIR) + "/scenes/" + scene));
  RenderSettings settings;
  settings.width = 64;
  settings.height = 48;
  settings.cells = cells;
  settings.cms = cmsMethodFor(method);
  // The per-cluster control variate these tests hold to the per-cluster solve and kCellSampleCap
  // (the per-triangle one, now the default on Vulkan too, is tests/e2e/cms_triangle_cv_test.cpp's).
  settings.perTriangleCv = false;
  MethodLights lights;
  lights.selection = buildLightSelection(prepared.lights, LightSelection::Power);
  lights.cms = setUpClusters(prepared, lights.selection, 16, settings.cms.defaults);
  WavefrontRenderer renderer(ctx, prepared, lights, settings);
  renderer.renderSamples(spp);
  return renderer.cmsCellState();
}

// The statistics a render actually gathers (many_lights, cms, after 6 spp: the cells hold the
// samples since the solve after spp 3, under the selections that solve kept or adopted), solved
// by the solve pass and by the double-precision reference: same decisions, same coefficients.
TEST_F(CmsSolve, StatisticsOfARenderMatchTheReference) {
  const WavefrontRenderer::CmsCellState state = renderedCells(*ctx_, "many_lights.gltf", "cms", 16, 6);
  const uint32_t L = state.clusters;
  ASSERT_EQ(L, 16u);
  Batch batch(L);
  batch.defaults = state.defaults;
  std::vector<float> initial;
  const uint32_t statsStride = shared::cellStatsStride(L), solStride = shared::cellSolutionStride(L);
  for (size_t slot = 0; slot < state.keys.size(); ++slot) {
    if (state.keys[slot] == 0) continue;
    batch.add(std::vector<float>(state.stats.begin() + slot * statsStride, state.stats.begin() + (slot + 1) * statsStride),
              state.samples[slot]);
    initial.insert(initial.end(), state.solution.begin() + slot * solStride, state.solution.begin() + (slot + 1) * solStride);
  }
  ASSERT_GT(batch.cells(), 20u) << "the render reached few cells";
  std::vector<float> statsAfter;
  std::vector<uint32_t> samplesAfter;
  std::vector<float> gpu = solveOnGpu(batch, state.params, &initial, &statsAfter, &samplesAfter);
  uint32_t valid = 0, kept = 0;
  for (uint32_t i = 0; i < batch.cells(); ++i) {
    std::string where = "cell " + std::to_string(i);
    GpuCell g = gpuCell(gpu, L, i);
    expectWellFormed(g, batch.defaults.data(), where, (state.params.flags & shared::kSolveBvhDefaults) != 0);
    const float* previous = &initial[size_t(i) * solStride + shared::solutionSelect(L, 0)];
    CellSolution ref = solveCellReference(batch.cell(i), batch.samples[i], L, state.params, batch.defaults.data(), previous);
    ASSERT_EQ(g.valid() == 1.0f, ref.valid) << where;
    EXPECT_EQ(samplesAfter[i] == 0 && batch.samples[i] > 0, ref.resetStatistics && batch.samples[i] > 0) << where;
    if (ref.valid) {
      ++valid;
      EXPECT_LE(scaledError(batch.cell(i), L, gpuAlphas(g), refAlphas(ref)), 1e-3) << where;
    }
    kept += !ref.resetStatistics;
    for (uint32_t k = 0; k < L; ++k) EXPECT_NEAR(g.select(k), ref.select[k], 1e-4) << where << " c_" << k;
  }
  EXPECT_GT(valid, batch.cells() / 4) << "most reached cells have enough samples to be solved";
  EXPECT_GT(kept, 0u) << "some cells keep their selection and statistics";
}

// A cell stops gathering once it holds kCellSampleCap vertices: its count stops there (up to
// the vertices of one pass that read the count at once), and the cell keeps being used.
TEST_F(CmsSolve, CellsStopGatheringAtTheCap) {
  // Few cells (2 along the longest axis), so they fill up; cv keeps its selection: no resets.
  const WavefrontRenderer::CmsCellState state = renderedCells(*ctx_, "cornell_box.gltf", "cv", 2, 24);
  uint32_t atCap = 0, most = 0;
  for (size_t slot = 0; slot < state.keys.size(); ++slot) {
    if (state.keys[slot] == 0) continue;
    most = std::max(most, state.samples[slot]);
    atCap += state.samples[slot] >= shared::kCellSampleCap;
  }
  EXPECT_GT(atCap, 0u) << "no cell reached the cap (largest " << most << ")";
  EXPECT_LE(most, shared::kCellSampleCap + 64u * 48u) << "a cell went on gathering";
}

// With a planned total, the last iteration gathers nothing: no solve would read it
// (cms/training_schedule.h). Planned 16: solves after 1, 3 and 7; samples 7..15 leave the cells'
// statistics and counts exactly as the solve after 7 left them. Unplanned, they go on gathering.
TEST_F(CmsSolve, ThePlannedLastIterationLeavesTheCellsAlone) {
  PreparedScene prepared = prepareScene(loadGltf(std::string(MIXTRACE_SOURCE_DIR) + "/scenes/veach_mis.gltf"));
  RenderSettings settings;
  settings.width = 64;
  settings.height = 48;
  settings.cms = cmsMethodFor("cms");
  MethodLights lights;
  lights.selection = buildLightSelection(prepared.lights, LightSelection::Power);
  lights.cms = setUpClusters(prepared, lights.selection, 16, settings.cms.defaults);
  for (bool planned : {true, false}) {
    WavefrontRenderer renderer(*ctx_, prepared, lights, settings);
    if (planned) renderer.planSamples(16);
    renderer.renderSamples(7);
    const WavefrontRenderer::CmsCellState trained = renderer.cmsCellState();
    renderer.renderSamples(9);
    const WavefrontRenderer::CmsCellState after = renderer.cmsCellState();
    uint64_t vertices = 0;
    for (uint32_t n : trained.samples) vertices += n;
    ASSERT_GT(vertices, 0u) << "the training iterations gathered nothing";
    if (planned) {
      EXPECT_EQ(after.samples, trained.samples);
      EXPECT_EQ(after.stats, trained.stats);
      EXPECT_EQ(after.solution, trained.solution) << "a solve ran after the last useful one";
    } else {
      EXPECT_NE(after.stats, trained.stats) << "an open-ended render stopped gathering";
    }
  }
}

// A cluster reached by almost no samples (A_kk ~ 1e-9 of the others: only a stray BSDF hit) next
// to a well-sampled BSDF technique: without a ridge its alpha_k ~ -A_kB alpha_B / A_kk is huge,
// and every light sample that picks it pays alpha_k / c_k (fireflies of 1e4 and more, seen on
// many_lights). The ridge, proportional to the mean diagonal, shrinks it to about 0 and leaves
// the well-sampled techniques nearly untouched.
TEST_F(CmsSolve, RidgeShrinksATechniqueWithAlmostNoSamples) {
  const uint32_t L = 3;
  std::vector<float> s(shared::cellStatsStride(L), 0.0f);
  s[shared::statsAkk(L, 0)] = 50.0f;
  s[shared::statsAkk(L, 1)] = 80.0f;
  s[shared::statsAkk(L, 2)] = 1e-9f;   // the stray one
  s[shared::statsAkB(L, 0)] = 5.0f;
  s[shared::statsAkB(L, 1)] = 4.0f;
  s[shared::statsAkB(L, 2)] = 1e-6f;
  s[shared::statsABB(L)] = 100.0f;
  for (int c = 0; c < 3; ++c) {
    s[shared::statsBk(L, 0, c)] = 10.0f;
    s[shared::statsBk(L, 1, c)] = 24.0f;
    s[shared::statsBk(L, 2, c)] = 0.0f;   // it carried no light
    s[shared::statsBB(L, c)] = 30.0f;
  }
  Batch batch(L);
  batch.add(s, 1000);
  batch.add(s, 1000);
  std::vector<float> noRidge = solveOnGpu(batch, makeParams(L, kBoth, 0.0f));
  std::vector<float> ridge = solveOnGpu(batch, makeParams(L, kBoth, 1e-3f));
  GpuCell a = gpuCell(noRidge, L, 0), b = gpuCell(ridge, L, 0);
  ASSERT_EQ(a.valid(), 1.0f);
  ASSERT_EQ(b.valid(), 1.0f);
  EXPECT_GT(std::abs(a.alpha(2).x), 100.0) << "without a ridge the stray cluster's alpha explodes";
  EXPECT_LT(std::abs(b.alpha(2).x), 1e-3) << "the ridge shrinks it";
  for (uint32_t k = 0; k < 2; ++k) EXPECT_NEAR(b.alpha(k).x, a.alpha(k).x, 0.01 * std::abs(a.alpha(k).x)) << k;
  EXPECT_NEAR(b.alphaB().x, a.alphaB().x, 0.01 * std::abs(a.alphaB().x));
  expectMatchesReference(b, batch.cell(0), 1000, makeParams(L, kBoth, 1e-3f), batch.defaults.data(), 1e-4, "ridge");
}

// More workgroups than a dispatch allows in x: the solver wraps them into y.
TEST_F(CmsSolve, CellCountBeyondOneDispatchRow) {
  uint32_t maxX = ctx_->properties().limits.maxComputeWorkGroupCount[0];
  if (uint64_t(maxX) * shared::kWorkgroupSize > 8000000u) GTEST_SKIP() << "device allows " << maxX << " workgroups in x";
  uint32_t cells = maxX * shared::kWorkgroupSize + 3 * shared::kWorkgroupSize + 5;
  Batch batch(0);
  batch.stats.resize(size_t(cells) * batch.stride());
  batch.samples.assign(cells, 1u);
  for (uint32_t i = 0; i < cells; ++i) {
    float* s = &batch.stats[size_t(i) * batch.stride()];
    s[shared::statsABB(0)] = 2.0f;
    for (int c = 0; c < 3; ++c) s[shared::statsBB(0, c)] = float(i % 1000000u) + c;
  }
  std::vector<float> gpu = solveOnGpu(batch, makeParams(0));
  size_t wrong = 0;
  for (uint32_t i = 0; i < cells; ++i) {
    GpuCell g = gpuCell(gpu, 0, i);
    for (int c = 0; c < 3; ++c) wrong += std::abs(g.alphaB()[c] - (i % 1000000u + c) / 2.0) > 1e-6 * (1.0 + i % 1000000u);
    wrong += g.valid() != 1.0f;
  }
  EXPECT_EQ(wrong, 0u);
}

TEST_F(CmsSolve, TooManyClustersIsAnError) {
  SolveParams params = makeParams(shared::kMaxClusters + 1);
  params.cellCount = 1;
  VkCommandBuffer cmd = ctx_->beginOneShot();
  EXPECT_THROW(solver_->record(cmd, params), Error);
  ctx_->endOneShotAndWait(cmd);
}

}  // namespace
