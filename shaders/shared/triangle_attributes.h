// A triangle's vertex attributes at barycentrics (u, v) (the weights of its second and third
// corners), from its shading data: one definition for the surface a ray hits (surface.h), the
// alpha test during traversal (alpha.h) and the emission of a light point (lights.h). Needs the
// TRIANGLE_UV2 accessor (second texture coordinates) and HAS_SECOND_UVS.
#ifndef MIXTRACE_SHARED_TRIANGLE_ATTRIBUTES_H
#define MIXTRACE_SHARED_TRIANGLE_ATTRIBUTES_H
#include "shared/dialect.h"
#include "shared/layouts.h"
#include "shared/vertex_color.h"
SHARED_BEGIN_WITH_BUFFERS

SHARED_FN vec2 triangleUv(TriangleShading s, float u, float v) {
  return (1.0f - u - v) * s.uv0 + u * s.uv1 + v * s.uv2;
}

// The second texture coordinates of triangle `tri` (only where its material reads them).
SHARED_FN vec2 triangleSecondUv(uint tri, float u, float v) {
  TriangleUvs t = TRIANGLE_UV2(tri);
  return (1.0f - u - v) * t.uv0 + u * t.uv1 + v * t.uv2;
}

// The coordinates texture slot `slot` (a kMaterialSecondUv* bit) of a material with `flags` reads:
// the second mapping where the material marks the slot, the first otherwise.
SHARED_FN vec2 slotUv(uint tri, TriangleShading s, uint flags, uint slot, float u, float v) {
  if (HAS_SECOND_UVS && (flags & slot) != 0u) return triangleSecondUv(tri, u, v);
  return triangleUv(s, u, v);
}

// COLOR_0, linear RGBA (white where the file has none).
SHARED_FN vec4 triangleVertexColor(TriangleShading s, float u, float v) {
  return (1.0f - u - v) * unpackVertexColor(s.color0) + u * unpackVertexColor(s.color1) +
         v * unpackVertexColor(s.color2);
}

SHARED_END_WITH_BUFFERS
#endif
