// What the integrators need at a ray hit: the point, its normals (both turned to the side the
// ray came from: the BSDF is two-sided, emission is not), texture coordinates and the BSDF
// parameters with textures applied. Needs the accessors of lights.h.
#ifndef MIXTRACE_SHARED_SURFACE_H
#define MIXTRACE_SHARED_SURFACE_H
#include "shared/bsdf.h"
#include "shared/dialect.h"
#include "shared/layouts.h"
#include "shared/lights.h"
#include "shared/ray_offset.h"
#include "shared/tangent_frame.h"
#include "shared/texture.h"
#include "shared/triangle_attributes.h"
SHARED_BEGIN_WITH_BUFFERS

struct SurfaceHit {
  vec3 position;
  vec3 positionError;    // rounding-error bound of `position` (ray_offset.h), for scatterOrigins
  vec3 geometricNormal;  // unit, on the side of the incoming ray
  vec3 shadingNormal;    // unit, same side as geometricNormal
  vec2 uv;              // the material's first texture coordinates
  vec2 uv2;             // its second (= uv unless its textures read two mappings)
  uint material;
  int emitter;           // the triangle's emitter (TriangleShading.emitter): -1 where it emits nothing
  vec4 vertexColor;      // COLOR_0 (white without it): multiplies the base colour and its alpha
  bool fromInside;       // the ray hit the back face (for volumetric glass: it leaves the volume)
};

// The shading normal n (unit, the file's side) perturbed by the material's normal map: the map's
// texel in the tangent frame (T, w cross(n, T), n) of the interpolated tangent, its x and y
// scaled by normalTexture.scale (glTF: +X right = +u, +Y up = -v, linear RGB 2c - 1). Unchanged
// without a map or without a usable tangent.
SHARED_FN vec3 normalMapped(TriangleShading s, float u, float v, vec2 uv, vec3 n) {
  MaterialGpu m = MATERIAL(s.material);
  if (m.normalTexture < 0) return n;
  vec4 t0 = unpackTangent(s.tangent0);
  vec4 t1 = unpackTangent(s.tangent1);
  vec4 t2 = unpackTangent(s.tangent2);
  vec3 t = (1.0f - u - v) * vec3(t0.x, t0.y, t0.z) + u * vec3(t1.x, t1.y, t1.z) + v * vec3(t2.x, t2.y, t2.z);
  t = t - n * dot(n, t);   // Gram-Schmidt against the interpolated normal
  float tl = length(t);
  if (!(tl > 1e-6f)) return n;
  t = t / tl;
  float w = t0.w;          // one handedness per triangle: its first corner's
  vec3 b = cross(n, t) * w;
  vec4 texel = sampleTexture(m.normalTexture, uv, false);
  vec3 c = vec3(texel.x * 2.0f - 1.0f, texel.y * 2.0f - 1.0f, texel.z * 2.0f - 1.0f);
  vec3 mapped = c.x * m.normalScale * t + c.y * m.normalScale * b + c.z * n;
  float ml = length(mapped);
  return ml > 0.0f ? mapped / ml : n;
}

// The coordinates texture slot `slot` (a kMaterialSecondUv* bit) reads at the hit.
SHARED_FN vec2 surfaceUv(SurfaceHit h, uint flags, uint slot) { return (flags & slot) != 0u ? h.uv2 : h.uv; }

SHARED_FN SurfaceHit makeSurfaceHit(uint tri, float u, float v, vec3 incomingDirection) {
  TriangleGeom g = TRIANGLE(tri);
  TriangleShading s = TRIANGLE_SHADING(tri);
  SurfaceHit h;
  h.position = g.v0 + u * g.e1 + v * g.e2;
  h.positionError = trianglePointError(g, u, v);
  vec3 ng = triangleGeometricNormal(g);   // normalize(cross) underflows for tiny triangles
  bool front = dot(ng, incomingDirection) < 0.0f;
  h.geometricNormal = front ? ng : -ng;
  h.fromInside = !front;
  vec3 ns = (1.0f - u - v) * s.n0 + u * s.n1 + v * s.n2;
  float len = length(ns);
  ns = len > 0.0f ? ns / len : ng;
  h.uv = triangleUv(s, u, v);
  h.uv2 = h.uv;
  uint flags = MATERIAL(s.material).flags;
  if (HAS_SECOND_UVS && (flags & kMaterialSecondUvAny) != 0u) h.uv2 = triangleSecondUv(tri, u, v);
  if (HAS_NORMAL_MAPS && HAS_TEXTURES) ns = normalMapped(s, u, v, surfaceUv(h, flags, kMaterialSecondUvNormal), ns);
  ns = front ? ns : -ns;
  // A shading normal that disagrees with the geometry (bad file normals) is not trusted.
  if (!(dot(ns, h.geometricNormal) > 0.0f)) ns = h.geometricNormal;
  h.shadingNormal = ns;
  h.material = s.material;
  h.emitter = s.emitter;
  h.vertexColor = vec4(1.0f);
  if (HAS_VERTEX_COLORS)
    h.vertexColor = triangleVertexColor(s, u, v);
  return h;
}

