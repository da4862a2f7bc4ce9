// One path with controlled mixture sampling (methods learned, cv, cms; docs/estimator.md), whole,
// as a loop: at every vertex the light comes from a cluster chosen by the vertex's cell, p_eff =
// c_k p_k + p_B, every sample adds its statistics to the cell and, with the control variate, the
// vertex pays + sum(alpha) - g(z)/p_eff(z) for both samples. Written once for the two schedules
// that keep a path in registers: the CPU backend (host/cpu/cpu_cms_path.cpp) and the Vulkan
// renderer's fused schedule (wavefront/fused.comp). The wavefront passes pay the same terms split
// over dispatches (shade.comp, and shadow.comp once a light sample's visibility is known), drawing
// the same random numbers in the same order, so with the same seed and the same cell solutions
// all three trace the same paths. The terms are shared/cms_vertex_terms.h's and
// shared/cms_pair_terms.h's; only when each is paid is written here.
//
// The includer provides what shared/path_tracer.h needs (scene accessors, the traversal), the CMS
// accessors of shared/cms_cells.h, cms_sampling.h, cms_vertex_terms.h and cms_pair_terms.h, and:
//   CMS_PATH_WEIGHT(cell, beta, pixel) -> CMS_STAT_REAL: the statistics weight of a sample of a
//       vertex in `cell` with throughput `beta` in `pixel` (docs/estimator.md §5); 0 for kNoCell
//       or while the cell does not gather.
//   CMS_PATH_COUNT_VERTEX(cell): counts a vertex in its cell while that gathers, or one that found
//       no cell (kNoCell: its probe sequence in the cell table was full).
#ifndef MIXTRACE_SHARED_CMS_PATH_TRACER_H
#define MIXTRACE_SHARED_CMS_PATH_TRACER_H
#include "shared/bsdf.h"
#include "shared/cms_technique_source.h"
#include "shared/dialect.h"
#include "shared/path_tracer.h"
#include "shared/ray_offset.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "shared/scatter_side.h"
#include "shared/surface.h"
SHARED_BEGIN_WITH_BUFFERS

// What a path of this render knows of the method and the cell table.
struct CmsPathSetup {
  CellGrid grid;
  uint clusterCount;      // L
  bool controlVariate;    // cv, cms: the vertices pay the control variate
  bool pairTechniques;    // the control variate's coefficients per technique (the pair table)
  uint pairCapacity;      // slots of the pair table
  uint emitterCount;      // technique sources of punctual lights start here
  uint maxDepth;          // Mitsuba convention: 1 = emitters seen directly
  uint lightCount;
  uint pixel;             // the path's pixel, for the relative statistics weight
};

// What the BSDF sample of the previous vertex leaves for the next one: its terms depend on what it
// hits (docs/estimator.md §3), so they are paid once the next hit is known.
struct CmsPendingBsdfSample {
  float pdf;          // p_B; 0: camera ray, nothing pending
  uint cell;
  vec3 throughput;    // path throughput at the vertex that drew it
  vec3 bsdfCos;       // bsdf * |cos| of its direction
  vec3 normal;        // the vertex's geometric normal (the BVH defaults' selection)
};

// What the steps below know of a surface vertex (shade.comp's Vertex).
struct CmsVertex {
  SurfaceHit sh;
  BsdfParams bsdf;
  OrthonormalBasis frame;
  vec3 wo;          // towards the previous vertex, in the shading frame
  vec3 next;        // the offset origin of the rays leaving the vertex
  vec3 nextBelow;   // the same on the far side, for transmitted rays (= next when opaque)
  vec3 beta;        // the path throughput up to the vertex
  uint cell;        // the vertex's cell (kNoCell: none)
  bool cv;          // the cell pays a control variate
};

// The previous vertex's BSDF sample, now that its hit is known (shade.comp
// settlePreviousBsdfSample); `from` is that vertex's ray origin. Returns the emission's weight.
SHARED_FN float cmsSettlePendingBsdfSample(CmsPathSetup c, CmsPendingBsdfSample pending, HitRecord hit, SurfaceHit sh,
                                           vec3 le, vec3 from, vec3 direction, INOUT(vec3) radiance) {
  uint L = c.clusterCount;
  float pj;
  uint j = clusterOfBsdfHit(hit.triangle, le, from, sh.position, direction, pj);
  float cj = bsdfHitClusterWeight(pending.cell, L, j, hit.triangle, from, pending.normal);
  float peff = bsdfSampleMixtureDensity(j, cj, pj, pending.pdf);
  CMS_STAT_REAL w = CMS_PATH_WEIGHT(pending.cell, pending.throughput, c.pixel);
  bool cv = c.controlVariate && cellSolutionValid(pending.cell, L);
  if (c.pairTechniques && j != kNoCell) {
    // Per technique: the hit's triangle's technique.
    radiance -= settlePairSample(c.pairCapacity, pending.cell, L, j, techniqueSourceOfHit(hit.triangle, c.emitterCount),
                                 pj, pending.pdf, peff, le * pending.bsdfCos, w, pending.throughput, cv);
  } else if (c.pairTechniques) {
    // No light technique: g = alpha_B p_B alone.
    if (cv) radiance -= pairControlVariateTerm(pending.throughput, pending.cell, L, kNoPairSlot, 0.0f, pending.pdf, peff);
  } else if (cv) {
    radiance -= controlVariateTerm(pending.throughput, pending.cell, L, j, pj, pending.pdf, peff);
  }
  addSampleStatistics(pending.cell, L, j, pj, pending.pdf, peff, le * pending.bsdfCos, w);
  return balanceWeight(pending.pdf, peff);
}

