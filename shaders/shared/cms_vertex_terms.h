// The per-vertex terms of controlled mixture sampling, written once for both backends: the Vulkan
// passes (shaders/wavefront/shade.comp, shadow.comp, through gpu/cms_statistics.glsl) and the CPU
// reference (host/cpu/cpu_cms_path.cpp) call these functions, and only decide when each term is
// paid (the GPU splits a vertex over the shade and shadow passes, the CPU traces it in one loop).
//
// A vertex x of a cell draws a light sample and a BSDF sample; for a sample z the code knows
//   k     its cluster (kNoCell: z lies in no cluster's support, e.g. a BSDF sample that hit no light),
//   pk    p_k(z), the density of the cluster's light sampling,
//   pB    p_B(z), the density of BSDF sampling (0 for a point the BSDF cannot reach, docs/estimator.md §1),
//   peff  the mixture density c_k p_k(z) + p_B(z) both samples are divided by,
//   f     the integrand Le bsdf |cos| (visibility included, throughput excluded),
//   T     the path throughput at x, and w the sample's statistics weight (§5; 0: it gathers nothing).
//
// The includer defines, besides the accessors of cms_sampling.h (and LIGHT_CLUSTER(light),
// LIGHT_CLUSTER_PMF(light): a light's cluster and its pmf inside the cluster):
//   CMS_STAT_REAL                     the precision the statistics' increments are formed in
//                                     (float on the GPU, double on the CPU reference);
//   CMS_ADD_STAT(cell, index, value)  adds `value` to entry `index` of the cell's statistics (the
//                                     GPU's float atomics or compare-and-swap loops, the CPU's
//                                     double compare-exchange loops).
#ifndef MIXTRACE_SHARED_CMS_VERTEX_TERMS_H
#define MIXTRACE_SHARED_CMS_VERTEX_TERMS_H
#include "shared/bsdf.h"
#include "shared/cms_layouts.h"
#include "shared/cms_sampling.h"
#include "shared/dialect.h"
#include "shared/layouts.h"
#include "shared/lights.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "shared/scatter_side.h"
SHARED_BEGIN_WITH_BUFFERS

// ---- Densities (docs/estimator.md §1, §2) ----

// The light sample through the cell's clusters: a cluster k from the cell's selection c, a light
// inside it with its fixed pmf (one more random number), a point on that light; with the BVH
// defaults (cms_sampling.h) the light comes from the defaults with probability delta, chosen at
// (selectFrom, selectNormal): the ray origin and geometric normal, as the vertex's BSDF sample
// is weighed (bsdfHitClusterWeight). On return ck is the light's effective c_k
// (vertexClusterWeight), ls.pdf the sample's light-sampling density c_k p_k(z) and pk is p_k(z).
// Returns whether the point carries light towards `position` (lights.h sampleLightPoint); k is
// kNoCell where no light was drawn (the BVH reaches none): the sample then counts nothing.
SHARED_FN bool sampleClusterLight(uint cell, uint L, vec3 position, vec3 selectFrom, vec3 selectNormal, float uLight,
                                  float uEmitter, vec2 uPoint, INOUT(uint) rng, OUT(uint) k, OUT(float) pk,
                                  OUT(float) ck, OUT(LightSample) ls) {
  float delta = defaultsShare(cell, L);
  uint light = selectVertexLight(cell, L, selectFrom, selectNormal, uLight, rngNextFloat(rng), delta, ck);
  k = kNoCell;
  pk = 0.0f;
  if (light == kNoVertexLight) {
    ck = 0.0f;
    ls.pdf = 0.0f;
    return false;
  }
  k = LIGHT_CLUSTER(light);
  bool carries = sampleLightPoint(position, light, uEmitter, uPoint, ls);
  pk = LIGHT_CLUSTER_PMF(light) * ls.pdf;
  ls.pdf = ck * pk;
  return carries;
}

