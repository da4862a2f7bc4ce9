// Robust ray origins: a ray that leaves a surface starts just off it, on the side it leaves
// towards, by no more than the rounding error of the surface point itself (pbrt-v4's
// OffsetRayOrigin, after Wächter & Binder, Ray Tracing Gems ch. 6).
//
// A surface point is computed as p = v0 + u e1 + v e2 (surface.h, and light points in lights.h)
// from the triangle's stored v0 and edges, the very data the intersector tests against, so the
// exact point for the computed (u, v) lies on the triangle's plane; an error in u, v only moves
// it within the plane. The float evaluation's error is bounded per component by
// gamma(3) (|v0| + |u e1| + |v e2|); moving p along the geometric normal n by dot(|n|, error)
// puts it outside that error box, on n's side. The bound depends only on the triangle's own
// vertices and the point, never on the rest of the scene: one far-away prop (a triangle at 1e5
// beside a 1-unit room) changes no offset in the room, where the previous offset, a fraction of
// the scene's largest coordinate, pushed every ray of the room 1.5 units off its surface.
//
// The factor is generous (16 ulps instead of gamma(3) ~ 3): the Möller–Trumbore test
// (bvh_traverse.h) rounds too, by about gamma(5) |s| |e1| |e2| in its scaled t, which is of the
// point error's size for any triangle that is not a sliver; the final p + offset rounds; and GPU
// compilers may contract or reorder the interpolation. It is still 16 times smaller than the
// 256 ulps of Ray Tracing Gems' integer offset. Exact zeros stay exact: a floor whose vertices
// all have y = 0 has error 0 in y, the ray starts on the plane, and the intersector's scaled t
// there is exactly 0 (its terms multiply by those zeros), which never counts as a hit (t > 0).
#ifndef MIXTRACE_SHARED_RAY_OFFSET_H
#define MIXTRACE_SHARED_RAY_OFFSET_H
#include "shared/dialect.h"
#include "shared/layouts.h"
SHARED_BEGIN_WITH_BUFFERS

const float kSurfacePointRelativeError = 16.0f * 5.9604645e-8f;   // 16 * 2^-24 (unit roundoff)

// Per-component bound on the rounding error of g.v0 + u g.e1 + v g.e2 evaluated in float.
SHARED_FN vec3 trianglePointError(TriangleGeom g, float u, float v) {
  return kSurfacePointRelativeError * (abs(g.v0) + abs(u * g.e1) + abs(v * g.e2));
}

// p moved off its surface along n (unit geometric normal on the side the new ray leaves towards)
// by the distance that clears p's error box `pError`.
SHARED_FN vec3 offsetRayOrigin(vec3 p, vec3 pError, vec3 n) {
  float d = dot(abs(n), pError);
  return p + d * n;
}

// The origins of the rays leaving a hit at p, with error bound pointError (trianglePointError,
// SurfaceHit.positionError) and geometric normal n (on the incoming side): offset to that side
// (`above`) and, for a BSDF that transmits, to the far side (`below`; otherwise the same), for
// every integrator alike (scatter_side.h originTowards picks one).
SHARED_FN void scatterOrigins(vec3 p, vec3 pointError, vec3 n, bool transmits, OUT(vec3) above, OUT(vec3) below) {
  above = offsetRayOrigin(p, pointError, n);
  below = transmits ? offsetRayOrigin(p, pointError, -n) : above;
}

SHARED_END_WITH_BUFFERS
#endif
