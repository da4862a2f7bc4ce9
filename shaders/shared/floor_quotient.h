// floor(i / n) for integers without integer division, shared by the texture wrap modes
// (shared/texture.h) and the camera's pixel rows (shared/camera.h).
//
// Why: SIMD units have no integer division, so lavapipe divides lane by lane (and the remainders
// were a large part of a textured scene's shade pass and the generate pass's costliest lines).
// The float quotient is within one of the true one while |i / n| < 2^21: float(i) and a GLSL
// division (allowed 2.5 ulp off, a GPU's reciprocal) each err by a few ulps, relatively; below
// 2^24 in |i| the correctly rounded quotient is even exact, since its distance to an integer is at
// least 1 / n. The two corrections absorb the one either way.
#ifndef MIXTRACE_SHARED_FLOOR_QUOTIENT_H
#define MIXTRACE_SHARED_FLOOR_QUOTIENT_H
#include "shared/dialect.h"
SHARED_BEGIN

// floor(i / n) for n > 0 and |i / n| < 2^21.
SHARED_FN int floorQuotient(int i, int n) {
  int q = int(floor(float(i) / float(n)));
  int rest = i - q * n;
  if (rest < 0) --q;
  if (rest >= n) ++q;
  return q;
}

SHARED_END
#endif