// Whether the BSDF at a vertex with geometric normal n could have sampled the light sample's
// point, i.e. whether it is not hidden (§1). Hidden: below the surface (unless the BSDF transmits;
// wiLocalZ is the direction's z in the shading frame, scatter_side.h), emitting nothing towards
// the vertex (`carries` false: a one-sided emitter's back, a spot's outside) whatever lies between,
// or without solid-angle density from the vertex (in its plane, e.g. a light sampling itself).
// The BSDF sample treats such a hit as no light either (clusterOfBsdfHit), so each technique's
// density stays the density of its own samples. A point without density takes, with clusters,
// p_k = 1 and light density c_k: p_k is in the light's own area measure and the terms only need
// ratios, so any positive p_k does. (Without clusters, a sample without density is not used.)
SHARED_FN bool lightPointReachable(float ck, vec3 n, float wiLocalZ, bool transmits, bool carries, INOUT(float) pk,
                                   INOUT(LightSample) ls) {
  bool above = lightSideReachable(ls.direction, n, wiLocalZ, transmits);
  if (!(ls.pdf > 0.0f)) {
    above = false;
    carries = false;
    pk = 1.0f;
    ls.pdf = ck;
  }
  return above && carries;
}

// The light sample's integrand f = bsdf |cos| Le (visibility aside) and BSDF density p_B at the
// vertex (wo, wi in its shading frame); both 0 at a hidden point, p_B also for a delta light.
SHARED_FN vec3 lightSampleIntegrand(BsdfParams bsdf, vec3 wo, vec3 wi, LightSample ls, bool reachable,
                                    OUT(float) pB) {
  pB = (ls.isDelta || !reachable) ? 0.0f : bsdfPdf(bsdf, wo, wi);
  vec3 f = vec3(0.0f);
  if (reachable) f = bsdfEval(bsdf, wo, wi) * abs(wi.z) * ls.radiance;
  return f;
}

// The mixture density of a light sample: its light density (c_k p_k with clusters) plus p_B
// (balance heuristic, §1).
SHARED_FN float lightSampleMixtureDensity(float lightPdf, float pB) { return lightPdf + pB; }

// The light a BSDF sample reached: the emitting triangle's, or the environment's where it escaped
// (tri = kNoHit; only where le is not black, so the scene has an environment).
SHARED_FN uint lightOfBsdfHit(uint tri) { return tri == kNoHit ? environmentLight() : lightOfTriangle(tri); }

// The cluster j of the point a BSDF sample along `dir` hit on emitting triangle `tri` (kNoHit: the
// environment), seen from `from`, and its p_j; kNoCell (p_j = 0) where the point emits nothing
// towards `from` (le black: the back of a one-sided emitter, a black texel of the environment or
// no environment at all counts as no light point, for BSDF and light samples alike, §1).
SHARED_FN uint clusterOfBsdfHit(uint tri, vec3 le, vec3 from, vec3 point, vec3 dir, OUT(float) pj) {
  pj = 0.0f;
  if (isBlack(le)) return kNoCell;
  if (tri == kNoHit) {
    uint env = environmentLight();
    pj = LIGHT_CLUSTER_PMF(env) * environmentPdf(dir);
    return LIGHT_CLUSTER(env);
  }
  pj = clusterPointPdf(tri, from, point);
  return LIGHT_CLUSTER(lightOfTriangle(tri));
}

// The effective c_j of the light of triangle `tri` (kNoHit: the environment; of cluster j) for a BSDF sample drawn at a
// vertex of `cell` whose light sample was chosen at (selectFrom, selectNormal): the cell's c_j, or
// with the BVH defaults vertexClusterWeight (kNoCell j: 0).
SHARED_FN float bsdfHitClusterWeight(uint cell, uint L, uint j, uint tri, vec3 selectFrom, vec3 selectNormal) {
  if (j == kNoCell) return 0.0f;
  if (!CMS_BVH_DEFAULTS) return clusterSelectPmf(cell, L, j);
  return vertexClusterWeight(cell, L, lightOfBsdfHit(tri), selectFrom, selectNormal, defaultsShare(cell, L));
}

