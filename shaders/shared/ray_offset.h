// Robust ray origins: offset a surface point along the geometric normal by a few ULPs scaled
// with the magnitude of the coordinates (Wächter & Binder, Ray Tracing Gems ch. 6), so a ray
// never re-hits the surface it leaves. Near a coordinate plane the ULPs of the point say nothing
// about the rounding error of the hit (that comes from the ray origins and vertices involved), so
// there the offset is a fixed fraction of the scene's coordinate magnitude: scaled with the
// scene, so that a scene a millimetre across is offset by as little, relative to its size, as one
// a metre across (an absolute 2^-16 brightened a 2 mm room by 0.4 %).
//
// The includer defines SCENE_SCALE() -> float: the largest absolute coordinate of the scene's
// bounds (Bounds::magnitude()).
#ifndef MIXTRACE_SHARED_RAY_OFFSET_H
#define MIXTRACE_SHARED_RAY_OFFSET_H
#include "shared/dialect.h"
SHARED_BEGIN_WITH_BUFFERS

SHARED_FN float offsetComponent(float p, float n, float scale) {
  const float kOrigin = 1.0f / 32.0f;       // times the scene scale: "near the plane"
  const float kFloatScale = 1.0f / 65536.0f; // times the scene scale: the offset there
  const float kIntScale = 256.0f;
  int offsetInt = int(kIntScale * n);
  float pInt = intBitsToFloat(floatBitsToInt(p) + (p < 0.0f ? -offsetInt : offsetInt));
  return abs(p) < kOrigin * scale ? p + kFloatScale * scale * n : pInt;
}

// n: geometric normal on the side the new ray leaves towards.
SHARED_FN vec3 offsetRayOrigin(vec3 p, vec3 n) {
  float scale = max(SCENE_SCALE(), 1e-30f);
  return vec3(offsetComponent(p.x, n.x, scale), offsetComponent(p.y, n.y, scale), offsetComponent(p.z, n.z, scale));
}

SHARED_END_WITH_BUFFERS
#endif
