// The environment light: radiance from an equirectangular map at infinity, sampled by a
// piecewise-constant distribution over its texels (each weighted by its luminance x its solid
// angle, so that a texel is drawn as often as it contributes), with exact pdfs.
// One source for the GPU shade pass, the CPU code and the tests.
//
// Map convention (Mitsuba 3's envmap, so that the two renderers agree on the same file): +Y is
// up; in map space a direction m has u = atan2(m.x, -m.z) / (2 pi) (wrapped to [0, 1)) and
// v = acos(m.y) / pi, v = 0 the top row. So -Z is the map's left edge (u = 0), +X is u = 1/4 and
// +Z the centre column. --env-rotate R turns the environment by R about +Y (right-handed):
// map space is world space rotated by -R. Radiance is the nearest texel's: piecewise constant,
// as the distribution is. Inside a texel the sample is uniform in (u, v), so its solid-angle
// density varies as 1 / sin(theta) (and grows without bound at the poles, where the texels
// shrink to points: the pdf stays exact, and integrable).
//
// The includer defines ENV_DATA(i) -> float (the ENVIRONMENT buffer, shared/environment_layout.h).
#ifndef MIXTRACE_SHARED_ENVIRONMENT_H
#define MIXTRACE_SHARED_ENVIRONMENT_H
#include "shared/constants.h"
#include "shared/dialect.h"
#include "shared/environment_layout.h"
SHARED_BEGIN_WITH_BUFFERS

SHARED_FN uint envWidth() { return uint(ENV_DATA(kEnvWidth)); }
SHARED_FN uint envHeight() { return uint(ENV_DATA(kEnvHeight)); }

// Whether the scene has an environment, and its light index.
SHARED_FN bool hasEnvironmentLight() { return ENV_DATA(kEnvLight) >= 0.0f; }
SHARED_FN uint environmentLight() { return uint(ENV_DATA(kEnvLight)); }

// World direction -> map space (rotated by -R about +Y), and back.
SHARED_FN vec3 envToMap(vec3 d) {
  float c = ENV_DATA(kEnvRotationCos);
  float s = ENV_DATA(kEnvRotationSin);
  vec3 m;
  m.x = c * d.x - s * d.z;
  m.y = d.y;
  m.z = s * d.x + c * d.z;
  return m;
}
SHARED_FN vec3 envFromMap(vec3 m) {
  float c = ENV_DATA(kEnvRotationCos);
  float s = ENV_DATA(kEnvRotationSin);
  vec3 d;
  d.x = c * m.x + s * m.z;
  d.y = m.y;
  d.z = -s * m.x + c * m.z;
  return d;
}

// The texel (column, row) a map-space direction falls in.
SHARED_FN uint envColumn(vec3 m) {
  float u = atan2(m.x, -m.z) * (0.5f * kInvPi);
  if (u < 0.0f) u += 1.0f;
  uint w = envWidth();
  return min(uint(u * float(w)), w - 1u);
}
SHARED_FN uint envRow(vec3 m) {
  float v = acos(clamp(m.y, -1.0f, 1.0f)) * kInvPi;
  uint h = envHeight();
  return min(uint(v * float(h)), h - 1u);
}

SHARED_FN vec3 envTexelRadiance(uint column, uint row) {
  uint w = envWidth();
  uint i = envRadianceOffset(w, envHeight()) + 3u * (row * w + column);
  return vec3(ENV_DATA(i), ENV_DATA(i + 1u), ENV_DATA(i + 2u));
}

// Radiance arriving along -dir (dir: unit, from the scene towards the environment).
SHARED_FN vec3 environmentRadiance(vec3 dir) {
  vec3 m = envToMap(dir);
  return envTexelRadiance(envColumn(m), envRow(m));
}

// Density of texel (column, row) in the unit square of (u, v): its probability x W x H, from the
// same CDF differences the sampler inverts.
SHARED_FN float envTexelPdfUv(uint column, uint row) {
  uint w = envWidth();
  uint h = envHeight();
  uint marginal = envMarginalOffset() + row;
  uint conditional = envConditionalOffset(w, h) + row * (w + 1u) + column;
  float pRow = ENV_DATA(marginal + 1u) - ENV_DATA(marginal);
  float pColumn = ENV_DATA(conditional + 1u) - ENV_DATA(conditional);
  return pRow * float(h) * pColumn * float(w);
}

// Solid-angle density of a (u, v) density at map direction m: dω = 2 pi^2 sin(theta) du dv.
SHARED_FN float envSolidAnglePdf(float pdfUv, vec3 m) {
  float sinTheta = sqrt(max(m.x * m.x + m.z * m.z, 0.0f));
  if (!(sinTheta > 0.0f) || !(pdfUv > 0.0f)) return 0.0f;
  return pdfUv / (2.0f * kPi * kPi * sinTheta);
}

// The solid-angle density with which sampleEnvironment produces dir.
SHARED_FN float environmentPdf(vec3 dir) {
  vec3 m = envToMap(dir);
  return envSolidAnglePdf(envTexelPdfUv(envColumn(m), envRow(m)), m);
}

// Inverts the inclusive CDF [offset, offset + n] (n + 1 entries, 0 first): the first bin i with
// u < cdf[i + 1], which never has zero width; t is u's position inside it, in [0, 1).
SHARED_FN uint envInvertCdf(uint offset, uint n, float u, OUT(float) t) {
  uint lo = 0u;
  uint hi = n - 1u;
  while (lo < hi) {
    uint mid = (lo + hi) >> 1u;
    if (u < ENV_DATA(offset + mid + 1u)) hi = mid; else lo = mid + 1u;
  }
  float a = ENV_DATA(offset + lo);
  float b = ENV_DATA(offset + lo + 1u);
  t = b > a ? clamp((u - a) / (b - a), 0.0f, 0.99999994f) : 0.5f;
  return lo;
}

// A direction towards the environment for u in [0, 1)^2, its solid-angle pdf and its radiance.
// pdf 0 where the sample has no density (a pole, to float precision).
SHARED_FN vec3 sampleEnvironment(vec2 u, OUT(float) pdf, OUT(vec3) radiance) {
  uint w = envWidth();
  uint h = envHeight();
  float tRow, tColumn;
  uint row = envInvertCdf(envMarginalOffset(), h, u.x, tRow);
  uint column = envInvertCdf(envConditionalOffset(w, h) + row * (w + 1u), w, u.y, tColumn);
  float theta = kPi * (float(row) + tRow) / float(h);
  float phi = kTwoPi * (float(column) + tColumn) / float(w);
  float sinTheta = sin(theta);
  vec3 m;
  m.x = sin(phi) * sinTheta;
  m.y = cos(theta);
  m.z = -cos(phi) * sinTheta;
  pdf = envSolidAnglePdf(envTexelPdfUv(column, row), m);
  radiance = envTexelRadiance(column, row);
  return envFromMap(m);
}

SHARED_END_WITH_BUFFERS
#endif
