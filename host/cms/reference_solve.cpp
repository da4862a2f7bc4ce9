#include "cms/reference_solve.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include "shared/cms_solve.h"   // the policy constants only (no CELL_STATS: no buffer code)

namespace mixtrace {

namespace {

using shared::SolveParams;

bool finite3(const double* v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

bool usableDiagonal(double a) { return std::isfinite(a) && a >= double(shared::kSolveMinDiagonal); }

// The output is float: a coefficient beyond float's range cannot be written, so it counts as
// non-finite, as it does on the GPU.
bool fitsFloat(const glm::dvec3& v) {
  for (int c = 0; c < 3; ++c)
    if (!(std::abs(v[c]) <= double(FLT_MAX))) return false;
  return true;
}

double luminance(const glm::dvec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// Entry (t, u) of the full arrowhead matrix over techniques 0..L-1 (clusters) and L (B).
double matrixEntry(const double* stats, uint32_t L, uint32_t t, uint32_t u) {
  if (t == u) return t == L ? stats[shared::statsABB(L)] : stats[shared::statsAkk(L, t)];
  if (t == L) return stats[shared::statsAkB(L, u)];
  if (u == L) return stats[shared::statsAkB(L, t)];
  return 0.0;   // two clusters: disjoint supports
}

glm::dvec3 rhs(const double* stats, uint32_t L, uint32_t t) {
  const double* b = t == L ? &stats[shared::statsBB(L, 0)] : &stats[shared::statsBk(L, t, 0)];
  return glm::dvec3(b[0], b[1], b[2]);
}

// Solves the ridge-regularised, Jacobi-scaled system over `techniques` by dense Cholesky: r =
// ridge * the mean diagonal entry of the initial techniques is added to the diagonal, then the
// system is scaled to a unit diagonal. A pivot at or below the floor drops its technique and
// starts over (with the same r). Returns alpha per technique of the final set (which it shrinks
// in place).
std::vector<glm::dvec3> solveSystem(const double* stats, uint32_t L, double ridge, std::vector<uint32_t>& techniques) {
  const double diag = 1.0;
  const double floor = double(shared::kSolvePivotFloor);
  double mean = 0.0;
  for (uint32_t t : techniques) mean += matrixEntry(stats, L, t, t) / double(techniques.size());
  const double r = ridge * mean;
  for (;;) {
    size_t m = techniques.size();
    std::vector<double> scale(m);
    for (size_t i = 0; i < m; ++i) scale[i] = 1.0 / std::sqrt(matrixEntry(stats, L, techniques[i], techniques[i]) + r);
    std::vector<double> G(m * m, 0.0);   // lower Cholesky factor, row-major
    size_t failed = m;
    for (size_t j = 0; j < m && failed == m; ++j) {
      for (size_t i = j; i < m; ++i) {
        double a = i == j ? diag : matrixEntry(stats, L, techniques[i], techniques[j]) * scale[i] * scale[j];
        for (size_t l = 0; l < j; ++l) a -= G[i * m + l] * G[j * m + l];
        if (i == j) {
          if (!(a > floor)) { failed = j; break; }
          G[j * m + j] = std::sqrt(a);
        } else {
          G[i * m + j] = a / G[j * m + j];
        }
      }
    }
    if (failed != m) {
      techniques.erase(techniques.begin() + failed);
      continue;
    }
    std::vector<glm::dvec3> z(m);
    for (size_t i = 0; i < m; ++i) {
      glm::dvec3 v = rhs(stats, L, techniques[i]) * scale[i];
      for (size_t l = 0; l < i; ++l) v -= G[i * m + l] * z[l];
      z[i] = v / G[i * m + i];
    }
    std::vector<glm::dvec3> y(m);
    for (size_t i = m; i-- > 0;) {
      glm::dvec3 v = z[i];
      for (size_t l = i + 1; l < m; ++l) v -= G[l * m + i] * y[l];
      y[i] = v / G[i * m + i];
    }
    for (size_t i = 0; i < m; ++i) y[i] *= scale[i];
    return y;
  }
}

}  // namespace

CellSolution solveCellReference(const float* stats, uint32_t samples, uint32_t L, const SolveParams& params,
                                const float* defaults, const float* previousSelect) {
  // Every float is exactly a double, so the float statistics take the double path unchanged.
  std::vector<double> wide(stats, stats + shared::cellStatsStride(L));
  return solveCellReference(wide.data(), samples, L, params, defaults, previousSelect);
}

CellSolution solveCellReference(const double* stats, uint32_t samples, uint32_t L, const SolveParams& params,
                                const float* defaults, const float* previousSelect) {
  CellSolution out;
  out.alpha.assign(L, glm::dvec3(0.0));
  out.select.assign(L, 0.0);
  out.inSystem.assign(L + 1, false);

  // Techniques with usable samples: clusters first, B last (its pivot is the Schur complement).
  std::vector<uint32_t> techniques;
  for (uint32_t k = 0; k < L; ++k)
    if (usableDiagonal(stats[shared::statsAkk(L, k)]) && std::isfinite(stats[shared::statsAkB(L, k)]) &&
        finite3(&stats[shared::statsBk(L, k, 0)]))
      techniques.push_back(k);
  if (usableDiagonal(stats[shared::statsABB(L)]) && finite3(&stats[shared::statsBB(L, 0)])) techniques.push_back(L);

  double ridge = std::isfinite(params.ridge) && params.ridge > 0.0f ? double(params.ridge) : 0.0;
  std::vector<glm::dvec3> solved = solveSystem(stats, L, ridge, techniques);

  std::vector<glm::dvec3> alpha(L, glm::dvec3(0.0));
  glm::dvec3 alphaB(0.0);
  bool allFinite = true;
  glm::dvec3 alphaSum(0.0);
  for (size_t i = 0; i < techniques.size(); ++i) {
    out.inSystem[techniques[i]] = true;
    (techniques[i] == L ? alphaB : alpha[techniques[i]]) = solved[i];
    allFinite = allFinite && fitsFloat(solved[i]);
    alphaSum += solved[i];
  }
  for (int c = 0; c < 3; ++c)   // every vertex adds the sum (bound: shared/cms_solve.h)
    allFinite = allFinite && std::abs(alphaSum[c]) <= double(shared::kSolveMaxAlphaSum);
  out.solved = samples >= params.minSamples && !techniques.empty() && allFinite;
  out.keepControlVariate = (params.flags & shared::kSolveKeepControlVariate) != 0;
  out.valid = out.solved && (params.flags & shared::kSolveControlVariate) != 0 && !out.keepControlVariate;
  if (out.valid) {
    out.alpha = alpha;
    out.alphaB = alphaB;
    out.alphaSum = alphaSum;
  }

  // Selection: defaults sanitised and normalised, learned share where the solve allows it.
  std::vector<double> d(L, 0.0);
  double defaultSum = 0.0;
  for (uint32_t k = 0; k < L; ++k) {
    if (std::isfinite(defaults[k]) && defaults[k] > 0.0f) d[k] = defaults[k];
    defaultSum += d[k];
  }
  for (uint32_t k = 0; k < L; ++k) d[k] = defaultSum > 0.0 ? d[k] / defaultSum : 1.0 / L;

  std::vector<double> weight(L, 0.0);
  double weightSum = 0.0;
  for (uint32_t k = 0; k < L; ++k) {
    weight[k] = std::max(luminance(alpha[k]), 0.0);
    weightSum += weight[k];
  }
  bool learn = out.solved && (params.flags & shared::kSolveLearnSelection) != 0 && weightSum > 0.0 &&
               std::isfinite(weightSum);
  double eps = std::isfinite(params.defensive) ? std::clamp(double(params.defensive), double(shared::kSolveMinDefensive), 1.0)
                                               : 1.0;
  // With the BVH defaults only the learned part is stored (kSolveBvhDefaults); delta = 1 - sum c
  // is the defaults' share, so the vector is compared with that share appended.
  const bool bvhDefaults = (params.flags & shared::kSolveBvhDefaults) != 0;
  double selectSum = 0.0;
  for (uint32_t k = 0; k < L; ++k) {
    double c = bvhDefaults ? (learn ? (1.0 - eps) * weight[k] / weightSum : 0.0)
                           : (learn ? (1.0 - eps) * weight[k] / weightSum + eps * d[k] : d[k]);
    if (d[k] > 0.0 && !bvhDefaults) c = std::max(c, 1e-30);
    out.select[k] = c;
    selectSum += c;
  }
  if (!bvhDefaults)
    for (double& c : out.select) c /= selectSum;

  // Keep the previous selection (and the statistics gathered under it) unless there is none yet,
  // or the cell is solved and its selection moved by more than the threshold in total variation.
  bool previousValid = previousSelect != nullptr;
  double previousSum = 0.0, change = 0.0, newSum = 0.0;
  for (uint32_t k = 0; previousValid && k < L; ++k) {
    previousValid = std::isfinite(previousSelect[k]) && previousSelect[k] >= 0.0f;
    previousSum += previousSelect[k];
    newSum += out.select[k];
    change += std::abs(out.select[k] - previousSelect[k]);
  }
  if (bvhDefaults) {
    change += std::abs((1.0 - newSum) - (1.0 - previousSum));
    previousValid = previousValid && previousSum <= 1.0 + 1e-3;
  } else {
    previousValid = previousValid && std::abs(previousSum - 1.0) <= 1e-3;
  }
  bool adopt = !previousValid || (out.solved && 0.5 * change > shared::kSelectionChangeThreshold);
  if (!adopt)
    for (uint32_t k = 0; k < L; ++k) out.select[k] = previousSelect[k];
  out.resetStatistics = adopt || !allFinite;
  return out;
}

}  // namespace mixtrace
