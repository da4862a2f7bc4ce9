#include "cpu/cpu_cms_path.h"

#include <cmath>

#include "cpu/cpu_kernel_access.h"
#include "shared/bsdf.h"
#include "shared/ray_offset.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "shared/scatter_side.h"

namespace mixtrace {
namespace {

using namespace shared;

// What the BSDF sample of the previous vertex left for the next one: its terms depend on what it
// hits (docs/estimator.md §3), so they are paid once the next hit is known (shade.comp's cv* path
// state).
struct PendingBsdfSample {
  float pdf = 0.0f;              // p_B; 0: camera ray, nothing pending
  uint32_t cell = kNoCell;
  glm::vec3 throughput{0.0f};    // path throughput at the vertex that drew it
  glm::vec3 bsdfCos{0.0f};       // bsdf * |cos| of its direction
  glm::vec3 normal{0.0f};        // the vertex's geometric normal (the BVH defaults' selection)
};

// What the steps below know of a surface vertex (shade.comp's Vertex).
struct Vertex {
  SurfaceHit sh;
  BsdfParams bsdf;
  OrthonormalBasis frame;
  vec3 wo;       // towards the previous vertex, in the shading frame
  vec3 next;     // the offset origin of the rays leaving the vertex
  vec3 nextBelow;   // the same on the far side, for transmitted rays (= next when opaque)
  vec3 beta;     // the path throughput up to the vertex
  uint cell;     // the vertex's cell (kNoCell: none)
  bool cv;       // the cell pays a control variate
};

// One path, in the steps of shade.comp (and shadow.comp, whose shadow ray is traced at once). The
// terms are shared/cms_vertex_terms.h's; only when each is paid is written here.
class CmsPath {
 public:
  CmsPath(const CmsPathContext& ctx, RenderCounters& counters)
      : ctx_(ctx), counters_(counters), cells_(*ctx.cells), L_(cells_.clusterCount()),
        controlVariate_(cells_.controlVariate()), pairs_(cells_.pairTechniques()),
        pairCapacity_(cells_.pairCapacity()) {
    grid_.origin = cells_.grid().origin;
    grid_.invCellSize = cells_.grid().invCellSize;
    grid_.tableSize = cells_.grid().tableSize;
  }

  vec3 trace(vec3 origin, vec3 direction, uint32_t& rng) {
    vec3 beta(1.0f);
    PendingBsdfSample pending;
    for (uint32_t depth = 1; depth <= ctx_.maxDepth; ++depth) {
      ++counters_.extensionRays;
      HitRecord hit = traceClosest(origin, direction, kFloatMax);
      SurfaceHit sh;
      SurfaceMaterial sm;
      if (hit.triangle != kNoHit) {
        sh = makeSurfaceHit(hit.triangle, hit.u, hit.v, direction);
        sm = surfaceMaterial(sh);
      }
      const bool hitEmitter = hit.triangle != kNoHit && sh.emitter >= 0;
      const bool escaped = hit.triangle == kNoHit && hasEnvironmentLight();
      const vec3 le = hitEmitter ? surfaceEmission(sh, sm) : escaped ? environmentRadiance(direction) : vec3(0.0f);

      float emissionWeight = 1.0f;
      if (pending.pdf > 0.0f) emissionWeight = settlePendingBsdfSample(pending, hit, sh, le, origin, direction);
      if (hit.triangle == kNoHit) {   // the path ends, with the environment's light if there is one
        if (escaped) radiance_ += beta * le * (pending.pdf > 0.0f ? emissionWeight : 1.0f);
        break;
      }
      if (isBlack(beta)) break;            // continued only to settle the terms above

      // Emission reached by this ray (MIS weight against the mixture of the previous vertex).
      if (hitEmitter) radiance_ += beta * le * (pending.pdf > 0.0f ? emissionWeight : 1.0f);
      if (depth >= ctx_.maxDepth) break;

      Vertex v;
      v.sh = sh;
      v.bsdf = surfaceBsdf(sh, sm);
      v.frame = makeOrthonormalBasis(sh.shadingNormal);
      v.wo = toLocal(v.frame, -direction);
      scatterOrigins(sh.position, sh.positionError, sh.geometricNormal, bsdfTransmits(v.bsdf), v.next,
                     v.nextBelow);
      v.beta = beta;
      enterCell(v);
      sampleLight(v, rng);
      vec3 wiWorld;
      if (!sampleBsdf(v, rng, pending, beta, wiWorld)) break;
      origin = originTowards(wiWorld, v.sh.geometricNormal, v.next, v.nextBelow);
      direction = wiWorld;
    }
    return radiance_;
  }

