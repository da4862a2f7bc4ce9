// The sparse per-cell solve of the per-triangle control variate on the GPU (docs/estimator.md §4,
// §6; ../shared/cms.md §4), in float: the same rules as the double-precision reference
// host/cms/sparse_solve.cpp, whose header comment states them, computed by the stages below over
// the pair table's slots (shared/cms_pair_state.h) and over the cells, with per-cell sums gathered
// in a scratch buffer of the solve's own (SPARSE_SCRATCH, binding 43).
//
// The arrowhead system of a cell is solved exactly by eliminating its light techniques t:
//     alpha_B = (b_B - sum_t A_tB b_t / A_tt) / (A_BB - sum_t A_tB^2 / A_tt)
//     alpha_t = (b_t - A_tB alpha_B) / A_tt
// Jacobi-scaled and with the ridge r added to every diagonal entry. A cell's pairs are scattered
// over the hashed table, so every per-cell sum is an atomic add from the pair stages; a cell has no
// list of its pairs and needs none. Stages, each one dispatch of its own pipeline (SPEC_SPARSE_STAGE),
// a barrier between them:
//   kSparseInitCells   cells: the BSDF row (useB, A_BB as the first candidate of the maximum
//                      diagonal), every sum zeroed.
//   kSparseMaxPairs    pairs: the largest usable diagonal (atomicMax on the bits: for positive
//                      floats the order of the bits is the order of the values) and the count.
//   kSparseMeanPairs   pairs: sum of A_tt / max (in units of the maximum: cannot overflow).
//   kSparseRidgeCells  cells: r = ridge * mean diagonal, s_B.
//   kSparseSchurPairs  pairs: sum l_t^2 and sum l_t z_t (RGB), l_t = A_tB s_t s_B, z_t = b_t s_t.
//   kSparsePivotCells  cells: the Schur pivot 1 - sum l_t^2 (B dropped at or below
//                      kSolvePivotFloor), y_B, alpha_B.
//   kSparseAlphaPairs  pairs: alpha_t = (z_t - l_t y_B) s_t into PAIR_ALPHA, its finiteness, sum
//                      alpha_t (RGB) over triangle techniques, the solved flag of a triangle pair,
//                      and a solved pair's share Q_t added to its cluster's remainder pair, if any
//                      (whose sum kSparseMaxPairs zeroed).
//   kSparseRemainderPairs pairs: sum alpha_R P_R over the remainder techniques, P_R = 1 - the
//                      shares their solved pairs gave (clamped to [0, 1]; docs/estimator.md §4).
//   kSparseFinishCells cells: validity (min samples, a technique in the system, all finite, |sum
//                      alpha| <= kSolveMaxAlphaSum, the kSolveControlVariate flag); writes
//                      solutionAlphaB, solutionValid, solutionAlphaSum (zeros and 0 when invalid).
//   kSparseClearPairs  pairs: PAIR_ALPHA = 0 (and not solved) for the pairs of a cell that is not valid, so a
//                      reader never sees a coefficient its cell does not use (the double solve's
//                      alpha of an invalid cell is 0 everywhere, too).
// and, recorded apart after the per-cluster solve (host/wavefront/passes/sparse_solve_pass.h):
//   kSparseRestartPairs pairs: the statistics and sample count of every pair whose cell holds 0
//                      samples (the cluster solve restarted it: a new selection). Keys stay.
// The pair stages run one invocation per *occupied* slot, not per slot: the list of claimed slots
// (PAIR_OCCUPIED, shared/cms_pair_state.h) sizes them through an indirect dispatch whose
// arguments kSparsePairArgs (one invocation) writes from the list's count before the first pair
// stage (and again before the restart). A table is sized for the worst case (every cell seeing
// every technique) and is mostly empty: paper Veach MIS at 160x120 uses 112k of 4.2M slots.
// A slot whose key is empty, or names a cell >= cellCount, takes part in nothing. The sums are
// compare-and-swap loops on the bits (uint atomics: every device has them), so the pass needs no
// optional feature; contention is per cell, low for the usual tens of pairs per cell.
#ifndef MIXTRACE_SHARED_CMS_SPARSE_SOLVE_H
#define MIXTRACE_SHARED_CMS_SPARSE_SOLVE_H
#include "shared/buffer_table.h"
#include "shared/cms_pair_layout.h"
#include "shared/cms_solve.h"   // the policy constants, cmsUsableDiagonal, cmsScale, cmsCoupling (no buffers)
#include "shared/dialect.h"

// The per-cell scratch, uints (floats as their bits), kSparseScratchStride per cell; owned and
// sized by the solve (host/wavefront/passes/sparse_solve_pass.cpp).
#define BUFFER_SPARSE_SCRATCH(X) \
  X(SPARSE_SCRATCH, sparseScratch, 43, READ_WRITE, uint, CELL_SCRATCH, "CMS sparse solve scratch")

