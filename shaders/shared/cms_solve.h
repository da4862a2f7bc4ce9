// The per-cell solve of controlled mixture sampling (docs/estimator.md §4, §6, §7), in float, as
// the solve pass runs it (shaders/cms/solve.comp, one invocation per cell). The double-precision
// reference (host/cms/reference_solve.cpp) implements the same rules independently and shares
// only the policy constants below.
//
// Rules, per cell (each keeps the estimator unbiased: any alpha is, docs/estimator.md §6):
//   - A technique whose diagonal entry is not a positive normal float, or whose row holds a NaN or
//     Inf (A_kk, A_kB, b_k for a cluster; A_BB, b_B for the BSDF technique), has no usable samples
//     and is dropped from the system: its alpha is 0.
//   - Ridge (docs/estimator.md §6): r = ridge * the mean diagonal entry of the techniques in the
//     system is added to every diagonal entry. Proportional to the trace, it shrinks the alpha of a technique
//     with few samples (A_kk << the others: a cluster a rarely chosen light sample or a stray BSDF
//     hit reached) towards 0, where a ridge relative to each technique's own diagonal would not: a
//     cluster with A_kk ~ 1e-9 otherwise gets alpha_k ~ -A_kB alpha_B / A_kk, and its light samples
//     pay alpha_k / c_k, fireflies of 1e4 and more.
//   - Jacobi scaling: with D = diag(A) + r, solve (D^-1/2 (A + r I) D^-1/2) y = D^-1/2 b and set
//     alpha = D^-1/2 y. The scaled diagonal is exactly 1.
//   - The arrowhead Cholesky factor is O(L): L_kk = 1, L_Bk = A'_kB,
//     L_BB = sqrt(1 - sum_k L_Bk^2). A pivot L_BB^2 <= kSolvePivotFloor
//     (singular or nearly so: B is a combination of the clusters) drops B; the clusters then
//     decouple. Factored once, solved for the three RGB right-hand sides.
//   - The cell is solved when it has at least minSamples samples, at least one technique in the
//     system, a finite alpha everywhere and |sum of alpha| <= kSolveMaxAlphaSum. Unsolved cells write alpha = 0, valid = 0.
//   - With kSolveControlVariate the solved alpha is written and valid = 1; without it alpha = 0
//     and valid = 0, but the solve still runs: its alpha feeds the learned selection ("learned"
//     method, selection without a control variate).
//   - With kSolveKeepControlVariate (the per-triangle control variate, shared/cms_sparse_solve.h)
//     everything runs as without kSolveControlVariate, but alpha_B, valid and the sum of alpha are
//     left as the sparse solve wrote them.
//   - Selection: with kSolveLearnSelection and a solved cell whose weights w_k = max(lum(alpha_k), 0)
//     have a positive finite sum, c_k = (1 - eps) w_k / sum w + eps d_k; otherwise c_k = d_k. The
//     defaults d are sanitised (non-finite or negative entries count as 0) and normalised (uniform
//     when they sum to 0); eps is clamped to [kSolveMinDefensive, 1] so that every cluster with
//     d_k > 0 keeps c_k > 0 (a light that can never be selected would bias the estimate); c is
//     normalised to sum 1. With kSolveBvhDefaults only the learned part is stored, c_k =
//     (1 - eps) w_k / sum w when learning and 0 otherwise, not normalised: the rest, 1 - sum c_k,
//     is the share of the defaults, the light BVH at each vertex (shared/cms_sampling.h), and
//     counts as one more entry of the selection in the total-variation test below.
//   - Statistics persist across iterations (more samples, better alpha) as long as they estimate
//     the same system. A and b depend on the selection through p_eff, so when the new selection
//     differs from the one the cell used so far by more than kSelectionChangeThreshold in total
//     variation (or the cell had no valid selection yet), the cell adopts it and its statistics
//     and sample count are reset (docs/estimator.md §7); otherwise, and while the cell is unsolved,
//     it keeps the old selection and its statistics keep accumulating. With fixed defaults (no
//     kSolveLearnSelection) a cell never resets. A non-finite alpha also resets the statistics.
// Every output is finite for any input.
#ifndef MIXTRACE_SHARED_CMS_SOLVE_H
#define MIXTRACE_SHARED_CMS_SOLVE_H
#include "shared/cms_layouts.h"
#include "shared/constants.h"
#include "shared/dialect.h"
#include "shared/sampling.h"
SHARED_BEGIN

