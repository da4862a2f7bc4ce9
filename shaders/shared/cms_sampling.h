// Light sampling through clusters, the techniques of controlled mixture sampling (docs/estimator.md
// §2): a cluster k from the cell's selection pmf c_k (learned, or the defaults), a light inside it
// with its fixed pmf, then a point on it (lights.h). p_k(z) is the density of the last two steps,
// so the mixture density of a light sample is sum_k c_k p_k(z) = c_k p_k(z) (clusters are
// disjoint).
//
// The includer defines, besides the accessors of lights.h: LIGHT_CLUSTER_PMF(light) -> float (the
// light's pmf inside its cluster), CLUSTER(i) -> ClusterGpu,
// CLUSTER_LIGHT(i) -> ClusterLightGpu, CELL_SOLUTION(i) -> float (the solve pass's output) and
// CLUSTER_DEFAULT(k) -> float (the default selection pmf).
#ifndef MIXTRACE_SHARED_CMS_SAMPLING_H
#define MIXTRACE_SHARED_CMS_SAMPLING_H
#include "shared/cluster_layout.h"
#include "shared/cms_cells.h"
#include "shared/cms_layouts.h"
#include "shared/dialect.h"
#include "shared/layouts.h"
#include "shared/lights.h"
SHARED_BEGIN_WITH_BUFFERS

// c_k at a vertex in `cell` (kNoCell: the defaults).
SHARED_FN float clusterSelectPmf(uint cell, uint L, uint k) {
  if (cell == kNoCell) return CLUSTER_DEFAULT(k);
  return CELL_SOLUTION(cell * cellSolutionStride(L) + solutionSelect(L, k));
}

// Inverts the cell's selection CDF by a linear scan (L <= 32); never returns an empty cluster
// unless every c_k is 0.
SHARED_FN uint selectCluster(uint cell, uint L, float u) {
  float cdf = 0.0f;
  uint last = 0u;
  for (uint k = 0u; k < L; ++k) {
    float c = clusterSelectPmf(cell, L, k);
    if (c <= 0.0f) continue;
    last = k;
    cdf += c;
    if (u < cdf) return k;
  }
  return last;   // rounding: u at the very top of the CDF
}

SHARED_FN uint selectLightInCluster(uint k, float u) {
  ClusterGpu c = CLUSTER(k);
  uint lo = c.firstLight;
  uint hi = c.firstLight + c.lightCount - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) >> 1u;
    if (u < CLUSTER_LIGHT(mid).cdf) hi = mid; else lo = mid + 1u;
  }
  return CLUSTER_LIGHT(lo).light;
}

// p_k(z) for the point `lightPoint` on emitting triangle `tri` seen from `from`: the density of
// sampling it once its cluster was chosen (0 where the triangle does not emit).
SHARED_FN float clusterPointPdf(uint tri, vec3 from, vec3 lightPoint) {
  float pointPdf = areaLightPointPdf(tri, from, lightPoint);
  return pointPdf > 0.0f ? LIGHT_CLUSTER_PMF(lightOfTriangle(tri)) * pointPdf : 0.0f;
}

SHARED_FN bool cellSolutionValid(uint cell, uint L) {
  return cell != kNoCell && CELL_SOLUTION(cell * cellSolutionStride(L) + solutionValid(L)) > 0.5f;
}

SHARED_FN vec3 cellAlpha(uint cell, uint L, uint k) {
  uint base = cell * cellSolutionStride(L);
  return vec3(CELL_SOLUTION(base + solutionAlpha(L, k, 0u)), CELL_SOLUTION(base + solutionAlpha(L, k, 1u)),
              CELL_SOLUTION(base + solutionAlpha(L, k, 2u)));
}

SHARED_FN vec3 cellAlphaB(uint cell, uint L) {
  uint base = cell * cellSolutionStride(L);
  return vec3(CELL_SOLUTION(base + solutionAlphaB(L, 0u)), CELL_SOLUTION(base + solutionAlphaB(L, 1u)),
              CELL_SOLUTION(base + solutionAlphaB(L, 2u)));
}

// The integral of the control variate: sum_k alpha_k + alpha_B (each density integrates to 1),
// as the solve stored it.
SHARED_FN vec3 cellAlphaSum(uint cell, uint L) {
  uint base = cell * cellSolutionStride(L);
  return vec3(CELL_SOLUTION(base + solutionAlphaSum(L, 0u)), CELL_SOLUTION(base + solutionAlphaSum(L, 1u)),
              CELL_SOLUTION(base + solutionAlphaSum(L, 2u)));
}

SHARED_END_WITH_BUFFERS
#endif