// The hit's material and what its textures say there (white where a slot has no texture).
struct SurfaceMaterial {
  MaterialGpu m;
  vec4 baseColor;           // baseColorTexture (sRGB-decoded)
  vec4 metallicRoughness;   // metallicRoughnessTexture: roughness in y, metalness in z
  vec4 emissive;            // emissiveTexture (sRGB-decoded), only where the triangle emits
  vec4 transmission;        // transmissionTexture: its factor in x
};

// The material's texture slots at the hit, looked up in one loop over the slots it uses: a SIMD
// group runs both sides of every branch for all its lanes (lavapipe does even when they agree), so
// one lookup site per slot cost every lane every slot's lookup, where the loop runs as many turns
// as its lanes' materials have textures (one, for most files' materials; benchmarks/README.md,
// "What a pass costs on lavapipe"). Scalar code looks up the same slots in the same order.
SHARED_FN SurfaceMaterial surfaceMaterial(SurfaceHit h) {
  SurfaceMaterial r;
  r.m = MATERIAL(h.material);
  r.baseColor = vec4(1.0f);
  r.metallicRoughness = vec4(1.0f);
  r.emissive = vec4(1.0f);
  r.transmission = vec4(1.0f);
  if (!HAS_TEXTURES) return r;
  // One bit per slot with a texture: 1 base colour, 2 metallic-roughness, 4 emissive, 8 transmission.
  uint pending = (r.m.baseColorTexture >= 0 ? 1u : 0u) | (r.m.metallicRoughnessTexture >= 0 ? 2u : 0u) |
                 (HAS_AREA_LIGHTS && h.emitter >= 0 && r.m.emissiveTexture >= 0 ? 4u : 0u) |
                 (HAS_TRANSMISSION && r.m.transmissionTexture >= 0 ? 8u : 0u);
  // do-while, not while: lavapipe runs a loop's body until the end of the turn in which its last
  // lane leaves, so a test at the top would cost a second, empty turn of lookups.
  if (pending != 0u) do {
    uint slot = (pending & 1u) != 0u ? 1u : (pending & 2u) != 0u ? 2u : (pending & 4u) != 0u ? 4u : 8u;
    pending = pending & ~slot;
    int index = slot == 1u ? r.m.baseColorTexture
              : slot == 2u ? r.m.metallicRoughnessTexture
              : slot == 4u ? r.m.emissiveTexture : r.m.transmissionTexture;
    uint uvSlot = slot == 1u ? kMaterialSecondUvBaseColor
                : slot == 2u ? kMaterialSecondUvMetallicRoughness
                : slot == 4u ? kMaterialSecondUvEmissive : kMaterialSecondUvTransmission;
    vec4 t = sampleTexture(index, surfaceUv(h, r.m.flags, uvSlot), slot == 1u || slot == 4u);
    if (slot == 1u) r.baseColor = t;
    if (slot == 2u) r.metallicRoughness = t;
    if (slot == 4u) r.emissive = t;
    if (slot == 8u) r.transmission = t;
  } while (pending != 0u);
  return r;
}

// The BSDF at the hit, its material's textures applied (a slot's white leaves its factor exact).
SHARED_FN BsdfParams surfaceBsdf(SurfaceHit h, SurfaceMaterial sm) {
  MaterialGpu m = sm.m;
  vec3 baseColor = m.baseColor * vec3(h.vertexColor.x, h.vertexColor.y, h.vertexColor.z) *
                   vec3(sm.baseColor.x, sm.baseColor.y, sm.baseColor.z);
  float roughness = m.roughness * sm.metallicRoughness.y;
  float metallic = HAS_METALS ? m.metallic * sm.metallicRoughness.z : 0.0f;
  BsdfParams p = makeBsdfParams(baseColor, metallic, roughness);
  if (HAS_TRANSMISSION && (m.transmission > 0.0f || m.ior != kDefaultIor)) {
    float transmission = m.transmission * sm.transmission.x;
    p = withTransmission(p, transmission, m.ior, (m.flags & kMaterialVolumetric) == 0u, h.fromInside);
  }
  return p;
}

// Radiance the hit's surface emits back along the ray (what emittedRadianceOf of lights.h gives a light
// sample there, from what the hit already read): one-sided (the front face, where the ray did not come from inside) unless the
// material is double-sided.
SHARED_FN vec3 surfaceEmission(SurfaceHit h, SurfaceMaterial sm) {
  if (h.fromInside && (sm.m.flags & kMaterialDoubleSided) == 0u) return vec3(0.0f);
  return sm.m.emission * vec3(sm.emissive.x, sm.emissive.y, sm.emissive.z);
}

SHARED_END_WITH_BUFFERS
#endif
