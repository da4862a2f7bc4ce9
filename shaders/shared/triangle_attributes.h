// A triangle's vertex attributes at barycentrics (u, v) (the weights of its second and third
// corners), from its shading data: one definition for the surface a ray hits (surface.h), the
// alpha test during traversal (alpha.h) and the emission of a light point (lights.h).
#ifndef MIXTRACE_SHARED_TRIANGLE_ATTRIBUTES_H
#define MIXTRACE_SHARED_TRIANGLE_ATTRIBUTES_H
#include "shared/dialect.h"
#include "shared/layouts.h"
#include "shared/vertex_color.h"
SHARED_BEGIN

SHARED_FN vec2 triangleUv(TriangleShading s, float u, float v) {
  return (1.0f - u - v) * s.uv0 + u * s.uv1 + v * s.uv2;
}

// COLOR_0, linear RGBA (white where the file has none).
SHARED_FN vec4 triangleVertexColor(TriangleShading s, float u, float v) {
  return (1.0f - u - v) * unpackVertexColor(s.color0) + u * unpackVertexColor(s.color1) +
         v * unpackVertexColor(s.color2);
}

SHARED_END
#endif
