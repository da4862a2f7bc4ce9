// A vertex tangent as the triangles carry it (glTF TANGENT, or one the loader generated from the
// UVs): the unit direction octahedral-encoded in 2 x 15 bits, the bitangent's sign (glTF's w) in
// bit 30, "has a tangent" in bit 31. One uint per corner keeps the shading data small; 15 bits
// per axis put the direction within about 1e-4 rad. Packed by the host (scene/prepared_scene.cpp),
// unpacked by shared/surface.h for normal mapping.
#ifndef MIXTRACE_SHARED_TANGENT_FRAME_H
#define MIXTRACE_SHARED_TANGENT_FRAME_H
#include "shared/dialect.h"
SHARED_BEGIN

const uint kTangentPresent = 0x80000000u;
const uint kTangentNegativeW = 0x40000000u;

SHARED_FN float octahedralSign(float x) { return x < 0.0f ? -1.0f : 1.0f; }

SHARED_FN uint packTangent(vec4 t) {
  vec3 d = vec3(t.x, t.y, t.z);
  float l1 = abs(d.x) + abs(d.y) + abs(d.z);
  if (!(l1 > 0.0f)) return 0u;
  d = d / l1;
  float ox = d.x;
  float oy = d.y;
  if (d.z < 0.0f) {
    ox = (1.0f - abs(d.y)) * octahedralSign(d.x);
    oy = (1.0f - abs(d.x)) * octahedralSign(d.y);
  }
  uint x = uint(clamp(ox * 0.5f + 0.5f, 0.0f, 1.0f) * 32767.0f + 0.5f);
  uint y = uint(clamp(oy * 0.5f + 0.5f, 0.0f, 1.0f) * 32767.0f + 0.5f);
  return kTangentPresent | (t.w < 0.0f ? kTangentNegativeW : 0u) | x | (y << 15u);
}

// xyz unit (0 without a tangent), w = +-1.
SHARED_FN vec4 unpackTangent(uint p) {
  if ((p & kTangentPresent) == 0u) return vec4(0.0f);
  float ox = float(p & 0x7fffu) / 32767.0f * 2.0f - 1.0f;
  float oy = float((p >> 15u) & 0x7fffu) / 32767.0f * 2.0f - 1.0f;
  vec3 d = vec3(ox, oy, 1.0f - abs(ox) - abs(oy));
  if (d.z < 0.0f) {
    float x = (1.0f - abs(oy)) * octahedralSign(ox);
    float y = (1.0f - abs(ox)) * octahedralSign(oy);
    d.x = x;
    d.y = y;
  }
  d = normalize(d);
  return vec4(d.x, d.y, d.z, (p & kTangentNegativeW) != 0u ? -1.0f : 1.0f);
}

SHARED_END
#endif
