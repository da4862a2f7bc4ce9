// Controlled mixture sampling (docs/estimator.md): the per-cell statistics the shade pass adds
// to, the coefficients the solve pass writes, and the light clusters, as flat float/uint arrays
// with index functions (their size depends on the cluster count L, so they are not fixed structs;
// no layout check applies to them beyond their element type).
// Shared by the GPU passes, the CPU reference and the tests.
#ifndef MIXTRACE_SHARED_CMS_LAYOUTS_H
#define MIXTRACE_SHARED_CMS_LAYOUTS_H
#include "shared/dialect.h"
SHARED_BEGIN

// "No cell": a vertex the cell table refused, a pixel whose ray escaped, a sample in no cluster.
const uint kNoCell = 0xffffffffu;

// Capacity of the per-cell systems; --max-clusters chooses L <= kMaxClusters.
const uint kMaxClusters = 32u;

// A cell stops gathering statistics once this many vertices added to them since its last reset
// (a new selection resets it): its coefficients have converged, and every later sample would
// only pay for the atomics. About the per-cell budget of the paper, which trains for 16 spp at
// 640x480 and then stops updating. Measured (160x120, 64 spp, 2 seeds): relMSE unchanged in the
// third digit on Veach MIS (0.0297) and many_lights (0.0079) with caps of 4096 and 16384.
const uint kCellSampleCap = 4096u;

// Statistics of one cell (docs/estimator.md §4), floats, L clusters plus the BSDF technique B. A
// is the arrowhead matrix over (p_1 .. p_L, p_B): clusters are disjoint, so only A_kk, A_kB, A_BB
// exist.
//   [0, L)            A_kk
//   [L, 2L)           A_kB
//   2L                A_BB
//   [2L+1, 5L+1)      b_k, RGB (b_k.r at 2L+1+3k)
//   [5L+1, 5L+4)      b_B, RGB
// The number of samples a cell received is kept apart, as a uint (cellSampleCount buffer), so it
// stays exact past 2^24.
SHARED_FN uint cellStatsStride(uint L) { return 5u * L + 4u; }
SHARED_FN uint statsAkk(uint L, uint k) { return k; }
SHARED_FN uint statsAkB(uint L, uint k) { return L + k; }
SHARED_FN uint statsABB(uint L) { return 2u * L; }
SHARED_FN uint statsBk(uint L, uint k, uint channel) { return 2u * L + 1u + 3u * k + channel; }
SHARED_FN uint statsBB(uint L, uint channel) { return 5u * L + 1u + channel; }

// Solved coefficients of one cell, floats (written by the solve pass, read by the next iteration):
//   [0, 3L)           alpha_k, RGB
//   [3L, 3L+3)        alpha_B, RGB
//   [3L+3, 4L+3)      selection pmf c_k over clusters (sums to 1)
//   4L+3              1 when alpha is valid for this cell (else the cell uses no control variate)
//   [4L+4, 4L+7)      sum_k alpha_k + alpha_B, RGB: the control variate's integral, added at every
//                     vertex (stored so the shade pass reads 3 floats, not 3L+3)
SHARED_FN uint cellSolutionStride(uint L) { return 4u * L + 7u; }
SHARED_FN uint solutionAlpha(uint L, uint k, uint channel) { return 3u * k + channel; }
SHARED_FN uint solutionAlphaB(uint L, uint channel) { return 3u * L + channel; }
SHARED_FN uint solutionSelect(uint L, uint k) { return 3u * L + 3u + k; }
SHARED_FN uint solutionValid(uint L) { return 4u * L + 3u; }
SHARED_FN uint solutionAlphaSum(uint L, uint channel) { return 4u * L + 4u + channel; }

// Solve pass flags (SolveParams.flags).
const uint kSolveLearnSelection = 1u;   // write learned c_k (methods learned, cms); else the defaults
const uint kSolveControlVariate = 2u;   // write alpha (methods cv, cms); else alpha = 0, invalid
// The control variate is the sparse solve's (one technique per emissive triangle, shared/cms_sparse_solve.h,
// recorded before this solve): selection and restarts as always, alpha_k only feed the selection
// weights (the slots end as without kSolveControlVariate), and solutionAlphaB, solutionValid and
// solutionAlphaSum keep what the sparse solve wrote. Overrides kSolveControlVariate.
const uint kSolveKeepControlVariate = 4u;
// The defaults are the light BVH at each vertex (shared/cms_sampling.h): the selection slots hold
// only the learned part, c_k = (1 - eps) w_k / sum w (all 0 while the cell has learned nothing),
// and the rest of the probability, delta = 1 - sum c_k, is the defaults'.
const uint kSolveBvhDefaults = 8u;

// Push constants of the solve pass (cms/solve_interface.h): the whole range of its pipeline layout
// (host/vulkan/layout_checks.cpp checks that it fits the guaranteed 128 bytes).
struct SolveParams {
  uint cellCount;
  uint clusterCount;     // L
  uint minSamples;       // below this many samples a cell keeps no control variate
  uint flags;            // kSolve*
  float ridge;           // Tikhonov term, relative to the mean of the scaled diagonal
  float defensive;       // epsilon of docs/estimator.md §7: the default selection's share in c_k
  float pad0;
  float pad1;
};

// The weight of a vertex's samples in its cell's statistics (docs/estimator.md §5): the squared
// path throughput relative to a rough estimate of the pixel, so a cell minimises the summed
// relative variance of the pixels it feeds. Any weight keeps the estimator unbiased.
SHARED_FN float relativeSampleWeight(vec3 throughput, vec3 pixelEstimate) {
  vec3 r = throughput / (vec3(0.01f) + max(pixelEstimate, vec3(0.0f)));
  return (r.x * r.x + r.y * r.y + r.z * r.z) * (1.0f / 3.0f);
}

SHARED_END
#endif
