// Light selection and light sampling at a shading point, and the pdf of the same sample for
// MIS when a BSDF sample hits an emitter. One source for the GPU shade pass, the CPU code and
// the tests that check the returned pdf equals the evaluated one.
//
// The includer defines the buffer accessors LIGHT(i), EMITTER(i), TRIANGLE(i), TRIANGLE_SHADING(i),
// MATERIAL(i) (and TEXTURE(i), TEXEL(i) for texture.h, ENV_DATA(i) for environment.h), the method's
// selection distribution LIGHT_SELECT_PMF(i) and LIGHT_SELECT_CDF(i) (LightSelectionGpu), and the
// feature switches HAS_TEXTURES, HAS_AREA_LIGHTS, HAS_PUNCTUAL_LIGHTS, HAS_ENVIRONMENT and
// SINGLE_LIGHT (specialization constants on the GPU), and
// EMITTERS_UNIFORM: true where the method's selection is uniform (kLightSelectUniform), which picks
// the triangle inside a light uniformly instead of by EmitterGpu.pmf.
#ifndef MIXTRACE_SHARED_LIGHTS_H
#define MIXTRACE_SHARED_LIGHTS_H
#include "shared/constants.h"
#include "shared/dialect.h"
#include "shared/environment.h"
#include "shared/layouts.h"
#include "shared/ray_offset.h"
#include "shared/sampling.h"
#include "shared/texture.h"
#include "shared/triangle_attributes.h"
#ifdef LIGHT_BVH
#include "shared/light_bvh.h"
#endif
#ifndef EMITTERS_UNIFORM
#error "define EMITTERS_UNIFORM (the method's selection is uniform) before including shared/lights.h"
#endif
SHARED_BEGIN_WITH_BUFFERS

struct LightSample {
  vec3 direction;   // unit, from the shading point towards the light
  float distance;   // to the light point (kFloatMax for directional lights and the environment)
  vec3 radiance;    // arriving along -direction: Le (area, environment) or intensity / d^2 * falloff (punctual)
  float pdf;        // solid-angle pdf including selection (area); selection pmf (delta lights)
  vec3 position;    // the point on the light (area, point, spot)
  uint light;
  vec3 normal;      // geometric normal of the emitter at the point (area)
  uint triangle;    // emitting triangle (area), kNoHit otherwise (punctual lights, the environment)
  vec3 positionError;  // rounding-error bound of `position` (area: ray_offset.h), 0 otherwise
  bool isDelta;
};

// Picks a light from the selection distribution (inclusive CDF, binary search).
SHARED_FN uint selectLight(float u, uint lightCount) {
  if (SINGLE_LIGHT) return 0u;
  uint lo = 0u;
  uint hi = lightCount - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) >> 1u;
    if (u < LIGHT_SELECT_CDF(mid)) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

SHARED_FN float lightSelectPmf(uint light) {
  if (SINGLE_LIGHT) return 1.0f;
  return LIGHT_SELECT_PMF(light);
}

// The emitter of light l for u in [0, 1): uniformly (EMITTERS_UNIFORM), else by the CDF of
// EmitterGpu.pmf (binary search).
SHARED_FN uint selectEmitter(LightGpu l, float u) {
  if (EMITTERS_UNIFORM) return l.firstEmitter + min(uint(u * float(l.emitterCount)), l.emitterCount - 1u);
  uint lo = l.firstEmitter;
  uint hi = l.firstEmitter + l.emitterCount - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) >> 1u;
    if (u < EMITTER(mid).cdf) hi = mid; else lo = mid + 1u;
  }
  return lo;
}

// The probability of emitter e inside its light, as selectEmitter picks it.
SHARED_FN float emitterPmf(uint e) {
  EmitterGpu em = EMITTER(e);
  return emitterPmfInLight(em, LIGHT(em.light).emitterCount, EMITTERS_UNIFORM);
}

// Length of v without squaring its components in float: length() is 0 below ~1e-19 and
// infinite above ~1e19, so a light 1e-12 across had no area and one 1e15 across no distance.
SHARED_FN float scaledLength(vec3 v) {
  float m = max(max(abs(v.x), abs(v.y)), abs(v.z));
  return m > 0.0f && m <= kFloatMax ? m * length(v / m) : m;
}

// The cross product of the edges scaled to unit length: its direction is the geometric normal,
// its length sin(angle between the edges), whatever the triangle's size.
SHARED_FN vec3 unitEdgeCross(TriangleGeom g, OUT(float) len1, OUT(float) len2) {
  len1 = scaledLength(g.e1);
  len2 = scaledLength(g.e2);
  if (!(len1 > 0.0f && len2 > 0.0f)) return vec3(0.0f);
  return cross(g.e1 / len1, g.e2 / len2);
}

