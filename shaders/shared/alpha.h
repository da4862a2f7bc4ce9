// glTF alpha: whether a ray passes through a triangle where it hits it (alphaMode MASK below its
// alphaCutoff; BLEND with probability 1 - alpha: stochastic transparency, unbiased in expectation,
// as pbrt-v4 and Mitsuba 3 treat alpha). Alpha is the base colour factor's alpha times the base
// colour texture's times COLOR_0's; OPAQUE ignores it. Called by the BVH traversal for every
// candidate hit (BVH_ALPHA_PASSES, shared/bvh_traverse.h), so extension and shadow rays agree.
//
// The BLEND decision is a hash of the ray (origin and direction bits) and the triangle: a fresh
// uniform number for each ray, the same one each time that ray meets that triangle (the closest-
// and any-hit walks, and both backends, decide alike).
//
// The includer defines TRIANGLE_SHADING(i), MATERIAL(i), TEXTURE(i), TEXEL(i) and the feature
// switches HAS_ALPHA, HAS_TEXTURES and HAS_VERTEX_COLORS.
#ifndef MIXTRACE_SHARED_ALPHA_H
#define MIXTRACE_SHARED_ALPHA_H
#include "shared/dialect.h"
#include "shared/layouts.h"
#include "shared/rng.h"
#include "shared/texture.h"
#include "shared/triangle_attributes.h"
SHARED_BEGIN_WITH_BUFFERS

// Uniform in [0, 1) from the ray and the triangle.
SHARED_FN float alphaHash(vec3 origin, vec3 direction, uint tri) {
  uint h = pcgHash(tri ^ 0x9e3779b9u);
  h = pcgHash(h ^ floatBitsToUint(origin.x));
  h = pcgHash(h ^ floatBitsToUint(origin.y));
  h = pcgHash(h ^ floatBitsToUint(origin.z));
  h = pcgHash(h ^ floatBitsToUint(direction.x));
  h = pcgHash(h ^ floatBitsToUint(direction.y));
  h = pcgHash(h ^ floatBitsToUint(direction.z));
  return float(h >> 8u) * (1.0f / 16777216.0f);
}

// The alpha of triangle tri at barycentrics (u, v) (weights of its second and third corners).
SHARED_FN float surfaceAlpha(uint tri, TriangleShading s, MaterialGpu m, float u, float v) {
  float a = m.alpha;
  if (HAS_VERTEX_COLORS)
    a *= triangleVertexColor(s, u, v).w;
  if (HAS_TEXTURES && m.baseColorTexture >= 0) {
    a *= sampleTexture(m.baseColorTexture, slotUv(tri, s, m.flags, kMaterialSecondUvBaseColor, u, v), true).w;   // linear either way
  }
  return a;
}

SHARED_FN bool alphaPassesThrough(uint tri, float u, float v, vec3 origin, vec3 direction) {
  if (!HAS_ALPHA) return false;
  TriangleShading s = TRIANGLE_SHADING(tri);
  MaterialGpu m = MATERIAL(s.material);
  if ((m.flags & (kMaterialAlphaMask | kMaterialAlphaBlend)) == 0u) return false;
  float a = surfaceAlpha(tri, s, m, u, v);
  if ((m.flags & kMaterialAlphaMask) != 0u) return a < m.alphaCutoff;
  return alphaHash(origin, direction, tri) >= a;
}

SHARED_END_WITH_BUFFERS
#endif
