// glTF COLOR_0, as the triangles carry it: linear RGBA, each channel a 16-bit unsigned normalized
// integer, two per uint (R | G << 16, B | A << 16). Eight bits would band the dark values of a
// linear colour; a float per channel would add 36 bytes to every triangle's shading data, which
// every hit reads. Packed by the host (scene/prepared_scene.cpp), unpacked by shared/surface.h.
#ifndef MIXTRACE_SHARED_VERTEX_COLOR_H
#define MIXTRACE_SHARED_VERTEX_COLOR_H
#include "shared/dialect.h"
SHARED_BEGIN

SHARED_FN uint packUnorm16Pair(float a, float b) {
  uint lo = uint(clamp(a, 0.0f, 1.0f) * 65535.0f + 0.5f);
  uint hi = uint(clamp(b, 0.0f, 1.0f) * 65535.0f + 0.5f);
  return lo | (hi << 16u);
}

SHARED_FN uvec2 packVertexColor(vec4 c) {
  uvec2 p;
  p.x = packUnorm16Pair(c.x, c.y);
  p.y = packUnorm16Pair(c.z, c.w);
  return p;
}

SHARED_FN vec4 unpackVertexColor(uvec2 p) {
  const float k = 1.0f / 65535.0f;
  return vec4(float(p.x & 0xffffu) * k, float(p.x >> 16u) * k, float(p.y & 0xffffu) * k, float(p.y >> 16u) * k);
}

SHARED_END
#endif
