// The glass lobe of KHR_materials_transmission: a rough dielectric interface (Walter et al. 2007,
// "Microfacet Models for Refraction through Rough Surfaces") on the GGX distribution of bsdf.h,
// reflecting and transmitting by the exact Fresnel equations (not glTF's Schlick fresnel_mix,
// which has no total internal reflection: light inside a glass would leave at every angle).
//
// Two geometries, as KHR_materials_volume prescribes:
//   volumetric (thickness > 0): the surface bounds a volume; transmitted light bends by Snell's
//     law with eta = n_other / n_wo_side (the caller flips the IOR for a ray from inside), and
//     transmitted radiance scales by 1 / eta^2 (radiance is n^2-invariant, pbrt-v4's
//     TransportMode::Radiance); a furnace still sees 1 through a closed glass (eta^2 / eta^2).
//   thin-walled (no volume): both sides are outside; light passes without bending, as if through
//     a thin sheet: the transmitted direction is the reflected one mirrored through the surface
//     plane, with the reflection's microfacet, so reflection and transmission split each
//     microfacet's light by F and 1 - F (one interface's Fresnel; the sheet's inner bounces are
//     not modelled).
// Transmission is tinted by the base colour (glTF: specular_btdf * baseColor).
//
// Conventions as bsdf.h: local shading frame, normal +z, wo.z > 0 on the side the ray came from;
// a transmitted wi has wi.z < 0. Smooth glass is GGX at the minimum alpha (kMinAlpha), so every
// lobe has a density and MIS and the control variate need no delta case.
#ifndef MIXTRACE_SHARED_DIELECTRIC_H
#define MIXTRACE_SHARED_DIELECTRIC_H
#include "shared/dialect.h"
#include "shared/constants.h"
#include "shared/sampling.h"
SHARED_BEGIN

// Fresnel reflectance of unpolarised light at a dielectric interface, cosI the cosine of the
// angle of incidence on the side eta is relative to (eta = n_transmitted / n_incident); 1 at
// total internal reflection.
SHARED_FN float fresnelDielectric(float cosI, float eta) {
  cosI = clamp(cosI, 0.0f, 1.0f);
  float sin2T = (1.0f - cosI * cosI) / (eta * eta);
  if (sin2T >= 1.0f) return 1.0f;
  float cosT = sqrt(max(1.0f - sin2T, 0.0f));
  float rParallel = (eta * cosI - cosT) / (eta * cosI + cosT);
  float rPerpendicular = (cosI - eta * cosT) / (cosI + eta * cosT);
  return 0.5f * (rParallel * rParallel + rPerpendicular * rPerpendicular);
}

// wo refracted through the microfacet h (dot(wo, h) > 0) into the other medium; false at total
// internal reflection.
SHARED_FN bool refractAbout(vec3 wo, vec3 h, float eta, OUT(vec3) wi) {
  float cosI = dot(wo, h);
  float sin2T = max(0.0f, 1.0f - cosI * cosI) / (eta * eta);
  wi = vec3(0.0f);
  if (sin2T >= 1.0f) return false;
  float cosT = sqrt(1.0f - sin2T);
  wi = -wo / eta + (cosI / eta - cosT) * h;
  return true;
}

// The microfacet normal that refracts wo into wi (wi.z < 0) for a volumetric interface (the
// generalised half vector wo + eta wi, turned to +z), or that reflects wo into wi's mirror image
// for a thin one. False where none does: a microfacet seen from behind by either direction.
SHARED_FN bool transmissionHalfVector(vec3 wo, vec3 wi, float eta, bool thin, OUT(vec3) h) {
  h = vec3(0.0f, 0.0f, 1.0f);
  vec3 s = thin ? wo + vec3(wi.x, wi.y, -wi.z) : wo + eta * wi;
  float len = length(s);
  if (!(len > 0.0f)) return false;
  h = s / len;
  if (h.z < 0.0f) h = -h;
  if (thin) return dot(wo, h) > 0.0f;
  return dot(wo, h) > 0.0f && dot(wi, h) < 0.0f;
}

// The glass lobe's f (without the base colour tint of the transmission, applied by the caller):
// reflection for wi.z > 0, transmission for wi.z < 0. visibility(cosO, cosI) is bsdf.h's
// height-correlated G2 / (4 cosO cosI).
SHARED_FN float dielectricReflection(vec3 wo, vec3 wi, float eta, float alpha, float visibility) {
  vec3 h = normalize(wo + wi);
  return fresnelDielectric(dot(wo, h), eta) * ggxD(h, alpha) * visibility;
}

SHARED_FN float dielectricTransmission(vec3 wo, vec3 wi, float eta, bool thin, float alpha, float visibility) {
  vec3 h;
  if (!transmissionHalfVector(wo, wi, eta, thin, h)) return 0.0f;
  float t = 1.0f - fresnelDielectric(dot(wo, h), eta);
  if (thin) return t * ggxD(h, alpha) * visibility;
  // Walter's BTDF, |wi.h| |wo.h| G2 D (1 - F) / (|cos_i| cos_o (wi.h + wo.h / eta)^2), with
  // G2 = 4 |cos_i| cos_o visibility, and the 1 / eta^2 of radiance.
  float denom = dot(wi, h) + dot(wo, h) / eta;
  float jacobian = abs(dot(wi, h)) * dot(wo, h) / max(denom * denom, 1e-30f);
  return t * ggxD(h, alpha) * 4.0f * visibility * jacobian / (eta * eta);
}

// Solid-angle density of dielectricSample's wi (both its reflections and transmissions).
SHARED_FN float dielectricPdf(vec3 wo, vec3 wi, float eta, bool thin, float alpha) {
  if (wo.z <= 0.0f) return 0.0f;
  if (wi.z > 0.0f) {
    vec3 h = normalize(wo + wi);
    return fresnelDielectric(dot(wo, h), eta) * ggxReflectionPdf(wo, wi, alpha);
  }
  vec3 h;
  if (!(wi.z < 0.0f) || !transmissionHalfVector(wo, wi, eta, thin, h)) return 0.0f;
  float t = 1.0f - fresnelDielectric(dot(wo, h), eta);
  if (thin) return t * ggxReflectionPdf(wo, vec3(wi.x, wi.y, -wi.z), alpha);
  float denom = dot(wi, h) + dot(wo, h) / eta;
  return t * ggxVisibleNormalPdf(wo, h, alpha) * abs(dot(wi, h)) / max(denom * denom, 1e-30f);
}

// A visible microfacet, then reflection with probability F or transmission (refraction, or the
// mirrored reflection when thin) with 1 - F; uChoice picks. False for a direction on the wrong
// side of the surface (a failed sample).
SHARED_FN bool dielectricSample(vec3 wo, float eta, bool thin, float alpha, vec2 u, float uChoice, OUT(vec3) wi) {
  wi = vec3(0.0f, 0.0f, 1.0f);
  if (wo.z <= 0.0f) return false;
  vec3 h = sampleGgxVisibleNormal(wo, alpha, u);
  float f = fresnelDielectric(dot(wo, h), eta);
  vec3 reflected = reflectAbout(wo, h);
  if (uChoice < f) {
    wi = reflected;
    return wi.z > 0.0f;
  }
  if (thin) {
    wi = vec3(reflected.x, reflected.y, -reflected.z);
    return wi.z < 0.0f;
  }
  if (!refractAbout(wo, h, eta, wi)) return false;
  return wi.z < 0.0f;
}

SHARED_END
#endif
