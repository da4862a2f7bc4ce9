// The glTF 2.0 core metallic-roughness BRDF (glTF 2.0 specification, Appendix B) with
// KHR_materials_ior and KHR_materials_transmission, and the sampling that goes with it. Shared by
// the shaders and the CPU reference so both render the same material.
//
//   specular_brdf   = V * D                       (GGX, height-correlated Smith visibility)
//   metal_brdf      = specular_brdf * (baseColor + (1 - baseColor) (1 - |V.H|)^5)
//   dielectric_brdf = mix(baseColor / pi, specular_brdf, F0 + (1 - F0) (1 - |V.H|)^5)
//   glass           = the rough dielectric of dielectric.h (reflection and transmission)
//   f               = mix(mix(dielectric_brdf, glass, transmission), metal_brdf, metallic)
//
// F0 = ((ior - 1) / (ior + 1))^2 (0.04 at glTF's default ior 1.5). Conventions: directions in the
// local shading frame (normal = +z), unit length, both pointing away from the surface, wo.z > 0.
// Without transmission f and the pdf are 0 unless wi.z > 0; with it, wi.z < 0 is transmission.
#ifndef MIXTRACE_SHARED_BSDF_H
#define MIXTRACE_SHARED_BSDF_H
#include "shared/dialect.h"
#include "shared/constants.h"
#include "shared/dielectric.h"
#include "shared/sampling.h"
SHARED_BEGIN

struct BsdfParams {
  vec3 baseColor;
  float metallic;
  float alpha;         // GGX alpha = roughness^2, at least kMinAlpha
  float f0;            // the dielectric's reflectance at normal incidence, from the IOR
  float transmission;  // KHR_materials_transmission's factor (0: opaque; every glass branch tests > 0)
  float eta;           // IOR of the far side over the wo side's (the glass lobe; 1/ior seen from inside)
  bool thin;           // thin-walled glass: transmission without bending (dielectric.h)
};

SHARED_FN BsdfParams makeBsdfParams(vec3 baseColor, float metallic, float roughness) {
  float r = clamp(roughness, 0.0f, 1.0f);
  BsdfParams m;
  m.baseColor = clamp(baseColor, vec3(0.0f), vec3(1.0f));
  m.metallic = clamp(metallic, 0.0f, 1.0f);
  m.alpha = max(r * r, kMinAlpha);
  m.f0 = 0.04f;
  m.transmission = 0.0f;
  m.eta = kDefaultIor;
  m.thin = true;
  return m;
}

// The same material with KHR_materials_ior's refractive index `ior` (which sets F0) and
// KHR_materials_transmission: `transmission` of its dielectric part is glass, volumetric or
// thin-walled; `fromInside` when wo lies inside the volume (the ray hit the surface's back face).
SHARED_FN BsdfParams withTransmission(BsdfParams m, float transmission, float ior, bool thin, bool fromInside) {
  float r = (ior - 1.0f) / (ior + 1.0f);
  m.f0 = r * r;
  m.transmission = clamp(transmission, 0.0f, 1.0f);
  m.thin = thin;
  m.eta = (!thin && fromInside) ? 1.0f / ior : ior;
  return m;
}

// (1 - cos)^5, the Schlick Fresnel weight.
SHARED_FN float schlickWeight(float cosTheta) {
  float c = clamp(1.0f - cosTheta, 0.0f, 1.0f);
  float c2 = c * c;
  return c2 * c2 * c;
}

// Height-correlated Smith visibility V = G2 / (4 N.L N.V) for GGX (Heitz 2014), as glTF writes
// it. The floor on the denominator only matters when both cosines are ~1e-19 or below, where
// the product would underflow to 0 and V become Inf.
SHARED_FN float ggxVisibility(float cosO, float cosI, float alpha) {
  float denom = cosI * ggxSmithRoot(cosO, alpha) + cosO * ggxSmithRoot(cosI, alpha);
  return 0.5f / max(denom, 1e-30f);
}

SHARED_FN vec3 bsdfEval(BsdfParams m, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z == 0.0f) return vec3(0.0f);
  if (wi.z < 0.0f) {   // transmission: the glass alone
    if (!(m.transmission > 0.0f)) return vec3(0.0f);
    float visibility = ggxVisibility(wo.z, -wi.z, m.alpha);
    float t = dielectricTransmission(wo, wi, m.eta, m.thin, m.alpha, visibility);
    return m.baseColor * (t * m.transmission * (1.0f - m.metallic));
  }
  vec3 h = normalize(wo + wi);
  float visibility = ggxVisibility(wo.z, wi.z, m.alpha);
  float specular = ggxD(h, m.alpha) * visibility;
  // |V.H| == |L.H| for the half vector, which is what makes f reciprocal.
  float fw = schlickWeight(abs(dot(wo, h)));
  vec3 metal = (m.baseColor + (vec3(1.0f) - m.baseColor) * fw) * specular;
  float fresnelSchlick = m.f0 + (1.0f - m.f0) * fw;
  vec3 dielectric = mix(m.baseColor * kInvPi, vec3(specular), fresnelSchlick);
  if (m.transmission > 0.0f)
    dielectric = mix(dielectric, vec3(dielectricReflection(wo, wi, m.eta, m.alpha, visibility)), m.transmission);
  return mix(dielectric, metal, m.metallic);
}

