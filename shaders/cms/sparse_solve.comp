#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require   // cms_pair_table.h's insert (unused here) names the 64-bit swap
// The sparse per-cell solve of the per-triangle control variate (the stages, the maths and the
// scratch layout: shared/cms_sparse_solve.h; the rules: host/cms/sparse_solve.h). One pipeline,
// one dispatch per stage (STAGE): one invocation per cell or per occupied pair-table slot, spread over a
// 2D grid of workgroups so that any count fits the dispatch limits (host/wavefront/passes/sparse_solve_pass.cpp).
#include "cms/sparse_solve_interface.h"
#define PASS_BUFFERS SPARSE_SOLVE_BUFFERS
#define PASS_CONSTANTS SparseSolveConstants
#include "gpu/buffers.glsl"
// findPair: a solved pair's remainder pair (the solve never inserts).
#include "gpu/pair_table_access.glsl"
#include "shared/cms_pair_table.h"

layout(local_size_x = kWorkgroupSize) in;
layout(constant_id = SPEC_SPARSE_STAGE) const uint STAGE = kSparseInitCells;

// ---- the per-cell scratch

uint scratchIndex(uint cell, uint slot) { return cell * kSparseScratchStride + slot; }
float scratchFloat(uint cell, uint slot) { return uintBitsToFloat(sparseScratch[scratchIndex(cell, slot)]); }
vec3 scratchFloat3(uint cell, uint slot) {
  return vec3(scratchFloat(cell, slot), scratchFloat(cell, slot + 1u), scratchFloat(cell, slot + 2u));
}
void setScratchFloat(uint cell, uint slot, float v) { sparseScratch[scratchIndex(cell, slot)] = floatBitsToUint(v); }
void setScratchFloat3(uint cell, uint slot, vec3 v) {
  setScratchFloat(cell, slot, v.x);
  setScratchFloat(cell, slot + 1u, v.y);
  setScratchFloat(cell, slot + 2u, v.z);
}
uint scratchFlags(uint cell) { return sparseScratch[scratchIndex(cell, kSparseFlags)]; }

// A float add on a scratch slot by compare-and-swap on its bits (no float atomics needed).
void scratchAdd(uint cell, uint slot, float value) {
  if (value == 0.0) return;
  uint i = scratchIndex(cell, slot);
  uint seen = sparseScratch[i];
  for (;;) {
    uint expected = seen;
    seen = atomicCompSwap(sparseScratch[i], expected, floatBitsToUint(uintBitsToFloat(expected) + value));
    if (seen == expected) break;
  }
}
void scratchAdd3(uint cell, uint slot, vec3 v) {
  scratchAdd(cell, slot, v.x);
  scratchAdd(cell, slot + 1u, v.y);
  scratchAdd(cell, slot + 2u, v.z);
}

// ---- the BSDF row of a cell (its statistics, shared/cms_layouts.h)

float cellABB(uint cell) { return cellStats[cell * cellStatsStride(pc.clusterCount) + statsABB(pc.clusterCount)]; }
vec3 cellBB(uint cell) {
  uint i = cell * cellStatsStride(pc.clusterCount) + statsBB(pc.clusterCount, 0u);
  return vec3(cellStats[i], cellStats[i + 1u], cellStats[i + 2u]);
}

// ---- one pair slot

struct Pair {
  uint cell;
  uint technique;
  float aTT;
  float aTB;
  vec3 bT;
  bool usable;
};

// False for an empty slot, or one whose cell is not among the cells solved.
bool readPair(uint slot, out Pair p) {
  uint64_t key = pairKeys[slot];
  p.cell = kNoCell;
  p.usable = false;
  if (key == uint64_t(0)) return false;
  p.cell = pairKeyCell(key);
  p.technique = pairKeyTechnique(key);
  if (p.cell >= pc.cellCount) return false;
  p.aTT = pairStats[pairStatsAtt(slot)];
  p.aTB = pairStats[pairStatsAtB(slot)];
  p.bT = vec3(pairStats[pairStatsBt(slot, 0u)], pairStats[pairStatsBt(slot, 1u)], pairStats[pairStatsBt(slot, 2u)]);
  p.usable = sparsePairUsable(pairSamples[slot], pc.minTechniqueSamples, p.aTT, p.aTB, p.bT);
  return true;
}