// The vertex's cell, counted while it gathers; a solved cell pays the integral (shade.comp enterCell).
SHARED_FN void cmsEnterCell(CmsPathSetup c, INOUT(CmsVertex) v, INOUT(vec3) radiance) {
  v.cell = findOrInsertCell(c.grid, v.sh.position, v.sh.geometricNormal, v.sh.material);
  CMS_PATH_COUNT_VERTEX(v.cell);
  v.cv = c.controlVariate && cellSolutionValid(v.cell, c.clusterCount);
  if (v.cv) radiance += controlVariateIntegral(v.beta, v.cell, c.clusterCount);
}

// One light sample: a cluster from the cell's selection, a light in it, a point on that
// (shade.comp queueLightSample), and its shadow ray at once (shadow.comp). Named draws: C++
// leaves the order of constructor arguments unspecified.
SHARED_FN void cmsSampleLight(CmsPathSetup c, CmsVertex v, INOUT(uint) rng, INOUT(vec3) radiance,
                              INOUT(PathCounters) counters) {
  uint L = c.clusterCount;
  float uLight = rngNextFloat(rng);
  float uEmitter = rngNextFloat(rng);
  float uPointX = rngNextFloat(rng);
  float uPointY = rngNextFloat(rng);
  vec2 uPoint = vec2(uPointX, uPointY);
  if (c.lightCount == 0u) return;
  uint k;
  float pk;
  float ck;
  LightSample ls;
  bool carries = sampleClusterLight(v.cell, L, v.sh.position, v.next, v.sh.geometricNormal, uLight, uEmitter, uPoint,
                                    rng, k, pk, ck, ls);
  if (k == kNoCell) return;   // the defaults' BVH reached no light: no sample, nothing to pay
  bool cmsTerms = v.cell != kNoCell;
  if (!(ls.pdf > 0.0f || cmsTerms)) return;
  vec3 wi = toLocal(v.frame, ls.direction);
  bool reachable = lightPointReachable(ck, v.sh.geometricNormal, wi.z, bsdfTransmits(v.bsdf), carries, pk, ls);
  float pB;
  vec3 f = lightSampleIntegrand(v.bsdf, v.wo, wi, ls, reachable, pB);
  float peff = lightSampleMixtureDensity(ls.pdf, pB);
  vec3 contribution = v.beta * f / peff;
  if (reachable && (!isBlack(contribution) || cmsTerms)) counters.shadowRays += 1u;
  if (isBlack(contribution) && !cmsTerms) return;
  bool visible = false;
  if (reachable) {   // the shadow ray (shadow.comp)
    vec3 shadowDirection;
    float shadowLength;
    vec3 from = originTowards(ls.direction, v.sh.geometricNormal, v.next, v.nextBelow);
    shadowRay(from, ls, shadowDirection, shadowLength);
    visible = !traceAny(from, shadowDirection, shadowLength);
  }
  if (visible) radiance += contribution;
  // Whether the BSDF could have sampled this point depends on its visibility: a hidden point
  // has p_B = 0 and p_eff = c_k p_k.
  float pBSeen = visible ? pB : 0.0f;
  float peffSeen = lightSampleMixtureDensity(ls.pdf, pBSeen);
  if (!(cmsTerms && peffSeen > 0.0f)) return;
  vec3 fSeen = visible ? f : vec3(0.0f);
  CMS_STAT_REAL w = CMS_PATH_WEIGHT(v.cell, v.beta, c.pixel);
  if (c.pairTechniques) {
    // Per technique: the sampled point's triangle (or punctual light), even when hidden or blocked.
    radiance -= settlePairSample(c.pairCapacity, v.cell, L, k, techniqueSourceOfLightSample(ls, c.emitterCount), pk,
                                 pBSeen, peffSeen, fSeen, w, v.beta, v.cv);
  } else if (v.cv) {
    radiance -= controlVariateTerm(v.beta, v.cell, L, k, pk, pBSeen, peffSeen);
  }
  addSampleStatistics(v.cell, L, k, pk, pBSeen, peffSeen, fSeen, w);
}