 private:
  // The previous vertex's BSDF sample, now that its hit is known (shade.comp
  // settlePreviousBsdfSample); `from` is that vertex's ray origin. Returns the emission's weight.
  float settlePendingBsdfSample(const PendingBsdfSample& pending, const HitRecord& hit, const SurfaceHit& sh,
                                vec3 le, vec3 from, vec3 direction) {
    float pj;
    uint j = clusterOfBsdfHit(hit.triangle, le, from, sh.position, direction, pj);
    float cj = bsdfHitClusterWeight(pending.cell, L_, j, hit.triangle, from, pending.normal);
    float peff = bsdfSampleMixtureDensity(j, cj, pj, pending.pdf);
    const double w = cells_.statisticsWeight(pending.cell, pending.throughput, ctx_.pixel);
    const bool cv = controlVariate_ && cellSolutionValid(pending.cell, L_);
    if (pairs_ && j != kNoCell) {
      // Per technique: the hit's triangle's technique.
      radiance_ -= settlePairSample(pairCapacity_, pending.cell, L_, j, techniqueSourceOfHit(hit.triangle, cells_.emitterCount()), pj,
                                    pending.pdf, peff, le * pending.bsdfCos, w, pending.throughput, cv);
    } else if (pairs_) {
      // No light technique: g = alpha_B p_B alone.
      if (cv) radiance_ -= pairControlVariateTerm(pending.throughput, pending.cell, L_, kNoPairSlot, 0.0f, pending.pdf, peff);
    } else if (cv) {
      radiance_ -= controlVariateTerm(pending.throughput, pending.cell, L_, j, pj, pending.pdf, peff);
    }
    addSampleStatistics(pending.cell, L_, j, pj, pending.pdf, peff, le * pending.bsdfCos, w);
    return balanceWeight(pending.pdf, peff);
  }

  // The vertex's cell, counted while it gathers; a solved cell pays the integral (shade.comp enterCell).
  void enterCell(Vertex& v) {
    v.cell = findOrInsertCell(grid_, v.sh.position, v.sh.geometricNormal, v.sh.material);
    if (v.cell == kNoCell) cells_.countVertexWithoutCell();
    if (v.cell != kNoCell && cells_.gathering(v.cell)) cells_.countVertex(v.cell);
    v.cv = controlVariate_ && cellSolutionValid(v.cell, L_);
    if (v.cv) radiance_ += controlVariateIntegral(v.beta, v.cell, L_);
  }

  // One light sample: a cluster from the cell's selection, a light in it, a point on that
  // (shade.comp queueLightSample), and its shadow ray at once (shadow.comp). Named draws: C++
  // leaves the order of constructor arguments unspecified.
  void sampleLight(const Vertex& v, uint32_t& rng) {
    float uLight = rngNextFloat(rng);
    float uEmitter = rngNextFloat(rng);
    float uPointX = rngNextFloat(rng);
    float uPointY = rngNextFloat(rng);
    vec2 uPoint(uPointX, uPointY);
    if (ctx_.lightCount == 0) return;
    uint k;
    float pk, ck;
    LightSample ls;
    bool carries = sampleClusterLight(v.cell, L_, v.sh.position, v.next, v.sh.geometricNormal, uLight, uEmitter,
                                      uPoint, rng, k, pk, ck, ls);
    if (k == kNoCell) return;   // the defaults' BVH reached no light: no sample, nothing to pay
    const bool cmsTerms = v.cell != kNoCell;
    if (!(ls.pdf > 0.0f || cmsTerms)) return;
    vec3 wi = toLocal(v.frame, ls.direction);
    const bool reachable =
        lightPointReachable(ck, v.sh.geometricNormal, wi.z, bsdfTransmits(v.bsdf), carries, pk, ls);
    float pB;
    vec3 f = lightSampleIntegrand(v.bsdf, v.wo, wi, ls, reachable, pB);
    float peff = lightSampleMixtureDensity(ls.pdf, pB);
    vec3 contribution = v.beta * f / peff;
    if (reachable && (!isBlack(contribution) || cmsTerms)) ++counters_.shadowRays;
    if (isBlack(contribution) && !cmsTerms) return;
    bool visible = false;
    if (reachable) {   // the shadow ray (shadow.comp)
      vec3 shadowDirection;
      float shadowLength;
      const vec3 from = originTowards(ls.direction, v.sh.geometricNormal, v.next, v.nextBelow);
      shadowRay(from, ls, shadowDirection, shadowLength);
      visible = !traceAny(from, shadowDirection, shadowLength);
    }
    if (visible) radiance_ += contribution;
    // Whether the BSDF could have sampled this point depends on its visibility: a hidden point
    // has p_B = 0 and p_eff = c_k p_k.
    float pBSeen = visible ? pB : 0.0f;
    float peffSeen = lightSampleMixtureDensity(ls.pdf, pBSeen);
    if (!(cmsTerms && peffSeen > 0.0f)) return;
    const vec3 fSeen = visible ? f : vec3(0.0f);
    const double w = cells_.statisticsWeight(v.cell, v.beta, ctx_.pixel);
    if (pairs_) {
      // Per technique: the sampled point's triangle (or punctual light), even when hidden or blocked.
      radiance_ -= settlePairSample(pairCapacity_, v.cell, L_, k, techniqueSourceOfLightSample(ls, cells_.emitterCount()),
                                    pk, pBSeen, peffSeen, fSeen, w, v.beta, v.cv);
    } else if (v.cv) {
      radiance_ -= controlVariateTerm(v.beta, v.cell, L_, k, pk, pBSeen, peffSeen);
    }
    addSampleStatistics(v.cell, L_, k, pk, pBSeen, peffSeen, fSeen, w);
  }