void writePairAlpha(uint slot, vec3 alpha) {
  pairAlpha[pairAlphaIndex(slot, 0u)] = alpha.x;
  pairAlpha[pairAlphaIndex(slot, 1u)] = alpha.y;
  pairAlpha[pairAlphaIndex(slot, 2u)] = alpha.z;
}

// The fourth float of a slot's coefficients (shared/cms_pair_state.h): a triangle pair's solved
// flag, a remainder pair's sum of the shares Q_t of its cluster's solved pairs, gathered through
// this uint view of the same buffer by compare-and-swap on the bits.
layout(scalar, binding = BINDING_PAIR_ALPHA) buffer PairAlphaBits { uint pairAlphaBits[]; };

void addSolvedShare(uint remainderSlot, float share) {
  uint i = pairSolvedIndex(remainderSlot);
  uint seen = pairAlphaBits[i];
  for (;;) {
    uint expected = seen;
    seen = atomicCompSwap(pairAlphaBits[i], expected, floatBitsToUint(uintBitsToFloat(expected) + share));
    if (seen == expected) break;
  }
}

// s_t, l_t = A_tB s_t s_B and z_t = b_t s_t of a usable pair.
void pairRow(Pair p, out float st, out float lt, out vec3 zt) {
  st = cmsScale(scratchFloat(p.cell, kSparseRidge), p.aTT);
  lt = cmsCoupling(p.aTB, st, scratchFloat(p.cell, kSparseScaleB));
  zt = p.bT * st;
}

// ---- the stages

void initCell(uint cell) {
  float aBB = cellABB(cell);
  bool useB = cmsUsableDiagonal(aBB) && cmsIsFinite3(cellBB(cell));
  for (uint i = 0u; i < kSparseScratchStride; ++i) sparseScratch[scratchIndex(cell, i)] = 0u;
  sparseScratch[scratchIndex(cell, kSparseMaxDiagonal)] = useB ? floatBitsToUint(aBB) : 0u;
  sparseScratch[scratchIndex(cell, kSparseFlags)] = useB ? kSparseFlagUseB : 0u;
}

void ridgeCell(uint cell) {
  bool useB = (scratchFlags(cell) & kSparseFlagUseB) != 0u;
  float maxDiag = scratchFloat(cell, kSparseMaxDiagonal);
  float aBB = cellABB(cell);
  // Divided, not multiplied by 1 / max: near FLT_MAX that reciprocal is denormal, which GPUs flush.
  float meanOverMax = (useB ? aBB / maxDiag : 0.0) + scratchFloat(cell, kSparseDiagonalSum);
  float count = float(sparseScratch[scratchIndex(cell, kSparsePairsIn)] + (useB ? 1u : 0u));
  float ridge = (cmsIsFinite(pc.ridge) && pc.ridge > 0.0) ? pc.ridge : 0.0;
  float r = count > 0.0 ? (ridge * (meanOverMax / count)) * maxDiag : 0.0;
  setScratchFloat(cell, kSparseRidge, r);
  setScratchFloat(cell, kSparseScaleB, useB ? cmsScale(r, aBB) : 0.0);
}

void pivotCell(uint cell) {
  uint flags = scratchFlags(cell);
  bool useB = (flags & kSparseFlagUseB) != 0u;
  float pivot = 1.0 - scratchFloat(cell, kSparseSumL2);
  if (useB && !(pivot > kSolvePivotFloor)) {
    useB = false;   // B adds nothing the light techniques cannot express
    flags &= ~kSparseFlagUseB;
    setScratchFloat(cell, kSparseScaleB, 0.0);
  }
  float sB = scratchFloat(cell, kSparseScaleB);
  vec3 yB = useB ? (cellBB(cell) * sB - scratchFloat3(cell, kSparseSumLZ)) / pivot : vec3(0.0);
  vec3 alphaB = yB * sB;
  if (!cmsIsFinite3(alphaB)) flags |= kSparseFlagNonFinite;
  sparseScratch[scratchIndex(cell, kSparseFlags)] = flags;
  setScratchFloat3(cell, kSparseYB, yB);
  setScratchFloat3(cell, kSparseAlphaSum, cmsIsFinite3(alphaB) ? alphaB : vec3(0.0));
}