// One BSDF sample (shade.comp sampleBsdf): false when the path ends (a failed sample, settled at
// once); otherwise it becomes `pending`, `beta` the throughput beyond it, `wiWorld` its direction.
SHARED_FN bool cmsSampleBsdf(CmsPathSetup c, CmsVertex v, INOUT(uint) rng, INOUT(CmsPendingBsdfSample) pending,
                             INOUT(vec3) beta, OUT(vec3) wiWorld, INOUT(vec3) radiance) {
  uint L = c.clusterCount;
  float uDirectionX = rngNextFloat(rng);
  float uDirectionY = rngNextFloat(rng);
  vec2 uDirection = vec2(uDirectionX, uDirectionY);
  float uLobe = rngNextFloat(rng);
  vec3 wiLocal = vec3(0.0f);
  float pdf = 0.0f;
  bool sampled = bsdfSample(v.bsdf, v.wo, uDirection, uLobe, wiLocal, pdf) && pdf > 0.0f;
  wiWorld = toWorld(v.frame, wiLocal);
  if (!sampled || !leavesOnShadingSide(wiWorld, v.sh.geometricNormal, wiLocal.z)) {
    // A failed sample, or one on the wrong side of the geometric surface, is still a sample with
    // f = 0 that hits no light (docs/estimator.md §1): g / p_eff = alpha_B, and it adds
    // p_B^2 / p_eff^2 = 1 to A_BB.
    if (v.cv)
      radiance -= controlVariateTerm(v.beta, v.cell, L, kNoCell, 0.0f, kFailedBsdfSamplePdf, kFailedBsdfSamplePdf);
    addSampleStatistics(v.cell, L, kNoCell, 0.0f, kFailedBsdfSamplePdf, kFailedBsdfSamplePdf, vec3(0.0f),
                        CMS_PATH_WEIGHT(v.cell, v.beta, c.pixel));
    return false;
  }
  // A path that can carry nothing more is still traced, so the next depth can settle this
  // sample's control-variate and statistics terms.
  vec3 bsdfCos = bsdfEval(v.bsdf, v.wo, wiLocal) * abs(wiLocal.z);
  pending.pdf = pdf;
  pending.cell = v.cell;
  pending.throughput = v.beta;
  pending.bsdfCos = bsdfCos;
  pending.normal = v.sh.geometricNormal;
  beta *= bsdfCos / pdf;
  return true;
}

// The radiance of the path from `origin` along `direction`; `rng` continues the camera sample's
// random numbers. `firstCell` is the cell of its first hit (kNoCell where the camera ray escapes or
// the hit found none), which the viewer's cell views show.
SHARED_FN vec3 traceCmsPath(CmsPathSetup c, vec3 origin, vec3 direction, INOUT(uint) rng,
                            INOUT(PathCounters) counters, OUT(uint) firstCell) {
  firstCell = kNoCell;
  vec3 radiance = vec3(0.0f);
  vec3 beta = vec3(1.0f);
  CmsPendingBsdfSample pending;
  pending.pdf = 0.0f;
  pending.cell = kNoCell;
  pending.throughput = vec3(0.0f);
  pending.bsdfCos = vec3(0.0f);
  pending.normal = vec3(0.0f);
  for (uint depth = 1u; depth <= c.maxDepth; ++depth) {
    counters.extensionRays += 1u;
    HitRecord hit = traceClosest(origin, direction, kFloatMax);
    SurfaceHit sh;
    SurfaceMaterial sm;
    if (hit.triangle != kNoHit) {
      sh = makeSurfaceHit(hit.triangle, hit.u, hit.v, direction);
      sm = surfaceMaterial(sh);
    }
    bool hitEmitter = hit.triangle != kNoHit && HAS_AREA_LIGHTS && sh.emitter >= 0;
    bool escaped = hit.triangle == kNoHit && HAS_ENVIRONMENT && hasEnvironmentLight();
    vec3 le = hitEmitter ? surfaceEmission(sh, sm) : escaped ? environmentRadiance(direction) : vec3(0.0f);

    float emissionWeight = 1.0f;
    if (pending.pdf > 0.0f)
      emissionWeight = cmsSettlePendingBsdfSample(c, pending, hit, sh, le, origin, direction, radiance);
    if (hit.triangle == kNoHit) {   // the path ends, with the environment's light if there is one
      if (escaped) radiance += beta * le * emissionWeight;
      break;
    }
    if (isBlack(beta)) break;   // continued only to settle the terms above

    // Emission reached by this ray (MIS weight against the mixture of the previous vertex).
    if (hitEmitter) radiance += beta * le * emissionWeight;
    if (depth >= c.maxDepth) break;

    CmsVertex v;
    v.sh = sh;
    v.bsdf = surfaceBsdf(sh, sm);
    v.frame = makeOrthonormalBasis(sh.shadingNormal);
    v.wo = toLocal(v.frame, -direction);
    scatterOrigins(sh.position, sh.positionError, sh.geometricNormal, bsdfTransmits(v.bsdf), v.next, v.nextBelow);
    v.beta = beta;
    v.cell = kNoCell;
    v.cv = false;
    cmsEnterCell(c, v, radiance);
    if (depth == 1u) firstCell = v.cell;
    cmsSampleLight(c, v, rng, radiance, counters);
    vec3 wiWorld;
    if (!cmsSampleBsdf(c, v, rng, pending, beta, wiWorld, radiance)) break;
    origin = originTowards(wiWorld, v.sh.geometricNormal, v.next, v.nextBelow);
    direction = wiWorld;
  }
  return radiance;
}

SHARED_END_WITH_BUFFERS
#endif
