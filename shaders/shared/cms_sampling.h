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
//
// The light BVH as the default selection (learned and cms, docs/estimator.md §7): where the
// includer defines LIGHT_BVH(i) and LIGHT_SELECT_BVH is true, the cell's stored c_k are only the
// learned part of its selection, (1 - eps) w_k / sum w, summing to 1 - delta, and the rest, delta
// (1 before the cell has learned anything, eps after), goes to the defaults at the vertex: the
// light BVH at the vertex's point and normal, with a share kBvhDefaultsTableShare of the table's
// defaults d_k. A light's probability at the vertex is then
//     P(l | x) = c_k q_l|k + delta ((1 - s) P_bvh(l | x) + s d_k q_l|k)
// with q_l|k its fixed pmf inside its cluster k and s = kBvhDefaultsTableShare. The table part keeps
// every cluster's lights sampled where the BVH gives them nothing (a light behind the surface):
// the control variate's g must be sampled wherever it is non-zero (§3).
#ifndef MIXTRACE_SHARED_CMS_SAMPLING_H
#define MIXTRACE_SHARED_CMS_SAMPLING_H
#include "shared/cluster_layout.h"
#include "shared/cms_cells.h"
#include "shared/cms_layouts.h"
#include "shared/dialect.h"
#include "shared/layouts.h"
#include "shared/lights.h"
#ifdef LIGHT_BVH
#define CMS_BVH_DEFAULTS (LIGHT_SELECT_BVH)
#else
#define CMS_BVH_DEFAULTS false
#endif
SHARED_BEGIN_WITH_BUFFERS

// The table defaults' share inside the BVH defaults (s above).
const float kBvhDefaultsTableShare = 0.1f;
// selectVertexLight's answer where no light was drawn.
const uint kNoVertexLight = 0xffffffffu;

// c_k at a vertex in `cell` (kNoCell: the defaults; with the BVH defaults, none of it learned).
SHARED_FN float clusterSelectPmf(uint cell, uint L, uint k) {
  if (cell == kNoCell) return CMS_BVH_DEFAULTS ? 0.0f : CLUSTER_DEFAULT(k);
  return CELL_SOLUTION(cell * cellSolutionStride(L) + solutionSelect(L, k));
}

// delta, the defaults' share at a vertex of `cell`: 1 - sum_k c_k with the BVH defaults, else 0
// (the stored c_k hold the defaults themselves).
SHARED_FN float defaultsShare(uint cell, uint L) {
  if (!CMS_BVH_DEFAULTS) return 0.0f;
  float learned = 0.0f;
  for (uint k = 0u; k < L; ++k) learned += clusterSelectPmf(cell, L, k);
  return clamp(1.0f - learned, 0.0f, 1.0f);
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

// c_k + delta s d_k: the part of cluster k's weight that its in-cluster pmf spreads over its
// lights (the learned part and the table's share of the defaults).
SHARED_FN float tableClusterWeight(uint cell, uint L, uint k, float delta) {
  return clusterSelectPmf(cell, L, k) + delta * kBvhDefaultsTableShare * CLUSTER_DEFAULT(k);
}

// The effective c_k of a light of cluster k (in-cluster pmf q) whose BVH pmf at the vertex is
// bvhPmf: P(l | x) / q_l|k. The sampler and the BSDF hit both form it here, from the same floats.
SHARED_FN float mixedClusterWeight(uint cell, uint L, uint k, float q, float delta, float bvhPmf) {
  if (!(q > 0.0f)) return clusterSelectPmf(cell, L, k);   // never sampled in its cluster: p_k = 0 on it
  return tableClusterWeight(cell, L, k, delta) + delta * (1.0f - kBvhDefaultsTableShare) * bvhPmf / q;
}

// The effective c_k of `light` at a vertex of `cell` at (p, n): P(l | x) / q_l|k, so that the light
// density of any point on it is this times p_k (the cluster technique's density). Without the BVH
// defaults exactly the cell's c_k.
SHARED_FN float vertexClusterWeight(uint cell, uint L, uint light, vec3 p, vec3 n, float delta) {
  uint k = LIGHT_CLUSTER(light);
#ifdef LIGHT_BVH
  if (delta > 0.0f) return mixedClusterWeight(cell, L, k, LIGHT_CLUSTER_PMF(light), delta, lightBvhPmf(p, n, light));
#endif
  return clusterSelectPmf(cell, L, k);
}

// The weight a cluster scan gives cluster k: the cell's c_k, or with the defaults' share delta > 0
// the table weight (the learned part and the table's share of the defaults).
SHARED_FN float clusterScanWeight(uint cell, uint L, uint k, float delta) {
  return delta > 0.0f ? tableClusterWeight(cell, L, k, delta) : clusterSelectPmf(cell, L, k);
}

// Inverts the scan weights' CDF by a linear scan (L <= 32); never returns a cluster of weight 0
// unless every weight is 0.
SHARED_FN uint selectCluster(uint cell, uint L, float u, float delta) {
  float cdf = 0.0f;
  uint last = 0u;
  for (uint k = 0u; k < L; ++k) {
    float c = clusterScanWeight(cell, L, k, delta);
    if (!(c > 0.0f)) continue;
    last = k;
    cdf += c;
    if (u < cdf) return k;
  }
  return last;   // rounding: u at the very top of the CDF
}

// The light of a light sample at a vertex of `cell`, and its effective c_k (vertexClusterWeight):
// with probability delta (1 - s) from the light BVH at (p, n), else a cluster by its table weight
// and a light inside it by uInCluster. Every invocation walks the BVH once: to pick, or to evaluate
// the pmf of the light it picked from the table. kNoVertexLight where the BVH reaches no light
// (the sample is then not drawn: a defective density counts nothing, §3).
SHARED_FN uint selectVertexLight(uint cell, uint L, vec3 p, vec3 n, float u, float uInCluster, float delta,
                                 OUT(float) ck) {
#ifdef LIGHT_BVH
  if (delta > 0.0f) {
    float bvhShare = delta * (1.0f - kBvhDefaultsTableShare);
    bool fromBvh = !(u < 1.0f - bvhShare);
    uint light = fromBvh ? 0u : selectLightInCluster(selectCluster(cell, L, u, delta), uInCluster);
    float v = fromBvh ? min((u - (1.0f - bvhShare)) / bvhShare, kLightBvhOneMinusEpsilon) : 0.0f;
    float bvhPmf;
    uint walked = lightBvhWalk(p, n, fromBvh, v, light, bvhPmf);
    if (fromBvh) {
      if (!(bvhPmf > 0.0f)) return kNoVertexLight;
      light = walked;
    }
    ck = mixedClusterWeight(cell, L, LIGHT_CLUSTER(light), LIGHT_CLUSTER_PMF(light), delta, bvhPmf);
    return light;
  }
#endif
  uint k = selectCluster(cell, L, u, 0.0f);
  ck = clusterSelectPmf(cell, L, k);
  return selectLightInCluster(k, uInCluster);
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