// The unit normal along unitEdgeCross's c (0 for a degenerate triangle).
SHARED_FN vec3 normalOfUnitEdgeCross(vec3 c) {
  float sinAngle = scaledLength(c);
  return sinAngle > 0.0f ? c / sinAngle : vec3(0.0f);
}

SHARED_FN vec3 triangleGeometricNormal(TriangleGeom g) {
  float len1, len2;
  return normalOfUnitEdgeCross(unitEdgeCross(g, len1, len2));
}

// Solid-angle density of a uniform point on the triangle seen along d (from the shading point to
// the point): distance^2 / (area |cos|). The density is dimensionless (scale invariant), so it is
// formed from ratios, (|d| / |e1|) (|d| / |e2|) * 2 / |dot(e1/|e1| x e2/|e2|, d/|d|)|, never from
// the area or the squared distance themselves, which under/overflow in float at scene scales
// that the coordinates handle fine (1e-12 -> area 1e-24, distance^2 underflows; 1e15 -> area
// 1e30 times a distance^2 of 1e30 overflows). 0 when the point has no density (degenerate
// triangle, a point in the triangle's plane or at the shading point).
// The same from unitEdgeCross's results and d's scaledLength `dist`, for a caller that has them.
SHARED_FN float solidAnglePdfOfUnitEdgeCross(vec3 c, float len1, float len2, vec3 d, float dist) {
  if (!(dist > 0.0f && len1 > 0.0f && len2 > 0.0f)) return 0.0f;
  float cosTimesSin = abs(dot(c, d / dist));
  if (!(cosTimesSin > 0.0f)) return 0.0f;
  return 2.0f * (dist / len1) * (dist / len2) / cosTimesSin;
}

SHARED_FN float triangleSolidAnglePdf(TriangleGeom g, vec3 d) {
  float len1, len2;
  vec3 c = unitEdgeCross(g, len1, len2);
  return solidAnglePdfOfUnitEdgeCross(c, len1, len2, d, scaledLength(d));
}

// Radiance leaving triangle `tri` at barycentrics (u, v) towards `towardsViewer` (any length).
// One-sided (front face = counter-clockwise) unless the material is double-sided.
// emittedRadianceOf takes the triangle's geometry `g` = TRIANGLE(tri) from a caller that has it
// (lavapipe loads a texel row once per call, whatever an earlier load read).
SHARED_FN vec3 emittedRadianceOf(uint tri, TriangleGeom g, float u, float v, vec3 towardsViewer) {
  TriangleShading s = TRIANGLE_SHADING(tri);
  MaterialGpu m = MATERIAL(s.material);
  bool front = dot(cross(g.e1, g.e2), towardsViewer) > 0.0f;
  if (!front && (m.flags & kMaterialDoubleSided) == 0u) return vec3(0.0f);
  vec3 le = m.emission;
  if (HAS_TEXTURES && m.emissiveTexture >= 0) {
    vec4 t = sampleTexture(m.emissiveTexture, slotUv(tri, s, m.flags, kMaterialSecondUvEmissive, u, v), true);
    le = le * vec3(t.x, t.y, t.z);
  }
  return le;
}

// Solid-angle pdf with which sampleLightPoint() produces the point `lightPoint` on emitting
// triangle `tri` as seen from `from`, given its light was chosen: triangle pmf / area, converted
// by d^2 / |cos|. 0 for a triangle that does not emit.
SHARED_FN float areaLightPointPdf(uint tri, vec3 from, vec3 lightPoint) {
  int e = TRIANGLE_SHADING(tri).emitter;
  if (e < 0) return 0.0f;
  return emitterPmf(uint(e)) * triangleSolidAnglePdf(TRIANGLE(tri), lightPoint - from);
}

// The method's selection at a point with a normal: the light BVH's (method pt-bvh, where the
// includer defines LIGHT_BVH(i) and LIGHT_SELECT_BVH is true) or the table's, which ignores the
// point. pmf is the light's probability; 0 where no light can be chosen (the BVH: none reaches).
SHARED_FN uint selectLightAt(vec3 p, vec3 n, float u, uint lightCount, OUT(float) pmf) {
#ifdef LIGHT_BVH
  if (LIGHT_SELECT_BVH) {
    uint light = selectLightBvh(p, n, u, pmf);
    return pmf > 0.0f ? light : 0u;
  }
#endif
  uint light = selectLight(u, lightCount);
  pmf = lightSelectPmf(light);
  return light;
}