void finishCell(uint cell) {
  uint L = pc.clusterCount;
  uint flags = scratchFlags(cell);
  bool useB = (flags & kSparseFlagUseB) != 0u;
  uint inSystem = sparseScratch[scratchIndex(cell, kSparsePairsIn)] + (useB ? 1u : 0u);
  vec3 alphaSum = scratchFloat3(cell, kSparseAlphaSum);
  // Every vertex adds the sum: finite, and within the bound of shared/cms_solve.h.
  bool finite = (flags & kSparseFlagNonFinite) == 0u && cmsIsFinite3(alphaSum) &&
                max(max(abs(alphaSum.x), abs(alphaSum.y)), abs(alphaSum.z)) <= kSolveMaxAlphaSum;
  bool valid = cellSamples[cell] >= pc.minSamples && inSystem > 0u && finite &&
               (pc.flags & kSolveControlVariate) != 0u;
  if (valid) flags |= kSparseFlagValid;
  sparseScratch[scratchIndex(cell, kSparseFlags)] = flags;
  vec3 alphaB = valid ? scratchFloat3(cell, kSparseYB) * scratchFloat(cell, kSparseScaleB) : vec3(0.0);
  uint solution = cell * cellSolutionStride(L);
  for (uint c = 0u; c < 3u; ++c) {
    cellSolution[solution + solutionAlphaB(L, c)] = alphaB[c];
    cellSolution[solution + solutionAlphaSum(L, c)] = valid ? alphaSum[c] : 0.0;
  }
  cellSolution[solution + solutionValid(L)] = valid ? 1.0 : 0.0;
}

void cellStage(uint cell) {
  if (cell >= pc.cellCount) return;
  if (STAGE == kSparseInitCells) initCell(cell);
  else if (STAGE == kSparseRidgeCells) ridgeCell(cell);
  else if (STAGE == kSparsePivotCells) pivotCell(cell);
  else if (STAGE == kSparseFinishCells) finishCell(cell);
}

// The dispatch of the pair stages: one invocation per occupied slot, on the cell stages' grid.
void writePairArgs() {
  uint groups = (min(pairOccupied[kPairOccupiedCount], pc.pairCapacity) + kWorkgroupSize - 1u) / kWorkgroupSize;
  uvec2 grid = sparseDispatchGrid(groups, pc.maxGroupsX);
  sparseArgs[0] = grid.x;
  sparseArgs[1] = grid.y;
  sparseArgs[2] = 1u;
}

