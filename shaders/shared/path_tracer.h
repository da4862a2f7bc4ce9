// One path through the scene, whole, as a loop: emission at every vertex (MIS-weighted against
// light sampling), one light sample (its shadow ray traced at once) and one BSDF sample per vertex,
// balance heuristic. The estimator of the methods without learning (pt-uniform, pt-power, pt-bvh)
// written once for the two schedules that keep a path in registers: the CPU backend
// (host/cpu/cpu_renderer.cpp) and the Vulkan renderer's fused schedule (wavefront/fused.comp), the
// one for CPU devices, where every dispatch of the wavefront schedule ends in a thread-pool
// barrier. The wavefront passes (shade.comp, shadow.comp) compute the same terms split over
// dispatches; the same seed draws the same random numbers in the same order in all three.
//
// The includer provides the scene accessors and the traversal (bvh_traverse.h with its alpha
// hook), as for surface.h and lights.h.
#ifndef MIXTRACE_SHARED_PATH_TRACER_H
#define MIXTRACE_SHARED_PATH_TRACER_H
#include "shared/bsdf.h"
#include "shared/dialect.h"
#include "shared/lights.h"
#include "shared/ray_offset.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "shared/scatter_side.h"
#include "shared/surface.h"
SHARED_BEGIN_WITH_BUFFERS

// The rays a path traced, for the stats.
struct PathCounters {
  uint extensionRays;
  uint shadowRays;
};

SHARED_FN vec3 tracePath(vec3 origin, vec3 direction, INOUT(uint) rng, uint maxDepth, uint lightCount,
                         INOUT(PathCounters) counters) {
  vec3 radiance = vec3(0.0f);
  vec3 throughput = vec3(1.0f);
  float previousBsdfPdf = 0.0f;  // 0: camera ray, whose emitter hits take no MIS weight
  vec3 previousNormal = vec3(0.0f);   // the geometric normal at `origin` (the light BVH's pmf reads it)
  for (uint depth = 1u; depth <= maxDepth; ++depth) {
    counters.extensionRays += 1u;
    HitRecord hit = traceClosest(origin, direction, kFloatMax);
    if (hit.triangle == kNoHit) {
      // The environment, weighted against light sampling (a camera ray's is not).
      if (HAS_ENVIRONMENT && hasEnvironmentLight()) {
        float weight = 1.0f;
        if (previousBsdfPdf > 0.0f)
          weight = previousBsdfPdf / (previousBsdfPdf + environmentLightPdfAt(origin, previousNormal, direction));
        radiance += throughput * environmentRadiance(direction) * weight;
      }
      break;
    }
    SurfaceHit sh = makeSurfaceHit(hit.triangle, hit.u, hit.v, direction);
    SurfaceMaterial sm = surfaceMaterial(sh);

    if (HAS_AREA_LIGHTS && sh.emitter >= 0) {
      vec3 le = surfaceEmission(sh, sm);
      float weight = 1.0f;
      if (previousBsdfPdf > 0.0f) {
        float lightPdf = emitterLightPdfAt(uint(sh.emitter), hit.triangle, origin, previousNormal, sh.position);
        weight = previousBsdfPdf / (previousBsdfPdf + lightPdf);
      }
      radiance += throughput * le * weight;
    }
    if (depth == maxDepth) break;

    BsdfParams bsdf = surfaceBsdf(sh, sm);
    OrthonormalBasis frame = makeOrthonormalBasis(sh.shadingNormal);
    vec3 wo = toLocal(frame, -direction);
    vec3 next;
    vec3 nextBelow;
    scatterOrigins(sh.position, sh.positionError, sh.geometricNormal, bsdfTransmits(bsdf), next, nextBelow);

    // Draws in named steps: C++ leaves the order of constructor arguments unspecified, and the
    // same seed gives every schedule the same random numbers in the same order.
    float uLight = rngNextFloat(rng);
    float uEmitter = rngNextFloat(rng);
    float uPointX = rngNextFloat(rng);
    float uPointY = rngNextFloat(rng);
    vec2 uPoint = vec2(uPointX, uPointY);
    LightSample ls;
    // Chosen at the rays' origin `next` and the geometric normal, as the MIS weight above has them.
    if (lightCount > 0u && sampleLightAt(sh.position, next, sh.geometricNormal, lightCount, uLight, uEmitter, uPoint, ls) &&
        lightSideReachable(ls.direction, sh.geometricNormal, toLocal(frame, ls.direction).z, bsdfTransmits(bsdf))) {
      vec3 wi = toLocal(frame, ls.direction);
      vec3 f = bsdfEval(bsdf, wo, wi) * abs(wi.z);
      float weight = ls.isDelta ? 1.0f : ls.pdf / (ls.pdf + bsdfPdf(bsdf, wo, wi));
      vec3 contribution = throughput * f * ls.radiance * (weight / ls.pdf);
      if (!isBlack(contribution)) {
        counters.shadowRays += 1u;
        vec3 shadowDirection;
        float shadowLength;
        vec3 from = originTowards(ls.direction, sh.geometricNormal, next, nextBelow);
        shadowRay(from, ls, shadowDirection, shadowLength);
        if (!traceAny(from, shadowDirection, shadowLength)) radiance += contribution;
      }
    }

    float uDirectionX = rngNextFloat(rng);
    float uDirectionY = rngNextFloat(rng);
    vec2 uDirection = vec2(uDirectionX, uDirectionY);
    float uLobe = rngNextFloat(rng);
    vec3 wiLocal;
    float pdf;
    if (!bsdfSample(bsdf, wo, uDirection, uLobe, wiLocal, pdf) || !(pdf > 0.0f)) break;
    vec3 wiWorld = toWorld(frame, wiLocal);
    if (!leavesOnShadingSide(wiWorld, sh.geometricNormal, wiLocal.z)) break;
    vec3 weight = bsdfEval(bsdf, wo, wiLocal) * (abs(wiLocal.z) / pdf);
    if (isBlack(weight)) break;
    throughput *= weight;
    previousBsdfPdf = pdf;
    previousNormal = sh.geometricNormal;
    origin = originTowards(wiWorld, sh.geometricNormal, next, nextBelow);
    direction = wiWorld;
  }
  return radiance;
}

SHARED_END_WITH_BUFFERS
#endif