SHARED_FN float lightSelectPmfAt(vec3 p, vec3 n, uint light) {
#ifdef LIGHT_BVH
  if (LIGHT_SELECT_BVH) return lightBvhPmf(p, n, light);
#endif
  return lightSelectPmf(light);
}

// The light an emitting triangle belongs to (only for triangles with an emitter).
SHARED_FN uint lightOfTriangle(uint tri) { return EMITTER(uint(TRIANGLE_SHADING(tri).emitter)).light; }

// Solid-angle pdf with which sampleLight() produces `lightPoint` on `tri`: selection included.
SHARED_FN float areaLightPdf(uint tri, vec3 from, vec3 lightPoint) {
  float pointPdf = areaLightPointPdf(tri, from, lightPoint);
  return pointPdf > 0.0f ? lightSelectPmf(lightOfTriangle(tri)) * pointPdf : 0.0f;
}

// areaLightPdfAt for triangle tri's emitter e (TriangleShading.emitter, SurfaceHit.emitter), from a
// caller that has it: the emitter is read once.
SHARED_FN float emitterLightPdfAt(uint e, uint tri, vec3 from, vec3 fromNormal, vec3 lightPoint) {
  EmitterGpu em = EMITTER(e);
  float pointPdf = emitterPmfInLight(em, LIGHT(em.light).emitterCount, EMITTERS_UNIFORM) *
                   triangleSolidAnglePdf(TRIANGLE(tri), lightPoint - from);
  return pointPdf > 0.0f ? lightSelectPmfAt(from, fromNormal, em.light) * pointPdf : 0.0f;
}

// areaLightPdf for a selection that depends on the point: `from` and `fromNormal` are the point and
// normal the light sample's selection used (sampleLightAt's selectFrom, selectNormal).
SHARED_FN float areaLightPdfAt(uint tri, vec3 from, vec3 fromNormal, vec3 lightPoint) {
  int e = TRIANGLE_SHADING(tri).emitter;
  return e < 0 ? 0.0f : emitterLightPdfAt(uint(e), tri, from, fromNormal, lightPoint);
}

// The solid-angle pdf with which sampleLightAt (selection at from, fromNormal) produces the
// environment direction dir: for the MIS weight of a BSDF sample that escaped. 0 without an
// environment.
SHARED_FN float environmentLightPdfAt(vec3 from, vec3 fromNormal, vec3 dir) {
  if (!HAS_ENVIRONMENT || !hasEnvironmentLight()) return 0.0f;
  float pdf = environmentPdf(dir);
  return pdf > 0.0f ? lightSelectPmfAt(from, fromNormal, environmentLight()) * pdf : 0.0f;
}

// glTF's recommended spot falloff: smooth between the outer and inner cone, squared.
SHARED_FN float spotFalloff(LightGpu l, vec3 lightToPoint) {
  float c = dot(l.direction, lightToPoint);
  float a = clamp(c * l.spotScale + l.spotOffset, 0.0f, 1.0f);
  return a * a;
}