// `item` indexes the list of occupied slots (shared/cms_pair_state.h PAIR_OCCUPIED).
void pairStage(uint item) {
  if (item >= min(pairOccupied[kPairOccupiedCount], pc.pairCapacity)) return;
  uint slot = pairOccupied[kPairOccupiedFirst + item];
  if (slot >= pc.pairCapacity) return;
  Pair p;
  // The restart and the clear need the slot's cell only, not its statistics.
  uint64_t key = pairKeys[slot];
  if (key == uint64_t(0)) return;
  uint cell = pairKeyCell(key);
  if (cell >= pc.cellCount) return;
  if (STAGE == kSparseRestartPairs) {
    // Keys stay: the pair keeps its slot (shared/cms_pair_state.h); only what it gathered restarts.
    if (cellSamples[cell] != 0u) return;
    for (uint i = 0u; i < kPairStatsStride; ++i) pairStats[kPairStatsStride * slot + i] = 0.0;
    pairSamples[slot] = 0u;
    return;
  }
  if (STAGE == kSparseClearPairs) {
    if ((scratchFlags(cell) & kSparseFlagValid) != 0u) return;
    writePairAlpha(slot, vec3(0.0));
    pairAlpha[pairSolvedIndex(slot)] = 0.0;
    return;
  }
  if (!readPair(slot, p)) return;
  bool remainder = isRemainderTechnique(p.technique);
  if (STAGE == kSparseMaxPairs) {
    if (remainder) pairAlpha[pairSolvedIndex(slot)] = 0.0;   // its sum of shares restarts (kSparseAlphaPairs)
    if (!p.usable) return;
    atomicMax(sparseScratch[scratchIndex(p.cell, kSparseMaxDiagonal)], floatBitsToUint(p.aTT));
    atomicAdd(sparseScratch[scratchIndex(p.cell, kSparsePairsIn)], 1u);
  } else if (STAGE == kSparseMeanPairs) {
    if (p.usable) scratchAdd(p.cell, kSparseDiagonalSum, p.aTT / scratchFloat(p.cell, kSparseMaxDiagonal));
  } else if (STAGE == kSparseSchurPairs) {
    if (!p.usable || !((scratchFlags(p.cell) & kSparseFlagUseB) != 0u)) return;   // with B out l_t = 0
    float st, lt;
    vec3 zt;
    pairRow(p, st, lt, zt);
    scratchAdd(p.cell, kSparseSumL2, lt * lt);
    scratchAdd3(p.cell, kSparseSumLZ, lt * zt);
  } else if (STAGE == kSparseAlphaPairs) {
    vec3 alpha = vec3(0.0);
    if (p.usable) {
      float st, lt;
      vec3 zt;
      pairRow(p, st, lt, zt);   // s_B is 0 now when the pivot dropped B: the techniques decouple
      alpha = (zt - lt * scratchFloat3(p.cell, kSparseYB)) * st;
      if (!cmsIsFinite3(alpha)) {
        atomicOr(sparseScratch[scratchIndex(p.cell, kSparseFlags)], kSparseFlagNonFinite);
        alpha = vec3(0.0);   // the cell is invalid; nothing non-finite is ever stored
      }
      // A triangle technique's p_t integrates to 1; a remainder's alpha_R P_R joins the sum in
      // kSparseRemainderPairs, once every solved pair has given its share.
      if (!remainder) scratchAdd3(p.cell, kSparseAlphaSum, alpha);
    }
    writePairAlpha(slot, alpha);
    if (remainder) return;   // its fourth float is the sum of shares, gathered now
    pairAlpha[pairSolvedIndex(slot)] = p.usable ? 1.0 : 0.0;
    if (!p.usable) return;
    TechniqueClusterGpu t = techniqueClusters[p.technique];
    uint remainderSlot = findPair(pc.pairCapacity, p.cell, remainderTechnique(t.cluster));
    if (remainderSlot != kNoPairSlot) addSolvedShare(remainderSlot, t.share);
  } else if (STAGE == kSparseRemainderPairs) {
    // alpha_R P_R, P_R = 1 - the shares of the cluster's solved pairs: the mass of p_k where alpha_R
    // applies (host/cms/sparse_solve.h).
    if (!remainder || !p.usable) return;
    float mass = clamp(1.0 - uintBitsToFloat(pairAlphaBits[pairSolvedIndex(slot)]), 0.0, 1.0);
    vec3 alpha = vec3(pairAlpha[pairAlphaIndex(slot, 0u)], pairAlpha[pairAlphaIndex(slot, 1u)],
                      pairAlpha[pairAlphaIndex(slot, 2u)]);
    scratchAdd3(p.cell, kSparseAlphaSum, alpha * mass);
  }
}

void main() {
  uint i = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * kWorkgroupSize) + gl_GlobalInvocationID.x;
  if (STAGE == kSparsePairArgs) {
    if (i == 0u) writePairArgs();
  } else if (STAGE == kSparseInitCells || STAGE == kSparseRidgeCells || STAGE == kSparsePivotCells ||
      STAGE == kSparseFinishCells)
    cellStage(i);
  else
    pairStage(i);
}
