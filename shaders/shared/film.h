// The film the accumulate pass writes (shaders/wavefront/accumulate.comp): per pixel the running
// mean and the square root of Welford's sum of squared deviations, sqrt(M2). What is derived
// from it is written once, for the host's read-back and the viewer's display pass alike.
//
// Why sqrt(M2) and not M2: M2 scales with the square of the image, so in float it overflows for
// pixels above ~1e19 (emitters of 1e20 gave an infinite, then NaN, variance) and underflows below
// ~1e-19 (emitters of 1e-30 gave exactly 0), and `compare` called two correct renders different.
// sqrt(M2) has the image's own units and range. Welford's increment (x - mean)(x - mean') is never
// negative (both factors have the sign of x - mean), so its square root is sqrt|a| sqrt|b|, and the
// running sum becomes a hypot, formed without squaring the larger term. For the same reason the
// film's uncertainty leaves the renderer as the standard error of the mean (exr_io.h), never as
// a variance.
#ifndef MIXTRACE_SHARED_FILM_H
#define MIXTRACE_SHARED_FILM_H
#include "shared/dialect.h"
SHARED_BEGIN

// sqrt(a^2 + b^2) for a, b >= 0 without overflow or underflow of the squares.
SHARED_FN float filmHypot(float a, float b) {
  float big = max(a, b);
  float small = min(a, b);
  if (!(big > 0.0f)) return 0.0f;
  float ratio = small / big;
  return big * sqrt(1.0f + ratio * ratio);
}

// One Welford step of sqrt(M2), per channel: `before` = x - mean (old mean), `after` = x - mean
// (updated mean).
SHARED_FN vec3 filmRootM2Update(vec3 rootM2, vec3 before, vec3 after) {
  vec3 increment = sqrt(abs(before)) * sqrt(abs(after));
  return vec3(filmHypot(rootM2.x, increment.x), filmHypot(rootM2.y, increment.y), filmHypot(rootM2.z, increment.z));
}

// The standard error of the mean of n samples: sqrt(M2 / (n (n - 1))); 0 below 2 samples.
SHARED_FN float standardErrorOfMean(float rootM2, float n) {
  return n > 1.0f ? rootM2 / (sqrt(n) * sqrt(n - 1.0f)) : 0.0f;
}

SHARED_END
#endif
