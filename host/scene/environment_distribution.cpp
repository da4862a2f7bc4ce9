#include "scene/environment_distribution.h"

#include <cmath>

#include "shared/environment_layout.h"
#include "shared/sampling.h"

namespace mixtrace {
namespace {

constexpr double kPi = 3.14159265358979323846;

// cos(theta_top) - cos(theta_bottom) of a row: its solid angle over 2 pi, exactly (not sin(theta)
// at the row's centre, which is off by a few per cent near the poles of a small map).
double rowBand(uint32_t row, uint32_t height) {
  return std::cos(kPi * double(row) / double(height)) - std::cos(kPi * double(row + 1) / double(height));
}

double texelWeight(const Environment& env, uint32_t x, uint32_t y) {
  return double(shared::luminance(env.radiance[size_t(y) * env.width + x])) * rowBand(y, env.height);
}

// Writes the inclusive CDF of `weights` into out[0 .. n] (0 first, 1 last), in double so a row of
// a million texels keeps its small ones; a row without weight gets a uniform CDF (it is never
// chosen: its marginal probability is 0).
void writeCdf(const std::vector<double>& weights, float* out) {
  double total = 0.0;
  for (double w : weights) total += w;
  const size_t n = weights.size();
  double sum = 0.0;
  out[0] = 0.0f;
  for (size_t i = 0; i < n; ++i) {
    sum += weights[i];
    out[i + 1] = i + 1 == n ? 1.0f : float(total > 0.0 ? sum / total : double(i + 1) / double(n));
  }
}

}  // namespace

double environmentLuminanceIntegral(const Environment& env) {
  if (!env.present()) return 0.0;
  double sum = 0.0;
  for (uint32_t y = 0; y < env.height; ++y)
    for (uint32_t x = 0; x < env.width; ++x) sum += texelWeight(env, x, y);
  // Each texel spans 2 pi / W of phi; its row's band of cos(theta) is in the weight.
  return sum * (2.0 * kPi / env.width);
}

std::vector<float> buildEnvironmentBuffer(const Environment& env, int32_t light) {
  const bool present = light >= 0 && env.present();
  const uint32_t w = present ? env.width : 0u, h = present ? env.height : 0u;
  std::vector<float> data(present ? shared::envFloatCount(w, h) : shared::kEnvHeaderFloats, 0.0f);
  data[shared::kEnvWidth] = float(w);
  data[shared::kEnvHeight] = float(h);
  data[shared::kEnvLight] = present ? float(light) : -1.0f;
  data[shared::kEnvRotationCos] = std::cos(env.rotation);
  data[shared::kEnvRotationSin] = std::sin(env.rotation);
  if (!present) return data;

  std::vector<double> rowWeights(h, 0.0), weights(w);
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      weights[x] = texelWeight(env, x, y);
      rowWeights[y] += weights[x];
    }
    writeCdf(weights, &data[shared::envConditionalOffset(w, h) + size_t(y) * (w + 1)]);
  }
  writeCdf(rowWeights, &data[shared::envMarginalOffset()]);
  float* radiance = &data[shared::envRadianceOffset(w, h)];
  for (size_t i = 0; i < env.radiance.size(); ++i)
    for (int c = 0; c < 3; ++c) radiance[3 * i + size_t(c)] = env.radiance[i][c];
  return data;
}

}  // namespace mixtrace
