#pragma once
// The per-cell CMS solve in double precision, written independently of the GPU's float version
// (shared/cms_solve.h, whose header comment states the rules both follow): a dense Cholesky of the
// system restricted to the techniques with usable samples, not the arrowhead shortcut. Tests hold
// the solve pass to it; the CPU renderer uses it as its solve.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "shared/cms_layouts.h"

namespace mixtrace {

struct CellSolution {
  std::vector<glm::dvec3> alpha;   // per cluster; 0 when unsolved or without kSolveControlVariate
  glm::dvec3 alphaB{0.0};
  glm::dvec3 alphaSum{0.0};        // sum of alpha and alphaB: the control variate's integral
  std::vector<double> select;      // selection pmf over the clusters (sums to 1)
  bool valid = false;              // the cell uses its control variate
  bool solved = false;             // the system was solved (alpha finite, enough samples), whatever the flags
  std::vector<bool> inSystem;      // per technique, clusters then B: took part in the final system
  bool resetStatistics = false;    // the cell's statistics restart (new selection, or non-finite alpha)
  // kSolveKeepControlVariate: alpha, alphaB, alphaSum are 0 and valid false as without
  // kSolveControlVariate, and the caller leaves the cell's alpha_B, valid and sum of alpha as the
  // sparse solve (one technique per emissive triangle) wrote them.
  bool keepControlVariate = false;
};

// stats: cellStatsStride(L) floats of one cell; defaults: L floats (the default selection pmf);
// previousSelect: the L floats of the selection the cell used so far (nullptr: none yet).
CellSolution solveCellReference(const float* stats, uint32_t samples, uint32_t L, const shared::SolveParams& params,
                                const float* defaults, const float* previousSelect = nullptr);
// The same for statistics accumulated in double (the CPU renderer's).
CellSolution solveCellReference(const double* stats, uint32_t samples, uint32_t L, const shared::SolveParams& params,
                                const float* defaults, const float* previousSelect = nullptr);

}  // namespace mixtrace
