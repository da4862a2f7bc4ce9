// Robust ray origins: offset a surface point along the geometric normal by a few ULPs scaled
// with the magnitude of the coordinates (Wächter & Binder, Ray Tracing Gems ch. 6), so a ray
// never re-hits the surface it leaves, at any scene scale, without a fixed epsilon.
#ifndef MIXTRACE_SHARED_RAY_OFFSET_H
#define MIXTRACE_SHARED_RAY_OFFSET_H
#include "shared/dialect.h"
SHARED_BEGIN

SHARED_FN float offsetComponent(float p, float n) {
  const float kOrigin = 1.0f / 32.0f;
  const float kFloatScale = 1.0f / 65536.0f;
  const float kIntScale = 256.0f;
  int offsetInt = int(kIntScale * n);
  float pInt = intBitsToFloat(floatBitsToInt(p) + (p < 0.0f ? -offsetInt : offsetInt));
  return abs(p) < kOrigin ? p + kFloatScale * n : pInt;
}

// n: geometric normal on the side the new ray leaves towards.
SHARED_FN vec3 offsetRayOrigin(vec3 p, vec3 n) {
  return vec3(offsetComponent(p.x, n.x), offsetComponent(p.y, n.y), offsetComponent(p.z, n.z));
}

SHARED_END
#endif