// Smallest diagonal entry a technique needs to take part: the smallest normal float. Below it
// 1/sqrt overflows, and GPUs may flush the value to 0 anyway.
const float kSolveMinDiagonal = 1.17549435e-38f;
// A Schur pivot (scaled, so between 0 and 1 for a consistent system) at or below this means B is
// (numerically) a combination of the clusters: B is dropped. Float cancellation in
// 1 - sum L_Bk^2 is ~1e-6 for L = 32, so smaller pivots are noise.
const float kSolvePivotFloor = 1e-5f;
// Largest |sum of alpha| (per channel) a solved cell may have; radiance beyond is not physical.
const float kSolveMaxAlphaSum = 1e30f;
// Lower bound of the defensive fraction: keeps c_k > 0 wherever the default is.
const float kSolveMinDefensive = 1e-3f;
// Total-variation distance between a cell's new and old selection above which it adopts the new
// one and restarts its statistics. Smaller changes barely move the variance, and keeping the old
// selection lets the statistics, and so alpha, keep improving.
const float kSelectionChangeThreshold = 0.05f;

SHARED_FN bool cmsIsFinite(float x) {
#ifdef __cplusplus
  return std::isfinite(x);
#else
  return !isnan(x) && !isinf(x);
#endif
}

SHARED_FN bool cmsIsFinite3(vec3 v) { return cmsIsFinite(v.x) && cmsIsFinite(v.y) && cmsIsFinite(v.z); }

// A diagonal entry of A that lets its technique take part in the system.
SHARED_FN bool cmsUsableDiagonal(float a) { return cmsIsFinite(a) && a >= kSolveMinDiagonal; }

// The Jacobi scale of a diagonal entry a with the ridge r: (a + r)^-1/2, as a^-1/2 (1 + r/a)^-1/2
// so that neither a + r nor a tiny a underflowing against a large one is ever formed (r/a may
// overflow to Inf: the scale is then 0, the technique's alpha 0). Both solves use it.
SHARED_FN float cmsScale(float ridge, float a) { return (1.0f / sqrt(a)) / sqrt(1.0f + ridge / a); }

// A technique's coupling with B in the scaled system, A_tB s_t s_B. The product s_t s_B alone is
// denormal when both diagonals are near FLT_MAX (s ~ 2^-64 each), and GPUs flush denormals to 0
// (so does lavapipe, host/vulkan/denormal_mode.h): A_tB is multiplied by the smaller scale first.
// That product overflows only where the coupling itself does, and it is exactly 0 when B is out
// (s_B = 0; A_tB is finite for a usable technique).
SHARED_FN float cmsCoupling(float aTB, float st, float sB) { return (aTB * min(st, sB)) * max(st, sB); }

SHARED_END

// The solve itself reads and writes the cell buffers through accessors the includer defines:
// CELL_STATS(i), CELL_SAMPLES(cell), CELL_SOLUTION(i) (assignable), CLUSTER_DEFAULT(k).
#ifdef CELL_STATS
SHARED_BEGIN_WITH_BUFFERS

SHARED_FN vec3 cmsReadStats3(uint i) {
  vec3 v;
  v.x = CELL_STATS(i);
  v.y = CELL_STATS(i + 1u);
  v.z = CELL_STATS(i + 2u);
  return v;
}

SHARED_FN vec3 cmsReadSolution3(uint i) {
  vec3 v;
  v.x = CELL_SOLUTION(i);
  v.y = CELL_SOLUTION(i + 1u);
  v.z = CELL_SOLUTION(i + 2u);
  return v;
}

SHARED_FN void cmsWriteSolution3(uint i, vec3 v) {
  CELL_SOLUTION(i) = v.x;
  CELL_SOLUTION(i + 1u) = v.y;
  CELL_SOLUTION(i + 2u) = v.z;
}

// Whether cluster k has usable samples: a usable diagonal, and a finite row and right-hand side.
SHARED_FN bool cmsClusterUsable(uint stats, uint L, uint k) {
  return cmsUsableDiagonal(CELL_STATS(stats + statsAkk(L, k))) && cmsIsFinite(CELL_STATS(stats + statsAkB(L, k))) &&
         cmsIsFinite3(cmsReadStats3(stats + statsBk(L, k, 0u)));
}

// Row k of the scaled system and its forward substitution: sk = (A_kk + r)^-1/2, lBk = L_Bk (0 when
// B is not in the system, sB = 0), zk = b'_k. False when cluster k has no usable samples.
SHARED_FN bool cmsClusterRow(uint stats, uint L, uint k, float sB, float ridge, OUT(float) sk, OUT(float) lBk,
                             OUT(vec3) zk) {
  sk = 0.0f;
  lBk = 0.0f;
  zk = vec3(0.0f);
  if (!cmsClusterUsable(stats, L, k)) return false;
  sk = cmsScale(ridge, CELL_STATS(stats + statsAkk(L, k)));
  lBk = cmsCoupling(CELL_STATS(stats + statsAkB(L, k)), sk, sB);
  zk = cmsReadStats3(stats + statsBk(L, k, 0u)) * sk;
  return true;
}