// A point on light `light` for the shading point p; s.pdf is the pdf given the light was chosen
// (solid angle for area lights, 1 for delta lights). Returns false when the sample carries
// nothing (back face of a one-sided emitter, outside a spot cone, degenerate); it still counts
// as drawn.
SHARED_FN bool sampleLightPoint(vec3 p, uint light, float uEmitter, vec2 uPoint, OUT(LightSample) s) {
  s.light = light;
  LightGpu l = LIGHT(light);
  s.triangle = kNoHit;
  s.isDelta = l.kind != kLightArea && l.kind != kLightEnvironment;
  s.normal = vec3(0.0f);
  s.positionError = vec3(0.0f);
  s.radiance = vec3(0.0f);
  s.pdf = 0.0f;
  s.distance = 0.0f;
  s.direction = vec3(0.0f, 0.0f, 1.0f);
  s.position = p;
  if (HAS_AREA_LIGHTS && l.kind == kLightArea) {
    uint e = selectEmitter(l, uEmitter);
    EmitterGpu em = EMITTER(e);
    TriangleGeom g = TRIANGLE(em.triangle);
    vec3 bary = sampleTriangleBarycentrics(uPoint);   // weights of v0, v1, v2
    s.position = g.v0 + bary.y * g.e1 + bary.z * g.e2;
    s.positionError = trianglePointError(g, bary.y, bary.z);
    s.triangle = em.triangle;
    vec3 d = s.position - p;
    s.distance = scaledLength(d);
    if (!(s.distance > 0.0f)) return false;
    s.direction = d / s.distance;
    // Each load and the edge cross once: the same values as triangleGeometricNormal(g),
    // triangleSolidAnglePdf(g, d), emitterPmf(e) and emittedRadianceOf(em.triangle, g, ...).
    float len1, len2;
    vec3 c = unitEdgeCross(g, len1, len2);
    s.normal = normalOfUnitEdgeCross(c);
    float pointPdf = solidAnglePdfOfUnitEdgeCross(c, len1, len2, d, s.distance);
    if (!(pointPdf > 0.0f)) return false;
    s.pdf = emitterPmfInLight(em, l.emitterCount, EMITTERS_UNIFORM) * pointPdf;
    s.radiance = emittedRadianceOf(em.triangle, g, bary.y, bary.z, -d);
    return !isBlack(s.radiance);
  }
  if (HAS_ENVIRONMENT && l.kind == kLightEnvironment) {
    s.direction = sampleEnvironment(uPoint, s.pdf, s.radiance);
    s.distance = kFloatMax;
    s.normal = -s.direction;
    return s.pdf > 0.0f && !isBlack(s.radiance);
  }
  if (HAS_PUNCTUAL_LIGHTS) {
    s.pdf = 1.0f;
    if (l.kind == kLightDirectional) {
      s.direction = -l.direction;
      s.distance = kFloatMax;
      s.radiance = l.intensity;
      return true;
    }
    vec3 d = l.position - p;
    float dist2 = dot(d, d);
    if (!(dist2 > 0.0f)) return false;
    s.position = l.position;
    s.distance = sqrt(dist2);
    s.direction = d / s.distance;
    s.radiance = l.intensity / dist2;
    if (l.kind == kLightSpot) s.radiance = s.radiance * spotFalloff(l, -s.direction);
    return !isBlack(s.radiance);
  }
  return false;
}

// One light sample for the shading point p, the light chosen by the method's selection
// distribution; s.pdf includes the selection probability.
SHARED_FN bool sampleLight(vec3 p, uint lightCount, float uLight, float uEmitter, vec2 uPoint,
                           OUT(LightSample) s) {
  uint light = selectLight(uLight, lightCount);
  bool carries = sampleLightPoint(p, light, uEmitter, uPoint, s);
  s.pdf *= lightSelectPmf(light);
  return carries;
}

// sampleLight with the light chosen at (selectFrom, selectNormal), the point and normal at which
// the MIS weight of a BSDF sample from the same vertex later evaluates lightSelectPmfAt. Returns
// false with pdf 0 where no light can be chosen.
SHARED_FN bool sampleLightAt(vec3 p, vec3 selectFrom, vec3 selectNormal, uint lightCount, float uLight, float uEmitter,
                             vec2 uPoint, OUT(LightSample) s) {
  float pmf;
  uint light = selectLightAt(selectFrom, selectNormal, uLight, lightCount, pmf);
  bool carries = sampleLightPoint(p, light, uEmitter, uPoint, s);
  s.pdf *= pmf;
  return carries && pmf > 0.0f;
}

// Shadow rays stop this fraction of their length short of the light point (pbrt-v4's
// ShadowEpsilon): the light's own triangle lies just beyond the offset target, and the
// intersector's t for it errs by a few ulps of the ray's length over the cosine at the light,
// which the target's offset (a few ulps of the light point's coordinates, ray_offset.h) does not
// cover when the light is much nearer the world origin than the shading point. Relative to the
// ray's length, so scale invariant; an occluder closer to the light than 1e-4 of the distance is
// missed.
const float kShadowRayShortening = 1e-4f;

// The shadow ray from `origin` (already offset off its surface) to the light sample. It aims at
// the light point offset towards the origin, and its direction is taken from the two offset
// points themselves: aimed along the un-offset direction instead, a ray that leaves at a
// grazing angle drifts sideways by the origin's offset and reaches the light's own surface
// before tMax, which would count the light as occluding itself. Unbounded for directional lights.
SHARED_FN void shadowRay(vec3 origin, LightSample s, OUT(vec3) direction, OUT(float) tMax) {
  if (s.distance >= kFloatMax) {
    direction = s.direction;
    tMax = kFloatMax;
    return;
  }
  vec3 target = s.isDelta ? s.position
                          : offsetRayOrigin(s.position, s.positionError,
                                            dot(s.normal, s.direction) < 0.0f ? s.normal : -s.normal);
  vec3 toTarget = target - origin;
  float toTargetLength = scaledLength(toTarget);
  direction = toTargetLength > 0.0f ? toTarget / toTargetLength : s.direction;
  tMax = toTargetLength * (1.0f - kShadowRayShortening);
}

SHARED_END_WITH_BUFFERS
#endif
