// The film the accumulate pass writes (shaders/wavefront/accumulate.comp): per pixel the running
// mean and the sum of squared deviations M2 (Welford). What is derived from it is written once,
// for the host's read-back and the viewer's display pass alike.
#ifndef MIXTRACE_SHARED_FILM_H
#define MIXTRACE_SHARED_FILM_H
#include "shared/dialect.h"
SHARED_BEGIN

// The variance of the mean of n samples: sample variance / n = M2 / (n (n - 1)); 0 below 2
// samples, and never negative (M2 can round below 0).
SHARED_FN float varianceOfMean(float m2, float n) {
  return n > 1.0f ? max(m2, 0.0f) / (n * (n - 1.0f)) : 0.0f;
}

SHARED_END
#endif
