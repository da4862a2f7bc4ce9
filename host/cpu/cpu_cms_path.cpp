#include "cpu/cpu_cms_path.h"

#include <cmath>

#include "cpu/cpu_kernel_access.h"
#include "shared/bsdf.h"
#include "shared/ray_offset.h"
#include "shared/rng.h"
#include "shared/sampling.h"

namespace mixtrace {
namespace {

// What the BSDF sample of the previous vertex left for the next one: its terms depend on what it
// hits (docs/estimator.md §3), so they are paid once the next hit is known (shade.comp's cv* path
// state).
struct PendingBsdfSample {
  float pdf = 0.0f;              // p_B; 0: camera ray, nothing pending
  uint32_t cell = shared::kNoCell;
  glm::vec3 throughput{0.0f};    // path throughput at the vertex that drew it
  glm::vec3 bsdfCos{0.0f};       // bsdf * |cos| of its direction
};

}  // namespace

// The terms are shared/cms_vertex_terms.h's, as in shade.comp and shadow.comp; only when each is
// paid is written here (one loop instead of the GPU's shade and shadow passes).
glm::vec3 traceCmsPath(glm::vec3 origin, glm::vec3 direction, uint32_t& rng, const CmsPathContext& ctx,
                       RenderCounters& counters) {
  using namespace shared;
  CpuCmsCells& cells = *ctx.cells;
  const uint L = cells.clusterCount();
  const bool controlVariate = cells.controlVariate();
  CellGrid grid{};
  grid.origin = cells.grid().origin;
  grid.invCellSize = cells.grid().invCellSize;
  grid.tableSize = cells.grid().tableSize;

  vec3 radiance(0.0f), beta(1.0f);
  PendingBsdfSample pending;
  for (uint32_t depth = 1; depth <= ctx.maxDepth; ++depth) {
    ++counters.extensionRays;
    HitRecord hit = traceClosest(origin, direction, kFloatMax);
    const bool hitEmitter = hit.triangle != kNoHit && TRIANGLE_SHADING(hit.triangle).emitter >= 0;
    const vec3 le = hitEmitter ? emittedRadiance(hit.triangle, hit.u, hit.v, -direction) : vec3(0.0f);
    SurfaceHit sh;
    if (hit.triangle != kNoHit) sh = makeSurfaceHit(hit.triangle, hit.u, hit.v, direction);

    // The previous vertex's BSDF sample, now that its hit is known (shade.comp
    // settlePreviousBsdfSample).
    float emissionWeight = 1.0f;
    if (pending.pdf > 0.0f) {
      float pj;
      uint j = clusterOfBsdfHit(hit.triangle, le, origin, sh.position, pj);
      float peff = bsdfSampleMixtureDensity(pending.cell, L, j, pj, pending.pdf);
      emissionWeight = balanceWeight(pending.pdf, peff);
      if (controlVariate && cellSolutionValid(pending.cell, L))
        radiance -= controlVariateTerm(pending.throughput, pending.cell, L, j, pj, pending.pdf, peff);
      addSampleStatistics(pending.cell, L, j, pj, pending.pdf, peff, le * pending.bsdfCos,
                          cells.statisticsWeight(pending.cell, pending.throughput, ctx.pixel));
    }
    if (hit.triangle == kNoHit) break;   // no environment light: the path ends
    if (isBlack(beta)) break;            // continued only to settle the terms above

    // Emission reached by this ray (MIS weight against the mixture of the previous vertex).
    if (hitEmitter) radiance += beta * le * (pending.pdf > 0.0f ? emissionWeight : 1.0f);
    if (depth >= ctx.maxDepth) break;

    BsdfParams bsdf = surfaceBsdf(sh);
    OrthonormalBasis frame = makeOrthonormalBasis(sh.shadingNormal);
    vec3 wo = toLocal(frame, -direction);
    vec3 next = offsetRayOrigin(sh.position, hitPointError(hit.triangle, hit.u, hit.v), sh.geometricNormal);

    // The vertex's cell (shade.comp enterCell).
    uint cell = findOrInsertCell(grid, sh.position, sh.geometricNormal, sh.material);
    if (cell == kNoCell) cells.countVertexWithoutCell();
    if (cell != kNoCell && cells.gathering(cell)) cells.countVertex(cell);
    const bool cv = controlVariate && cellSolutionValid(cell, L);
    if (cv) radiance += controlVariateIntegral(beta, cell, L);

    // One light sample: a cluster from the cell's selection, a light in it, a point on that
    // (shade.comp queueLightSample, then shadow.comp). Named draws: C++ leaves the order of
    // constructor arguments unspecified.
    float uLight = rngNextFloat(rng);
    float uEmitter = rngNextFloat(rng);
    float uPointX = rngNextFloat(rng);
    float uPointY = rngNextFloat(rng);
    vec2 uPoint(uPointX, uPointY);
    if (ctx.lightCount > 0) {
      uint k;
      float pk;
      LightSample ls;
      bool carries = sampleClusterLight(cell, L, sh.position, uLight, uEmitter, uPoint, rng, k, pk, ls);
      const bool cmsTerms = cell != kNoCell;
      if (ls.pdf > 0.0f || cmsTerms) {
        vec3 wi = toLocal(frame, ls.direction);
        const bool reachable = lightPointReachable(cell, L, k, sh.geometricNormal, carries, pk, ls);
        float pB;
        vec3 f = lightSampleIntegrand(bsdf, wo, wi, ls, reachable, pB);
        float peff = lightSampleMixtureDensity(ls.pdf, pB);
        vec3 contribution = beta * f / peff;
        if (reachable && (!isBlack(contribution) || cmsTerms)) ++counters.shadowRays;
        if (!isBlack(contribution) || cmsTerms) {
          bool visible = false;
          if (reachable) {   // the shadow ray (shadow.comp)
            vec3 shadowDirection;
            float shadowLength;
            shadowRay(next, ls, shadowDirection, shadowLength);
            visible = !traceAny(next, shadowDirection, shadowLength);
          }
          if (visible) radiance += contribution;
          // Whether the BSDF could have sampled this point depends on its visibility: a hidden
          // point has p_B = 0 and p_eff = c_k p_k.
          float pBSeen = visible ? pB : 0.0f;
          float peffSeen = lightSampleMixtureDensity(ls.pdf, pBSeen);
          if (cmsTerms && peffSeen > 0.0f) {
            if (cv) radiance -= controlVariateTerm(beta, cell, L, k, pk, pBSeen, peffSeen);
            addSampleStatistics(cell, L, k, pk, pBSeen, peffSeen, visible ? f : vec3(0.0f),
                                cells.statisticsWeight(cell, beta, ctx.pixel));
          }
        }
      }
    }

    // One BSDF sample: the next extension ray (shade.comp sampleBsdf).
    float uDirectionX = rngNextFloat(rng);
    float uDirectionY = rngNextFloat(rng);
    vec2 uDirection(uDirectionX, uDirectionY);
    float uLobe = rngNextFloat(rng);
    vec3 wiLocal(0.0f);
    float pdf = 0.0f;
    bool sampled = bsdfSample(bsdf, wo, uDirection, uLobe, wiLocal, pdf) && pdf > 0.0f;
    vec3 wiWorld = toWorld(frame, wiLocal);
    if (!sampled || !(dot(wiWorld, sh.geometricNormal) > 0.0f)) {
      // A failed sample, or one into the surface, is still a sample with f = 0 that hits no light
      // (docs/estimator.md §1): g / p_eff = alpha_B, and it adds p_B^2 / p_eff^2 = 1 to A_BB.
      if (cv) radiance -= controlVariateTerm(beta, cell, L, kNoCell, 0.0f, kFailedBsdfSamplePdf, kFailedBsdfSamplePdf);
      addSampleStatistics(cell, L, kNoCell, 0.0, kFailedBsdfSamplePdf, kFailedBsdfSamplePdf, vec3(0.0f),
                          cells.statisticsWeight(cell, beta, ctx.pixel));
      break;
    }
    // A path that can carry nothing more is still traced, so the next depth can settle this
    // sample's control-variate and statistics terms.
    vec3 bsdfCos = bsdfEval(bsdf, wo, wiLocal) * std::abs(wiLocal.z);
    pending.pdf = pdf;
    pending.cell = cell;
    pending.throughput = beta;
    pending.bsdfCos = bsdfCos;
    beta *= bsdfCos / pdf;
    origin = next;
    direction = wiWorld;
  }
  return radiance;
}

}  // namespace mixtrace
