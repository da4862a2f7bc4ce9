#version 460
#extension GL_GOOGLE_include_directive : require
// Stage 3: at every queued path's hit: emission (MIS-weighted against light sampling), one light
// sample (queued as a shadow ray with its contribution) and one BSDF sample (the next extension
// ray). Balance heuristic over the two techniques: p_eff = p_light + p_bsdf.
#include "gpu/buffers.glsl"
#include "shared/bsdf.h"
#include "shared/lights.h"
#include "shared/ray_offset.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "shared/surface.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= queues.rayCount[pc.queueIn]) return;
  uint path = rayQueue[pc.queueIn * pc.pathCount + i];
  HitRecord hit = hits[path];
  if (hit.triangle == kNoHit) return;   // no environment light: the path ends

  vec3 dir = rayDirection[path];
  vec3 beta = throughput[path];
  SurfaceHit sh = makeSurfaceHit(hit.triangle, hit.u, hit.v, dir);

  // Emission reached by this ray.
  if (HAS_AREA_LIGHTS && triangleShading[hit.triangle].emitter >= 0) {
    vec3 le = emittedRadiance(hit.triangle, hit.u, hit.v, -dir);
    float bsdfPdfPrev = misPdf[path];
    float w = 1.0;
    if (bsdfPdfPrev > 0.0) {
      float lightPdf = areaLightPdf(hit.triangle, rayOrigin[path], sh.position);
      w = bsdfPdfPrev / (bsdfPdfPrev + lightPdf);
    }
    radiance[path] += beta * le * w;
  }
  if (pc.depth >= pc.maxDepth) return;

  uint rng = rngState[path];
  BsdfParams bsdf = surfaceBsdf(sh);
  OrthonormalBasis frame = makeOrthonormalBasis(sh.shadingNormal);
  vec3 wo = toLocal(frame, -dir);
  vec3 origin = offsetRayOrigin(sh.position, sh.geometricNormal);

  // One light sample (next event estimation).
  float uLight = rngNextFloat(rng);
  float uEmitter = rngNextFloat(rng);
  vec2 uPoint = vec2(rngNextFloat(rng), rngNextFloat(rng));
  LightSample ls;
  if (pc.lightCount > 0u && sampleLight(sh.position, pc.lightCount, uLight, uEmitter, uPoint, ls) &&
      dot(ls.direction, sh.geometricNormal) > 0.0) {
    vec3 wi = toLocal(frame, ls.direction);
    vec3 f = bsdfEval(bsdf, wo, wi) * abs(wi.z);
    float w = ls.isDelta ? 1.0 : ls.pdf / (ls.pdf + bsdfPdf(bsdf, wo, wi));
    vec3 contribution = beta * f * ls.radiance * (w / ls.pdf);
    if (contribution.x > 0.0 || contribution.y > 0.0 || contribution.z > 0.0) {
      ShadowRay s;
      s.origin = origin;
      s.path = path;
      s.contribution = contribution;
      s.pad = 0.0;
      shadowRay(origin, ls, s.direction, s.tMax);
      uint slot = atomicAdd(queues.shadowCount, 1u);
      shadowQueue[slot] = s;
    }
  }

  // One BSDF sample: the next extension ray. A failed sample ends the path.
  vec2 uDir = vec2(rngNextFloat(rng), rngNextFloat(rng));
  float uLobe = rngNextFloat(rng);
  vec3 wiLocal;
  float pdf;
  rngState[path] = rng;
  if (!bsdfSample(bsdf, wo, uDir, uLobe, wiLocal, pdf) || !(pdf > 0.0)) return;
  vec3 wiWorld = toWorld(frame, wiLocal);
  if (!(dot(wiWorld, sh.geometricNormal) > 0.0)) return;
  vec3 weight = bsdfEval(bsdf, wo, wiLocal) * (abs(wiLocal.z) / pdf);
  if (!(weight.x > 0.0 || weight.y > 0.0 || weight.z > 0.0)) return;
  throughput[path] = beta * weight;
  misPdf[path] = pdf;
  rayOrigin[path] = origin;
  rayDirection[path] = wiWorld;
  uint queueOut = 1u - pc.queueIn;
  uint slot = atomicAdd(queues.rayCount[queueOut], 1u);
  rayQueue[queueOut * pc.pathCount + slot] = path;
}