// The weight of a cluster in a learned selection: its share of the direct light, never negative.
SHARED_FN float cmsSelectionWeight(vec3 alpha) {
  float weight = max(luminance(alpha), 0.0f);
  return cmsIsFinite(weight) ? weight : 0.0f;
}

// c_k before normalisation: the defaults d (sanitised, normalised) or, when learning,
// (1 - eps) w_k / sum w + eps d_k with w_k from the alpha just written to the solution.
SHARED_FN float cmsNewSelection(uint solution, uint L, uint k, bool learn, float eps, float weightSum,
                                bool uniformDefaults, float defaultSum, bool bvhDefaults) {
  float learned = learn ? (1.0f - eps) * (cmsSelectionWeight(cmsReadSolution3(solution + solutionAlpha(L, k, 0u))) / weightSum)
                        : 0.0f;
  if (bvhDefaults) return learned;   // the defaults' share is the rest, 1 - sum c
  float raw = CLUSTER_DEFAULT(k);
  bool positive = uniformDefaults || (cmsIsFinite(raw) && raw > 0.0f);
  float d = uniformDefaults ? 1.0f / float(L) : (positive ? raw / defaultSum : 0.0f);
  float c = learn ? learned + eps * d : d;
  // eps * d, and a tiny default over the sum, can underflow: a cluster with a positive default
  // must stay selectable.
  if (positive) c = max(c, 1e-30f);
  return c;
}

