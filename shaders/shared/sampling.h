// Sampling building blocks shared by the shaders and the CPU reference: a shading frame,
// direction and point sampling routines with their pdfs, and the GGX microfacet terms the BSDF
// and its sampling need. All directions are unit vectors; "local" means the frame whose +z is the
// shading normal.
//
// Float literals carry an f suffix on purpose: in C++ an unsuffixed literal is a double, which
// both changes the arithmetic (GLSL would stay in float) and breaks GLM's template deduction.
#ifndef MIXTRACE_SHARED_SAMPLING_H
#define MIXTRACE_SHARED_SAMPLING_H
#include "shared/dialect.h"
#include "shared/constants.h"
SHARED_BEGIN

// ---------------------------------------------------------------------------------------------
// Orthonormal basis around a unit normal (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited"): branch-free apart from the sign, continuous except across n.z = 0, and exact
// for n = -z where the earlier Frisvad construction breaks down. Right-handed:
// cross(tangent, bitangent) == normal.
struct OrthonormalBasis {
  vec3 tangent;
  vec3 bitangent;
  vec3 normal;
};

SHARED_FN OrthonormalBasis makeOrthonormalBasis(vec3 n) {
  // Not sign(n.z): GLSL's sign(0) is 0, and the construction needs +-1.
  float s = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (s + n.z);
  float b = n.x * n.y * a;
  OrthonormalBasis basis;
  basis.tangent = vec3(1.0f + s * n.x * n.x * a, s * b, -s * n.x);
  basis.bitangent = vec3(b, s + n.y * n.y * a, -n.y);
  basis.normal = n;
  return basis;
}

SHARED_FN vec3 toLocal(OrthonormalBasis basis, vec3 v) {
  return vec3(dot(v, basis.tangent), dot(v, basis.bitangent), dot(v, basis.normal));
}

SHARED_FN vec3 toWorld(OrthonormalBasis basis, vec3 v) {
  return basis.tangent * v.x + basis.bitangent * v.y + basis.normal * v.z;
}

// ---------------------------------------------------------------------------------------------
// Colour helpers.

// Relative luminance of a linear Rec. 709 / sRGB colour.
// True when no channel is positive (also for NaN): nothing to add or to carry on.
SHARED_FN bool isBlack(vec3 c) { return !(c.x > 0.0f || c.y > 0.0f || c.z > 0.0f); }

SHARED_FN float luminance(vec3 c) {
  return dot(c, vec3(0.2126f, 0.7152f, 0.0722f));
}

// One sRGB-encoded channel in [0, 1] to linear (IEC 61966-2-1 piecewise curve). The power segment
// ((c + 0.055) / 1.055)^2.4 is a rational fit of degree 4/4, within 6e-7 of it (relative) at every
// 8-bit value and 1.4e-6 between them, as close as pow() in float (4e-7): a colour texture
// decodes 12 channels per bilinear lookup, and on lavapipe the pows were a fifth of a textured
// scene's shade pass (benchmarks/README.md, "What a pass costs on lavapipe").
SHARED_FN float srgbToLinear(float c) {
  float p = (((4.023686408996582f * c + 3.3877310752868652f) * c + 0.6408167481422424f) * c +
             0.040300384163856506f) * c + 0.0008346024551428854f;
  float q = (((0.04794520139694214f * c - 0.34395426511764526f) * c + 2.6193156242370605f) * c +
             4.770065784454346f) * c + 1.0f;
  return c <= 0.04045f ? c * (1.0f / 12.92f) : p / q;
}

// ---------------------------------------------------------------------------------------------
// Uniform and cosine-weighted directions. u: two uniforms in [0, 1).

// Shirley & Chiu's concentric map of the square onto the unit disk: area-preserving and with low
// distortion, so stratified uniforms stay well stratified on the disk.
SHARED_FN vec2 sampleConcentricDisk(vec2 u) {
  float ox = 2.0f * u.x - 1.0f;
  float oy = 2.0f * u.y - 1.0f;
  if (ox == 0.0f && oy == 0.0f) return vec2(0.0f, 0.0f);
  float r;
  float phi;
  if (abs(ox) > abs(oy)) {
    r = ox;
    phi = (0.25f * kPi) * (oy / ox);
  } else {
    r = oy;
    phi = 0.5f * kPi - (0.25f * kPi) * (ox / oy);
  }
  return vec2(r * cos(phi), r * sin(phi));
}