  // One BSDF sample (shade.comp sampleBsdf): false when the path ends (a failed sample, settled at
  // once); otherwise it becomes `pending`, `beta` the throughput beyond it, `wiWorld` its direction.
  bool sampleBsdf(const Vertex& v, uint32_t& rng, PendingBsdfSample& pending, vec3& beta, vec3& wiWorld) {
    float uDirectionX = rngNextFloat(rng);
    float uDirectionY = rngNextFloat(rng);
    vec2 uDirection(uDirectionX, uDirectionY);
    float uLobe = rngNextFloat(rng);
    vec3 wiLocal(0.0f);
    float pdf = 0.0f;
    bool sampled = bsdfSample(v.bsdf, v.wo, uDirection, uLobe, wiLocal, pdf) && pdf > 0.0f;
    wiWorld = toWorld(v.frame, wiLocal);
    if (!sampled || !leavesOnShadingSide(wiWorld, v.sh.geometricNormal, wiLocal.z)) {
      // A failed sample, or one on the wrong side of the geometric surface, is still a sample with f = 0 that hits no light
      // (docs/estimator.md §1): g / p_eff = alpha_B, and it adds p_B^2 / p_eff^2 = 1 to A_BB.
      if (v.cv)
        radiance_ -= controlVariateTerm(v.beta, v.cell, L_, kNoCell, 0.0f, kFailedBsdfSamplePdf, kFailedBsdfSamplePdf);
      addSampleStatistics(v.cell, L_, kNoCell, 0.0, kFailedBsdfSamplePdf, kFailedBsdfSamplePdf, vec3(0.0f),
                          cells_.statisticsWeight(v.cell, v.beta, ctx_.pixel));
      return false;
    }
    // A path that can carry nothing more is still traced, so the next depth can settle this
    // sample's control-variate and statistics terms.
    vec3 bsdfCos = bsdfEval(v.bsdf, v.wo, wiLocal) * std::abs(wiLocal.z);
    pending.pdf = pdf;
    pending.cell = v.cell;
    pending.throughput = v.beta;
    pending.bsdfCos = bsdfCos;
    pending.normal = v.sh.geometricNormal;
    beta *= bsdfCos / pdf;
    return true;
  }

  const CmsPathContext& ctx_;
  RenderCounters& counters_;
  CpuCmsCells& cells_;
  const uint L_;
  const bool controlVariate_;
  const bool pairs_;             // coefficients per technique (shared/cms_pair_terms.h), not per cluster
  const uint32_t pairCapacity_;
  CellGrid grid_{};
  vec3 radiance_{0.0f};
};

}  // namespace

glm::vec3 traceCmsPath(glm::vec3 origin, glm::vec3 direction, uint32_t& rng, const CmsPathContext& ctx,
                       RenderCounters& counters) {
  return CmsPath(ctx, counters).trace(origin, direction, rng);
}

}  // namespace mixtrace