// The mixture density of a BSDF sample of density pB that hit a point of cluster j (kNoCell: no
// light point) whose effective c_j is cj: c_j p_j + p_B.
SHARED_FN float bsdfSampleMixtureDensity(uint j, float cj, float pj, float pB) {
  return (j != kNoCell ? cj * pj : 0.0f) + pB;
}

// The balance heuristic's weight of a sample of density `pdf` with mixture density peff.
SHARED_FN float balanceWeight(float pdf, float peff) { return pdf / peff; }

// ---- The control variate (docs/estimator.md §3) ----

// g(z) = alpha_k p_k(z) + alpha_B p_B(z) in the cell's coefficients (k = kNoCell: alpha_B p_B).
SHARED_FN vec3 controlVariateAt(uint cell, uint L, uint k, float pk, float pB) {
  vec3 g = cellAlphaB(cell, L) * pB;
  if (k != kNoCell) g += cellAlpha(cell, L, k) * pk;
  return g;
}

// What a vertex in a cell with a valid solution adds once: T (sum_k alpha_k + alpha_B).
SHARED_FN vec3 controlVariateIntegral(vec3 T, uint cell, uint L) { return T * cellAlphaSum(cell, L); }

// What each of its samples subtracts: T g(z) / p_eff(z).
SHARED_FN vec3 controlVariateTerm(vec3 T, uint cell, uint L, uint k, float pk, float pB, float peff) {
  return T * controlVariateAt(cell, L, k, pk, pB) / peff;
}

// A BSDF sample that failed (pdf 0, or a direction into the surface) is still a sample: f = 0,
// in no cluster, and p_B = p_eff (any positive value: only the ratio p_B / p_eff = 1 matters), so
// it subtracts T alpha_B and adds w to A_BB. These are its densities for the functions here.
const float kFailedBsdfSamplePdf = 1.0f;

// ---- The statistics of the optimal coefficients (docs/estimator.md §4) ----

// Adds one sample's terms, with p = (.., p_k, .., p_B): A_ij += w p_i p_j / p_eff^2 and
// b_i += w f p_i / p_eff^2. Clusters are disjoint, so a sample touches only A_kk, A_kB, A_BB,
// b_k and b_B (b only for a sample in a cluster that carries light). The ratios p / p_eff
// (<= 1/c_k and <= 1) are formed first: p_eff^2 overflows a float for p_eff > 1.8e19 (a tiny
// emitter seen edge-on), and Inf * 0 would put a NaN into the cell.
SHARED_FN void addSampleStatistics(uint cell, uint L, uint k, CMS_STAT_REAL pk, CMS_STAT_REAL pB,
                                   CMS_STAT_REAL peff, vec3 f, CMS_STAT_REAL w) {
  if (!(w > CMS_STAT_REAL(0))) return;
  CMS_STAT_REAL rk = pk / peff;
  CMS_STAT_REAL rB = pB / peff;
  if (k != kNoCell) {
    CMS_ADD_STAT(cell, statsAkk(L, k), w * rk * rk);
    CMS_ADD_STAT(cell, statsAkB(L, k), w * rk * rB);
  }
  CMS_ADD_STAT(cell, statsABB(L), w * rB * rB);
  if (k == kNoCell || isBlack(f)) return;
  CMS_STAT_REAL scaleK = w * (pk / peff) / peff;
  CMS_STAT_REAL scaleB = w * (pB / peff) / peff;
  for (uint c = 0u; c < 3u; ++c) {
    CMS_ADD_STAT(cell, statsBk(L, k, c), CMS_STAT_REAL(f[c]) * scaleK);
    CMS_ADD_STAT(cell, statsBB(L, c), CMS_STAT_REAL(f[c]) * scaleB);
  }
}

SHARED_END_WITH_BUFFERS
#endif
