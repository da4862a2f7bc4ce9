#include "cms/sparse_solve.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>

#include "shared/cms_pair_layout.h"   // the remainder techniques' ids
#include "shared/cms_solve.h"         // the policy constants only (no CELL_STATS: no buffer code)

namespace mixtrace {

namespace {

bool finite3(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool usableDiagonal(double a) { return std::isfinite(a) && a >= double(shared::kSolveMinDiagonal); }

// The GPU stores alpha in float: a coefficient beyond float's range counts as non-finite.
bool fitsFloat(const glm::dvec3& v) {
  for (int c = 0; c < 3; ++c)
    if (!(std::abs(v[c]) <= double(FLT_MAX))) return false;
  return true;
}

bool pairUsable(const SparsePairStatistics& p, const SparseSolveParams& params) {
  return p.samples >= params.minTechniqueSamples && usableDiagonal(p.aTT) && std::isfinite(p.aTB) && finite3(p.bT);
}

// (a + r)^-1/2 as a^-1/2 (1 + r/a)^-1/2: never forms a + r, where a tiny a would vanish.
double jacobiScale(double a, double r) { return (1.0 / std::sqrt(a)) / std::sqrt(1.0 + r / a); }

}  // namespace

SparseCellSolution solveSparseCell(const SparseCellStatistics& cell, const SparseSolveParams& params,
                                   const TechniqueClusters* clusters) {
  const size_t n = cell.pairs.size();
  SparseCellSolution out;
  out.alpha.assign(n, glm::dvec3(0.0));
  out.inSystem.assign(n, false);
  out.mass.assign(n, 1.0);
  if (clusters != nullptr) out.clusterAlpha.assign(clusters->clusterCount, glm::dvec3(0.0));

  const SparseCellTotals& totals = cell.totals;
  bool useB = usableDiagonal(totals.aBB) && finite3(totals.bB);
  std::vector<bool> usable(n);
  for (size_t i = 0; i < n; ++i) usable[i] = pairUsable(cell.pairs[i], params);

  // The ridge: ridge * mean diagonal of the techniques in the system, summed in units of the
  // largest entry so that the sum of many entries near DBL_MAX cannot overflow.
  double maxDiag = useB ? totals.aBB : 0.0;
  for (size_t i = 0; i < n; ++i)
    if (usable[i]) maxDiag = std::max(maxDiag, cell.pairs[i].aTT);
  const double invMax = maxDiag > 0.0 ? 1.0 / maxDiag : 1.0;
  double meanOverMax = useB ? totals.aBB * invMax : 0.0;
  double count = useB ? 1.0 : 0.0;
  for (size_t i = 0; i < n; ++i)
    if (usable[i]) {
      meanOverMax += cell.pairs[i].aTT * invMax;
      count += 1.0;
    }
  const double ridge = std::isfinite(params.ridge) && params.ridge > 0.0 ? params.ridge : 0.0;
  const double r = count > 0.0 ? (ridge * (meanOverMax / count)) * maxDiag : 0.0;
  double sB = useB ? jacobiScale(totals.aBB, r) : 0.0;

  // Elimination of the light techniques: the Schur pivot of B and sum_t l_t z_t.
  std::vector<double> scale(n, 0.0), lTB(n, 0.0);
  double sumL2 = 0.0;
  glm::dvec3 sumLZ(0.0);
  for (size_t i = 0; i < n; ++i) {
    if (!usable[i]) continue;
    const SparsePairStatistics& p = cell.pairs[i];
    scale[i] = jacobiScale(p.aTT, r);
    lTB[i] = p.aTB * (scale[i] * sB);   // s_t s_B first: exactly 0 when B is out, never Inf * 0
    sumL2 += lTB[i] * lTB[i];
    sumLZ += lTB[i] * (p.bT * scale[i]);
  }
  const double pivot = 1.0 - sumL2;
  if (useB && !(pivot > double(shared::kSolvePivotFloor))) {
    useB = false;   // B adds nothing the light techniques cannot express
    sB = 0.0;
  }
  glm::dvec3 yB(0.0);
  if (useB) yB = (totals.bB * sB - sumLZ) / pivot;
  const glm::dvec3 alphaB = yB * sB;

  // Back substitution (with B out, l_t multiplies yB = 0: the techniques decouple).
  bool allFinite = fitsFloat(alphaB);
  uint32_t inSystem = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!usable[i]) continue;
    const SparsePairStatistics& p = cell.pairs[i];
    out.alpha[i] = (p.bT * scale[i] - lTB[i] * yB) * scale[i];
    out.inSystem[i] = true;
    inSystem += 1;
    allFinite = allFinite && fitsFloat(out.alpha[i]);
  }
  // The remainders' masses: P_R = 1 - the shares of their clusters' solved triangle pairs.
  std::unordered_map<uint32_t, double> solvedShare;   // by cluster
  for (size_t i = 0; i < n; ++i)
    if (out.inSystem[i] && !shared::isRemainderTechnique(cell.pairs[i].technique))
      solvedShare[cell.pairs[i].cluster] += cell.pairs[i].share;
  glm::dvec3 alphaSum = alphaB;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t t = cell.pairs[i].technique;
    if (shared::isRemainderTechnique(t)) {
      const auto found = solvedShare.find(shared::remainderTechniqueCluster(t));
      out.mass[i] = std::clamp(1.0 - (found == solvedShare.end() ? 0.0 : found->second), 0.0, 1.0);
    }
    alphaSum += out.alpha[i] * out.mass[i];
  }
  for (int c = 0; c < 3; ++c)   // every vertex adds the sum (bound: shared/cms_solve.h)
    allFinite = allFinite && std::abs(alphaSum[c]) <= double(shared::kSolveMaxAlphaSum);
  out.bInSystem = useB;
  out.techniquesInSystem = inSystem;
  out.valid = totals.samples >= params.minCellSamples && (inSystem > 0 || useB) && allFinite;

  if (!out.valid) {
    out.alpha.assign(n, glm::dvec3(0.0));
  } else {
    out.alphaB = alphaB;
    out.alphaSum = alphaSum;
  }
  // The map is checked whether or not the cell is valid, so that a caller's bug shows at once.
  if (clusters != nullptr && !clusters->clusterOf.empty()) {
    for (size_t i = 0; i < n; ++i) {
      const uint32_t t = cell.pairs[i].technique;
      const bool remainder = shared::isRemainderTechnique(t);
      const uint32_t k = remainder ? shared::remainderTechniqueCluster(t)
                                   : (t < clusters->clusterOf.size() ? clusters->clusterOf[t] : clusters->clusterCount);
      if (k >= clusters->clusterCount) throw std::out_of_range("solveSparseCell: technique without a cluster");
      out.clusterAlpha[k] += out.alpha[i] * out.mass[i];
    }
  }
  return out;
}

std::unordered_map<uint32_t, SparseCellSolution> solveSparseCells(const SparseStatisticsTable& table,
                                                                  const SparseSolveParams& params,
                                                                  const TechniqueClusters* clusters) {
  std::unordered_map<uint32_t, SparseCellSolution> out;
  out.reserve(table.cells().size());
  for (const auto& [id, cell] : table.cells()) out.emplace(id, solveSparseCell(cell, params, clusters));
  return out;
}

}  // namespace mixtrace