// Solves cell `cell` of the buffers (layouts in shared/cms_layouts.h) and writes its solution.
SHARED_FN void solveCell(uint cell, SolveParams params) {
  uint L = params.clusterCount;
  uint stats = cell * cellStatsStride(L);
  uint solution = cell * cellSolutionStride(L);
  float ridge = (cmsIsFinite(params.ridge) && params.ridge > 0.0f) ? params.ridge : 0.0f;

  // The BSDF technique, last row of the arrowhead.
  float aBB = CELL_STATS(stats + statsABB(L));
  vec3 bB = cmsReadStats3(stats + statsBB(L, 0u));
  bool useB = cmsUsableDiagonal(aBB) && cmsIsFinite3(bB);

  // The ridge r: ridge times the mean diagonal entry of the techniques in the system (summed in
  // units of the largest entry M, so the sum cannot overflow).
  float maxDiag = useB ? aBB : 0.0f;
  for (uint k = 0u; k < L; ++k)
    if (cmsClusterUsable(stats, L, k)) maxDiag = max(maxDiag, CELL_STATS(stats + statsAkk(L, k)));
  // Divided, not multiplied by 1 / max: near FLT_MAX that reciprocal is denormal, which GPUs flush.
  float meanOverMax = useB ? aBB / maxDiag : 0.0f;
  float usable = useB ? 1.0f : 0.0f;
  for (uint k = 0u; k < L; ++k)
    if (cmsClusterUsable(stats, L, k)) {
      meanOverMax += CELL_STATS(stats + statsAkk(L, k)) / maxDiag;
      usable += 1.0f;
    }
  float r = usable > 0.0f ? (ridge * (meanOverMax / usable)) * maxDiag : 0.0f;
  float sB = useB ? cmsScale(r, aBB) : 0.0f;

  // Forward pass: the Schur pivot of B and sum_k L_Bk z_k.
  uint inSystem = 0u;
  float sumLBk2 = 0.0f;
  vec3 sumLBkZk = vec3(0.0f);
  for (uint k = 0u; k < L; ++k) {
    float sk;
    float lBk;
    vec3 zk;
    if (!cmsClusterRow(stats, L, k, sB, r, sk, lBk, zk)) continue;
    inSystem += 1u;
    sumLBk2 += lBk * lBk;
    sumLBkZk += lBk * zk;
  }
  float pivot = 1.0f - sumLBk2;
  if (useB && !(pivot > kSolvePivotFloor)) {
    useB = false;   // singular: B adds nothing the clusters cannot express
    sB = 0.0f;
  }
  vec3 yB = vec3(0.0f);
  if (useB) {
    inSystem += 1u;
    float lBB = sqrt(pivot);
    vec3 zB = (bB * sB - sumLBkZk) / lBB;
    yB = zB / lBB;
  }
  vec3 alphaB = yB * sB;

  // Back substitution. Alpha goes straight to the solution (the passes below read it back for the
  // selection weights, and zero it when the cell turns out unsolved); the selection slots still
  // hold the cell's old selection.
  bool allFinite = cmsIsFinite3(alphaB);
  float weightSum = 0.0f;
  vec3 alphaSum = alphaB;
  for (uint k = 0u; k < L; ++k) {
    float sk;
    float lBk;
    vec3 zk;
    vec3 alpha = vec3(0.0f);
    if (cmsClusterRow(stats, L, k, sB, r, sk, lBk, zk)) alpha = (zk - lBk * yB) * sk;
    allFinite = allFinite && cmsIsFinite3(alpha);
    cmsWriteSolution3(solution + solutionAlpha(L, k, 0u), alpha);
    weightSum += cmsSelectionWeight(alpha);
    alphaSum += alpha;
  }
  // Every vertex adds the sum: it must be finite too, with room (the bound keeps the float and
  // double solves from disagreeing about sums that round to infinity in one of them).
  allFinite = allFinite && cmsIsFinite3(alphaSum) && max(max(abs(alphaSum.x), abs(alphaSum.y)), abs(alphaSum.z)) <= kSolveMaxAlphaSum;

  bool solved = CELL_SAMPLES(cell) >= params.minSamples && inSystem > 0u && allFinite;
  bool keepControlVariate = (params.flags & kSolveKeepControlVariate) != 0u;
  bool writeAlpha = solved && (params.flags & kSolveControlVariate) != 0u && !keepControlVariate;
  bool learn = solved && (params.flags & kSolveLearnSelection) != 0u && weightSum > 0.0f && cmsIsFinite(weightSum);

  // The defaults, sanitised and normalised.
  float defaultSum = 0.0f;
  for (uint k = 0u; k < L; ++k) {
    float d = CLUSTER_DEFAULT(k);
    if (cmsIsFinite(d) && d > 0.0f) defaultSum += d;
  }
  bool uniformDefaults = !(defaultSum > 0.0f) || !cmsIsFinite(defaultSum);
  float eps = cmsIsFinite(params.defensive) ? clamp(params.defensive, kSolveMinDefensive, 1.0f) : 1.0f;

  // The new selection (unnormalised here, divided by selectSum; with the BVH defaults stored as it
  // is), and its distance to the old one.
  bool bvhDefaults = (params.flags & kSolveBvhDefaults) != 0u;
  float selectSum = 0.0f;
  float oldSum = 0.0f;
  bool oldUsable = true;
  for (uint k = 0u; k < L; ++k) {
    selectSum += cmsNewSelection(solution, L, k, learn, eps, weightSum, uniformDefaults, defaultSum, bvhDefaults);
    float old = CELL_SOLUTION(solution + solutionSelect(L, k));
    oldUsable = oldUsable && cmsIsFinite(old) && old >= 0.0f;
    if (oldUsable) oldSum += old;
  }
  float norm = bvhDefaults ? 1.0f : selectSum;
  float change = 0.0f;
  for (uint k = 0u; k < L; ++k) {
    float c = cmsNewSelection(solution, L, k, learn, eps, weightSum, uniformDefaults, defaultSum, bvhDefaults) / norm;
    float old = CELL_SOLUTION(solution + solutionSelect(L, k));
    if (oldUsable) change += abs(c - old);
  }
  if (bvhDefaults && oldUsable) change += abs((1.0f - selectSum) - (1.0f - oldSum));   // the defaults' share
  // A cell without a valid selection yet adopts the new one; a solved cell adopts it when it moved
  // far enough; an unsolved one (too few samples so far) keeps its selection and accumulates on.
  bool oldValid = oldUsable && (bvhDefaults ? oldSum <= 1.0f + 1e-3f : abs(oldSum - 1.0f) <= 1e-3f);
  bool adopt = !oldValid || (solved && !(0.5f * change <= kSelectionChangeThreshold));
  for (uint k = 0u; k < L; ++k) {
    if (adopt)
      CELL_SOLUTION(solution + solutionSelect(L, k)) =
          cmsNewSelection(solution, L, k, learn, eps, weightSum, uniformDefaults, defaultSum, bvhDefaults) / norm;
    if (!writeAlpha) cmsWriteSolution3(solution + solutionAlpha(L, k, 0u), vec3(0.0f));
  }
  // Statistics holding NaN/Inf would keep the cell unsolved for good: they restart too.
  if (adopt || !allFinite) {
    for (uint i = 0u; i < cellStatsStride(L); ++i) CELL_STATS(stats + i) = 0.0f;
    CELL_SAMPLES(cell) = 0u;
  }

  if (keepControlVariate) return;   // the sparse solve's control variate stays
  cmsWriteSolution3(solution + solutionAlphaB(L, 0u), writeAlpha ? alphaB : vec3(0.0f));
  CELL_SOLUTION(solution + solutionValid(L)) = writeAlpha ? 1.0f : 0.0f;
  cmsWriteSolution3(solution + solutionAlphaSum(L, 0u), writeAlpha ? alphaSum : vec3(0.0f));
}

SHARED_END_WITH_BUFFERS
#endif  // CELL_STATS

#endif
