// Random numbers: a PCG-hash stream per path (Jarzynski & Olano 2020). Stateless to start
// (pixel, sample pass, seed) so a render is reproducible for a seed, one uint of state after.
#ifndef MIXTRACE_SHARED_RNG_H
#define MIXTRACE_SHARED_RNG_H
#include "shared/dialect.h"
SHARED_BEGIN

SHARED_FN uint pcgHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

SHARED_FN uint rngInit(uint pixel, uint sampleIndex, uint seed) {
  return pcgHash(pixel ^ pcgHash(sampleIndex + pcgHash(seed)));
}

SHARED_FN uint rngNextUint(INOUT(uint) state) {
  state = state * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// Uniform in [0, 1): 24 random bits, so the result is exactly representable and never 1.
SHARED_FN float rngNextFloat(INOUT(uint) state) {
  return float(rngNextUint(state) >> 8u) * (1.0f / 16777216.0f);
}

SHARED_END
#endif