// The pair stages' indirect dispatch arguments (VkDispatchIndirectCommand: groups x, y, z), written
// by kSparsePairArgs; owned by the solve.
#define BUFFER_SPARSE_ARGS(X) \
  X(SPARSE_ARGS, sparseArgs, 45, READ_WRITE, uint, DISPATCH_ARGS, "CMS sparse solve dispatch arguments")

SHARED_BEGIN
BUFFER_SPARSE_SCRATCH(BUFFER_BINDING_CONSTANT)
BUFFER_SPARSE_ARGS(BUFFER_BINDING_CONSTANT)

// Scratch slots of one cell.
const uint kSparseMaxDiagonal = 0u;   // float bits: the largest usable diagonal (A_BB included)
const uint kSparsePairsIn = 1u;       // uint: usable light techniques (pairs); + B: the ridge's count
const uint kSparseUnused = 2u;
const uint kSparseFlags = 3u;         // uint: kSparseFlag*
const uint kSparseDiagonalSum = 4u;   // float: sum of the pairs' A_tt / max diagonal
const uint kSparseRidge = 5u;         // float: r
const uint kSparseScaleB = 6u;        // float: s_B (0 when B is out)
const uint kSparseSumL2 = 7u;         // float: sum l_t^2
const uint kSparseSumLZ = 8u;         // float x3: sum l_t z_t, RGB
const uint kSparseYB = 11u;           // float x3: y_B, RGB (0 when B is out)
const uint kSparseAlphaSum = 14u;     // float x3: sum alpha_t + alpha_B, RGB
const uint kSparseScratchStride = 17u;

const uint kSparseFlagUseB = 1u;        // the BSDF technique is in the system
const uint kSparseFlagNonFinite = 2u;   // some alpha is not finite (the cell is invalid)
const uint kSparseFlagValid = 4u;       // the cell's control variate is used (written by the last cell stage)

// The stage a pipeline of the pass runs: a specialization constant, one pipeline per stage, so
// that each is compiled alone (lavapipe runs every branch of a shader with masks: a stage chosen
// by a push constant cost the sum of all stages). After the renderer's constant ids (SPEC_COUNT;
// sparse_solve_pass.cpp checks).
#define SPEC_SPARSE_STAGE 16   // room for the renderer's ids to grow
// Its values.
const uint kSparseInitCells = 0u;
const uint kSparseMaxPairs = 1u;
const uint kSparseMeanPairs = 2u;
const uint kSparseRidgeCells = 3u;
const uint kSparseSchurPairs = 4u;
const uint kSparsePivotCells = 5u;
const uint kSparseAlphaPairs = 6u;
const uint kSparseFinishCells = 7u;
const uint kSparseClearPairs = 8u;
const uint kSparseRestartPairs = 9u;
const uint kSparsePairArgs = 10u;   // one invocation: the pair stages' dispatch from the occupied count
const uint kSparseRemainderPairs = 11u;
const uint kSparseStageCount = 12u;

// Push constants of the sparse solve pass (cms/sparse_solve_interface.h).
struct SparseSolveConstants {
  uint cellCount;
  uint clusterCount;          // L of the cell statistics and solutions (shared/cms_layouts.h)
  uint pairCapacity;          // slots of the pair table (a power of two)
  uint minSamples;            // CELL_SAMPLES below this: the cell is invalid
  uint minTechniqueSamples;   // PAIR_SAMPLES below this: the technique is dropped (alpha_t = 0)
  uint flags;                 // kSolveControlVariate: write the solution; else zeros, invalid
  float ridge;                // relative to the mean diagonal of the techniques in the system
  uint maxGroupsX;            // the device's maxComputeWorkGroupCount[0]: kSparsePairArgs wraps into y past it
};

// The 2D grid of `groups` workgroups on a device with at most `maxX` in x (the rest wrap into y; the
// shader recovers the item from both): the host's dispatches of the cell stages and
// kSparsePairArgs's indirect dispatch of the pair stages use the same one.
SHARED_FN uvec2 sparseDispatchGrid(uint groups, uint maxX) {
  uvec2 grid;
  grid.x = min(groups, maxX);
  grid.y = grid.x == 0u ? 0u : (groups + grid.x - 1u) / grid.x;
  return grid;
}

// Whether a pair's statistics let its technique take part (the rules of host/cms/sparse_solve.h).
SHARED_FN bool sparsePairUsable(uint samples, uint minTechniqueSamples, float aTT, float aTB, vec3 bT) {
  return samples >= minTechniqueSamples && cmsUsableDiagonal(aTT) && cmsIsFinite(aTB) && cmsIsFinite3(bT);
}

SHARED_END
#endif
