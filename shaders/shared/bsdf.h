// The glTF 2.0 core metallic-roughness BRDF (glTF 2.0 specification, Appendix B) and the
// sampling that goes with it. Shared by the shaders and the CPU reference so both render the
// same material.
//
//   specular_brdf   = V * D                       (GGX, height-correlated Smith visibility)
//   metal_brdf      = specular_brdf * (baseColor + (1 - baseColor) (1 - |V.H|)^5)
//   dielectric_brdf = mix(baseColor / pi, specular_brdf, 0.04 + 0.96 (1 - |V.H|)^5)
//   f               = mix(dielectric_brdf, metal_brdf, metallic)
//
// Conventions: directions in the local shading frame (normal = +z), unit length, both pointing
// away from the surface. Reflection only: f and the pdf are 0 unless wo.z > 0 and wi.z > 0.
#ifndef MIXTRACE_SHARED_BSDF_H
#define MIXTRACE_SHARED_BSDF_H
#include "shared/dialect.h"
#include "shared/constants.h"
#include "shared/sampling.h"
SHARED_BEGIN

struct BsdfParams {
  vec3 baseColor;
  float metallic;
  float alpha;         // GGX alpha = roughness^2, at least kMinAlpha
};

SHARED_FN BsdfParams makeBsdfParams(vec3 baseColor, float metallic, float roughness) {
  float r = clamp(roughness, 0.0f, 1.0f);
  BsdfParams m;
  m.baseColor = clamp(baseColor, vec3(0.0f), vec3(1.0f));
  m.metallic = clamp(metallic, 0.0f, 1.0f);
  m.alpha = max(r * r, kMinAlpha);
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
  if (wo.z <= 0.0f || wi.z <= 0.0f) return vec3(0.0f);
  vec3 h = normalize(wo + wi);
  float specular = ggxD(h, m.alpha) * ggxVisibility(wo.z, wi.z, m.alpha);
  // |V.H| == |L.H| for the half vector, which is what makes f reciprocal.
  float fw = schlickWeight(abs(dot(wo, h)));
  vec3 metal = (m.baseColor + (vec3(1.0f) - m.baseColor) * fw) * specular;
  float fresnelDielectric = 0.04f + 0.96f * fw;
  vec3 dielectric = mix(m.baseColor * kInvPi, vec3(specular), fresnelDielectric);
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
  float fresnelDielectric = 0.04f + 0.96f * fw;
  vec3 fresnelMetal = m.baseColor + (vec3(1.0f) - m.baseColor) * fw;
  float specular = m.metallic * luminance(fresnelMetal) + (1.0f - m.metallic) * fresnelDielectric;
  float diffuse = (1.0f - m.metallic) * luminance(m.baseColor) * (1.0f - fresnelDielectric);
  if (diffuse <= 0.0f) return 1.0f;  // metallic == 1 or black base colour: f is all specular
  // specular >= 0.04 (1 - metallic) > 0 here, so the ratio is well defined.
  return clamp(specular / (specular + diffuse), 0.1f, 0.9f);
}

SHARED_FN float bsdfPdf(BsdfParams m, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  float pSpecular = bsdfSpecularProbability(m, wo);
  return pSpecular * ggxReflectionPdf(wo, wi, m.alpha)
       + (1.0f - pSpecular) * cosineHemispherePdf(wi.z);
}

// Draws wi from the mixture of GGX visible-normal sampling (reflected about the sampled normal)
// and cosine sampling; uLobe picks the lobe. A reflection below the horizon is a failed sample:
// returns false with pdf 0 (it still counts as a sample for the estimator).
SHARED_FN bool bsdfSample(BsdfParams m, vec3 wo, vec2 u, float uLobe, OUT(vec3) wi, OUT(float) pdf) {
  wi = vec3(0.0f, 0.0f, 1.0f);
  pdf = 0.0f;
  if (wo.z <= 0.0f) return false;
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
