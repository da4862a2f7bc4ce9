#pragma once
// The per-cell solve of controlled mixture sampling for the sparse statistics of one technique
// per emissive triangle (host/cms/sparse_statistics.h; ../shared/cms.md §4, §6; docs/estimator.md
// §4, §6), in double precision, O(number of pairs). Not wired into rendering yet.
//
// A is an arrowhead matrix (light techniques t are disjoint, so only A_tt, A_tB and A_BB are
// non-zero), and the light techniques are eliminated exactly:
//     alpha_B = (b_B - sum_t A_tB b_t / A_tt) / (A_BB - sum_t A_tB^2 / A_tt)
//     alpha_t = (b_t - A_tB alpha_B) / A_tt
// with the ridge r added to every diagonal entry (A_tt + r, A_BB + r) and the system Jacobi-scaled
// first, the same rules as the per-cluster solve (shared/cms_solve.h, host/cms/reference_solve.cpp),
// whose policy constants it shares:
//   - a technique is dropped (alpha_t = 0) when its pair has fewer than minTechniqueSamples
//     samples, its diagonal is not finite and >= kSolveMinDiagonal, or A_tB or b_t is not finite;
//     B is dropped on the same diagonal and finiteness rules. Dropped techniques take no part in
//     anything below (a technique with no usable samples cannot spoil the others);
//   - r = ridge * the mean diagonal entry of the techniques in the system;
//   - with s_i = (A_ii + r)^-1/2, l_t = A_tB s_t s_B, z_t = b_t s_t: the scaled Schur pivot of B is
//     1 - sum_t l_t^2; at or below kSolvePivotFloor (B a combination of the light techniques) B is
//     dropped and the light techniques decouple (alpha_t = b_t / (A_tt + r));
//   - the cell is valid when it has at least minCellSamples samples, at least one technique in the
//     system, every alpha finite and within float range (the GPU stores float), and
//     |sum of alpha| <= kSolveMaxAlphaSum per channel. An invalid cell's alpha is 0 everywhere.
//   - the integral of the control variate (alphaSum) is alpha_B + sum over triangle techniques of
//     alpha_t (p_t is normalised) + sum over remainder techniques R of alpha_R P_R, where P_R = 1 -
//     sum of Q_t over the triangle pairs of R's cluster that are in the system (clamped to [0, 1]):
//     the mass of p_k on the triangles that use alpha_R, those without a solved pair (docs/estimator.md
//     §4, "When the table fills").
// Any alpha keeps the estimator unbiased, so each rule trades variance only. Every output is
// finite for any input.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/glm.hpp>

#include "cms/sparse_statistics.h"

namespace mixtrace {

struct SparseSolveParams {
  uint64_t minCellSamples = 64;       // docs/estimator.md §6 (minCellSamples)
  uint64_t minTechniqueSamples = 1;   // a pair with fewer samples is dropped (alpha_t = 0)
  double ridge = 1e-3;                // relative to the mean diagonal entry
};

// Maps a light technique (an emissive triangle) to the cluster that selection picks it by, for
// the per-cluster sums of alpha_t that learned selection uses (../shared/cms.md §7).
struct TechniqueClusters {
  std::vector<uint32_t> clusterOf;   // indexed by technique
  uint32_t clusterCount = 0;
};

struct SparseCellSolution {
  bool valid = false;
  glm::dvec3 alphaB{0.0};
  std::vector<glm::dvec3> alpha;     // one per pair of the cell's statistics, in their order
  std::vector<bool> inSystem;        // per pair: took part in the final system (a triangle pair: solved)
  std::vector<double> mass;          // per pair: the integral of its density (1; P_R for a remainder)
  bool bInSystem = false;
  glm::dvec3 alphaSum{0.0};          // sum of alpha_t and alpha_B: the control variate's integral
  std::vector<glm::dvec3> clusterAlpha;   // sum of alpha_t per cluster (empty without a map)
  uint32_t techniquesInSystem = 0;   // light techniques only
};

// Throws std::out_of_range when a pair's technique has no cluster in `clusters` (given, non-empty
// map) or its cluster is >= clusterCount.
SparseCellSolution solveSparseCell(const SparseCellStatistics& cell, const SparseSolveParams& params,
                                   const TechniqueClusters* clusters = nullptr);

// Every cell of a table.
std::unordered_map<uint32_t, SparseCellSolution> solveSparseCells(const SparseStatisticsTable& table,
                                                                  const SparseSolveParams& params,
                                                                  const TechniqueClusters* clusters = nullptr);

}  // namespace mixtrace
