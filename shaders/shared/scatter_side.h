// Which side of a surface a scattered direction leaves on, for every integrator alike. The BSDF
// works in the shading frame (normal +z: reflection wi.z > 0, transmission wi.z < 0), the rays
// in the geometry; where shading normals bend the two apart, a direction on one side of the
// shading frame and the other of the geometric surface carries nothing (f = 0, and a BSDF sample
// there fails), so light never leaks through an opaque surface nor reflects off the far side of
// glass.
#ifndef MIXTRACE_SHARED_SCATTER_SIDE_H
#define MIXTRACE_SHARED_SCATTER_SIDE_H
#include "shared/dialect.h"
SHARED_BEGIN

// Whether world direction w with shading-frame z component wLocalZ leaves on the same side of the
// geometric surface (unit normal ng, on the incoming ray's side) as the shading frame says.
SHARED_FN bool leavesOnShadingSide(vec3 w, vec3 ng, float wLocalZ) {
  float g = dot(w, ng);
  if (wLocalZ > 0.0f) return g > 0.0f;
  return wLocalZ < 0.0f && g < 0.0f;
}

// Whether a light at direction w can reach the vertex through its BSDF: above the geometric
// surface, or for a BSDF that transmits also below it, on the shading frame's matching side.
SHARED_FN bool lightSideReachable(vec3 w, vec3 ng, float wLocalZ, bool transmits) {
  return transmits ? leavesOnShadingSide(w, ng, wLocalZ) : dot(w, ng) > 0.0f;
}

// The origin of a ray that leaves along w: the vertex's origin offset to the incoming side
// (`above`) or, for a transmitted ray, to the other (`below`).
SHARED_FN vec3 originTowards(vec3 w, vec3 ng, vec3 above, vec3 below) {
  return dot(w, ng) > 0.0f ? above : below;
}

SHARED_END
#endif