// Probability of drawing from the GGX lobe rather than the cosine lobe. It depends only on
// (m, wo), so the mixture pdf in bsdfPdf is exact. The weights are rough albedo estimates of the
// two terms of f, taking the Fresnel factor at the normal-incidence half vector (V.H = wo.z):
// specular ~ luminance of the Fresnel reflectance, diffuse ~ (1 - metallic) lum(baseColor) (1 - F).
// Both lobes keep at least 10% whenever the diffuse term exists, so neither part of f is left
// to a near-zero pdf by a poor estimate.
SHARED_FN float bsdfSpecularProbability(BsdfParams m, vec3 wo) {
  float fw = schlickWeight(wo.z);
  float fresnelSchlick = m.f0 + (1.0f - m.f0) * fw;
  vec3 fresnelMetal = m.baseColor + (vec3(1.0f) - m.baseColor) * fw;
  float opaqueDielectric = (1.0f - m.metallic) * (1.0f - m.transmission);
  float specular = m.metallic * luminance(fresnelMetal) + opaqueDielectric * fresnelSchlick;
  float diffuse = opaqueDielectric * luminance(m.baseColor) * (1.0f - fresnelSchlick);
  if (diffuse <= 0.0f) return 1.0f;  // metallic == 1 or black base colour: f is all specular
  // diffuse > 0 here, so the ratio is well defined.
  return clamp(specular / (specular + diffuse), 0.1f, 0.9f);
}

// Whether wi may lie below the surface (wi.z < 0): the material has a glass part.
SHARED_FN bool bsdfTransmits(BsdfParams m) { return m.transmission > 0.0f; }

// Probability of drawing from the glass lobe (dielectric.h): its share of f, (1 - metallic)
// transmission. Depends only on m, so the mixture pdf stays exact.
SHARED_FN float bsdfGlassProbability(BsdfParams m) { return (1.0f - m.metallic) * m.transmission; }

SHARED_FN float bsdfPdf(BsdfParams m, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z == 0.0f) return 0.0f;
  float pGlass = 0.0f;
  float glass = 0.0f;
  if (m.transmission > 0.0f) {
    pGlass = bsdfGlassProbability(m);
    glass = pGlass * dielectricPdf(wo, wi, m.eta, m.thin, m.alpha);
  }
  if (wi.z < 0.0f) return glass;
  float pSpecular = bsdfSpecularProbability(m, wo);
  return glass + (1.0f - pGlass) * (pSpecular * ggxReflectionPdf(wo, wi, m.alpha)
                                    + (1.0f - pSpecular) * cosineHemispherePdf(wi.z));
}

// Draws wi from the mixture of the glass lobe, GGX visible-normal sampling (reflected about the
// sampled normal) and cosine sampling; uLobe picks the lobe (and, rescaled, the glass lobe's
// reflection or transmission). A direction on the wrong side of the surface is a failed sample:
// returns false with pdf 0 (it still counts as a sample for the estimator).
SHARED_FN bool bsdfSample(BsdfParams m, vec3 wo, vec2 u, float uLobe, OUT(vec3) wi, OUT(float) pdf) {
  wi = vec3(0.0f, 0.0f, 1.0f);
  pdf = 0.0f;
  if (wo.z <= 0.0f) return false;
  if (m.transmission > 0.0f) {
    float pGlass = bsdfGlassProbability(m);
    if (uLobe < pGlass) {
      if (!dielectricSample(wo, m.eta, m.thin, m.alpha, u, uLobe / pGlass, wi)) return false;
      pdf = bsdfPdf(m, wo, wi);
      return pdf > 0.0f;
    }
    uLobe = min((uLobe - pGlass) / (1.0f - pGlass), 0.99999994f);
  }
  if (uLobe < bsdfSpecularProbability(m, wo)) {
    wi = reflectAbout(wo, sampleGgxVisibleNormal(wo, m.alpha, u));
  } else {
    wi = sampleCosineHemisphere(u);
  }
  if (wi.z <= 0.0f) return false;
  pdf = bsdfPdf(m, wo, wi);
  return pdf > 0.0f;
}

SHARED_END
#endif