// Cosine-weighted direction on the +z hemisphere (Malley's method: lift the disk sample).
SHARED_FN vec3 sampleCosineHemisphere(vec2 u) {
  vec2 d = sampleConcentricDisk(u);
  float z = sqrt(max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return vec3(d.x, d.y, z);
}

// Solid-angle pdf of sampleCosineHemisphere for a direction with local z = cosTheta.
SHARED_FN float cosineHemispherePdf(float cosTheta) {
  return max(cosTheta, 0.0f) * kInvPi;
}

// Uniform direction on the unit sphere (Archimedes: z is uniform in [-1, 1]).
SHARED_FN vec3 sampleUniformSphere(vec2 u) {
  float z = 1.0f - 2.0f * u.x;
  float r = sqrt(max(0.0f, 1.0f - z * z));
  float phi = kTwoPi * u.y;
  return vec3(r * cos(phi), r * sin(phi), z);
}

SHARED_FN float uniformSpherePdf() {
  return 0.25f * kInvPi;
}

// ---------------------------------------------------------------------------------------------
// Uniform point on a triangle. The square-root parameterisation: b0 = 1 - sqrt(u.x) has the
// density 2 (1 - b0) of a uniform triangle's first barycentric, and b1 splits the remaining
// segment uniformly. Returns (b0, b1, b2), the weights of (v0, v1, v2).
SHARED_FN vec3 sampleTriangleBarycentrics(vec2 u) {
  float su = sqrt(u.x);
  float b0 = 1.0f - su;
  float b1 = u.y * su;
  return vec3(b0, b1, max(0.0f, 1.0f - b0 - b1));
}

SHARED_FN vec3 sampleTrianglePoint(vec3 v0, vec3 v1, vec3 v2, vec2 u) {
  vec3 b = sampleTriangleBarycentrics(u);
  return v0 * b.x + v1 * b.y + v2 * b.z;
}

// ---------------------------------------------------------------------------------------------
// Isotropic GGX (Trowbridge-Reitz) microfacet distribution, local frame, alpha > 0.

// D(h). Written with sin^2 = h.x^2 + h.y^2 instead of 1 - cos^2: near the normal the latter
// cancels catastrophically, and with alpha^2 ~ 4e-6 that error would dominate the peak.
SHARED_FN float ggxD(vec3 h, float alpha) {
  if (h.z <= 0.0f) return 0.0f;
  float a2 = alpha * alpha;
  float t = (h.x * h.x + h.y * h.y) + a2 * (h.z * h.z);
  return a2 / (kPi * t * t);
}

// sqrt(cos^2 (1 - a^2) + a^2) = cos * sqrt(1 + a^2 tan^2): the square root shared by the Smith
// Lambda of GGX and the height-correlated visibility, in a form that stays finite at cos -> 0.
SHARED_FN float ggxSmithRoot(float cosTheta, float alpha) {
  float a2 = alpha * alpha;
  return sqrt(max(cosTheta * cosTheta * (1.0f - a2) + a2, 0.0f));
}

// Smith masking G1(w) for GGX: 2 cos / (cos + sqrt(cos^2 (1 - a^2) + a^2)).
SHARED_FN float ggxG1(vec3 w, float alpha) {
  if (w.z <= 0.0f) return 0.0f;
  return 2.0f * w.z / (w.z + ggxSmithRoot(w.z, alpha));
}

// Visible normal h for the view direction wo (wo.z > 0), distributed with the pdf
// ggxVisibleNormalPdf (Heitz 2018, "Sampling the GGX Distribution of Visible Normals"): stretch
// the view to the alpha = 1 configuration, sample the projected hemisphere there, unstretch.
SHARED_FN vec3 sampleGgxVisibleNormal(vec3 wo, float alpha, vec2 u) {
  vec3 vh = normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
  float lenSq = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = lenSq > 0.0f ? vec3(-vh.y, vh.x, 0.0f) * inversesqrt(lenSq) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = cross(vh, t1);
  // Uniform disk point, then warp its second coordinate onto the part of the disk that the
  // hemisphere of visible normals projects to.
  float r = sqrt(u.x);
  float phi = kTwoPi * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * sqrt(max(0.0f, 1.0f - p1 * p1)) + s * p2;
  vec3 nh = t1 * p1 + t2 * p2 + vh * sqrt(max(0.0f, 1.0f - p1 * p1 - p2 * p2));
  return normalize(vec3(alpha * nh.x, alpha * nh.y, max(0.0f, nh.z)));
}

// Pdf of sampleGgxVisibleNormal: D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z, with G1 / wo.z
// written out so that grazing wo is no 0/0.
SHARED_FN float ggxVisibleNormalPdf(vec3 wo, vec3 h, float alpha) {
  if (wo.z <= 0.0f) return 0.0f;
  return 2.0f * max(dot(wo, h), 0.0f) * ggxD(h, alpha) / (wo.z + ggxSmithRoot(wo.z, alpha));
}

// Solid-angle pdf of wi = reflect(-wo, h) for h drawn by sampleGgxVisibleNormal:
// D_wo(h) / (4 wo.h) = G1(wo) D(h) / (4 wo.z) = D(h) / (2 (wo.z + sqrt(...))), the last form
// free of the 0/0 at grazing wo. Counts only wi on the upper hemisphere (the others are failed
// samples), so it integrates to 1 minus the failure probability.
SHARED_FN float ggxReflectionPdf(vec3 wo, vec3 wi, float alpha) {
  if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
  vec3 h = normalize(wo + wi);
  return ggxD(h, alpha) / (2.0f * (wo.z + ggxSmithRoot(wo.z, alpha)));
}

// Mirror wo about h (both pointing away from the surface).
SHARED_FN vec3 reflectAbout(vec3 wo, vec3 h) {
  return h * (2.0f * dot(wo, h)) - wo;
}

SHARED_END
#endif
