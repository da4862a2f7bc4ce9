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

SHARED_FN BsdfParams surfaceBsdf(SurfaceHit h) {
  MaterialGpu m = MATERIAL(h.material);
  vec3 baseColor = m.baseColor * vec3(h.vertexColor.x, h.vertexColor.y, h.vertexColor.z);
  float metallic = HAS_METALS ? m.metallic : 0.0f;
  float roughness = m.roughness;
  if (HAS_TEXTURES) {
    if (m.baseColorTexture >= 0) {
      vec4 t = sampleTexture(m.baseColorTexture, surfaceUv(h, m.flags, kMaterialSecondUvBaseColor), true);
      baseColor = baseColor * vec3(t.x, t.y, t.z);
    }
    if (m.metallicRoughnessTexture >= 0) {
      vec4 t = sampleTexture(m.metallicRoughnessTexture, surfaceUv(h, m.flags, kMaterialSecondUvMetallicRoughness), false);
      roughness = roughness * t.y;
      metallic = HAS_METALS ? metallic * t.z : 0.0f;
    }
  }
  BsdfParams p = makeBsdfParams(baseColor, metallic, roughness);
  if (HAS_TRANSMISSION && (m.transmission > 0.0f || m.ior != kDefaultIor)) {
    float transmission = m.transmission;
    if (HAS_TEXTURES && m.transmissionTexture >= 0)
      transmission = transmission * sampleTexture(m.transmissionTexture, surfaceUv(h, m.flags, kMaterialSecondUvTransmission), false).x;
    p = withTransmission(p, transmission, m.ior, (m.flags & kMaterialVolumetric) == 0u, h.fromInside);
  }
  return p;
}

SHARED_END_WITH_BUFFERS
#endif
