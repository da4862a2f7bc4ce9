// The environment light's sampler and pdfs (shaders/shared/environment.h), compiled as C++ on the
// buffer the host builds for the shaders (scene/environment_distribution.h): a chi-square test of
// the sampled directions against the evaluated pdf (integrated over cells of the sphere that do
// not follow the map's texels), the pdf of a sampled direction equals the evaluated one, the
// radiance returned with a sample is the radiance looked up for its direction, and the power the
// light selection uses is the map's integral.
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "scene/environment_distribution.h"
#include "support/chi2.h"

namespace {
// The buffer the shared header reads (one per test, set before use).
std::vector<float> gEnvBuffer;
}  // namespace
#define ENV_DATA(i) (gEnvBuffer[i])
#include "shared/environment.h"
#include "shared/sampling.h"

namespace {

using namespace mixtrace;
using namespace mixtrace::shared;
using glm::vec3;

constexpr double kPi = 3.14159265358979323846;
constexpr int kSamples = 1000000;
// Chi-square tests in this executable expected to pass; each gets a Šidák share of 1 %.
constexpr int kChiSquareTests = 3;
const double kLevel = chi2::sidakLevel(kChiSquareTests);

// A map whose texels vary over two orders of magnitude, with one texel far brighter, and black
// texels (which must never be sampled).
Environment variedMap(uint32_t w, uint32_t h, float rotation) {
  Environment env;
  env.width = w;
  env.height = h;
  env.rotation = rotation;
  env.source = "test";
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (uint32_t i = 0; i < w * h; ++i) {
    const float scale = std::pow(10.0f, 2.0f * u(rng));
    env.radiance.push_back(vec3(u(rng), u(rng), u(rng)) * scale * 0.01f);
  }
  env.radiance[size_t(h / 3) * w + w / 4] = vec3(400.0f, 300.0f, 200.0f);
  for (uint32_t x = 0; x < w; x += 3) env.radiance[size_t(h - 2) * w + x] = vec3(0.0f);
  return env;
}

Environment oneColour(uint32_t w, uint32_t h, vec3 c) {
  Environment env;
  env.width = w;
  env.height = h;
  env.radiance.assign(size_t(w) * h, c);
  env.source = "test";
  return env;
}

void expectFits(const chi2::FitResult& fit) {
  std::printf("    p-value %.4f (chi2 %.1f, %d dof), pdf integral %.6f, failed %.6f\n", fit.chi2.pValue,
              fit.chi2.statistic, fit.chi2.dof, fit.pdfIntegral, fit.failureFraction);
  EXPECT_GT(fit.chi2.pValue, kLevel) << "chi2 " << fit.chi2.statistic << " dof " << fit.chi2.dof;
  EXPECT_NEAR(fit.pdfIntegral, 1.0 - fit.failureFraction, chi2::successFractionTolerance(fit));
}

chi2::FitResult fitSampler(const Environment& env) {
  gEnvBuffer = buildEnvironmentBuffer(env, 0);
  // The test's grid has its pole (+z) on the map's (+y): there the solid-angle density grows as
  // 1 / sin(theta), which the grid's own sin(theta) cancels, so the quadrature sees a bounded
  // integrand. Its cells (8 x 16) cut across the map's texels, whose edges it meets inside cells,
  // so it starts finely.
  chi2::SphereGrid grid;
  grid.thetaBins = 8;
  grid.phiBins = 16;
  return chi2::testSamplerAgainstPdf(
      [](chi2::Uniforms& u, vec3& dir) {
        float pdf;
        vec3 radiance;
        const vec3 d = sampleEnvironment(u.next2(), pdf, radiance);
        dir = vec3(-d.z, d.x, d.y);
        return pdf > 0.0f;
      },
      [](vec3 g) { return double(environmentPdf(glm::normalize(vec3(g.y, g.z, -g.x)))); }, 0.06, kSamples, 5, {},
      grid);
}

TEST(EnvironmentChi2, VariedMapFollowsItsPdf) { expectFits(fitSampler(variedMap(12, 6, 0.0f))); }

TEST(EnvironmentChi2, RotatedVariedMapFollowsItsPdf) { expectFits(fitSampler(variedMap(10, 5, 0.7f))); }

TEST(EnvironmentChi2, UniformMapIsUniformOverTheSphere) {
  const chi2::FitResult fit = fitSampler(oneColour(32, 16, vec3(0.5f)));
  expectFits(fit);
  // Uniform in solid angle to float precision, away from the poles.
  gEnvBuffer = buildEnvironmentBuffer(oneColour(32, 16, vec3(0.5f)), 0);
  chi2::Uniforms u(3);
  for (int i = 0; i < 1000; ++i) {
    float pdf;
    vec3 radiance;
    const vec3 d = sampleEnvironment(u.next2(), pdf, radiance);
    if (std::abs(d.y) > 0.9f) continue;
    // The row weights use sin(theta) at the row centre: within a row the density varies with
    // sin(centre) / sin(theta), at most a few per cent on a 16-row map away from the poles.
    EXPECT_NEAR(pdf, 1.0 / (4.0 * kPi), 0.35 / (4.0 * kPi));
    EXPECT_EQ(radiance, vec3(0.5f));
  }
}

// The pdf and radiance returned with a sample are those evaluated for its direction (the MIS
// weight of an escaped BSDF sample uses the evaluated ones). A direction on a texel edge may round
// into its neighbour: allowed for a handful of samples in a million.
TEST(EnvironmentPdf, SampledPdfAndRadianceEqualTheEvaluatedOnes) {
  for (float rotation : {0.0f, 2.1f}) {
    const Environment env = variedMap(24, 12, rotation);
    gEnvBuffer = buildEnvironmentBuffer(env, 0);
    chi2::Uniforms u(11);
    int mismatched = 0, sampled = 0;
    for (int i = 0; i < 200000; ++i) {
      float pdf;
      vec3 radiance;
      const vec3 d = sampleEnvironment(u.next2(), pdf, radiance);
      ASSERT_NEAR(glm::length(d), 1.0f, 1e-5f);
      if (!(pdf > 0.0f)) continue;
      ++sampled;
      EXPECT_TRUE(std::isfinite(pdf));
      const float evaluated = environmentPdf(d);
      const bool same = std::abs(evaluated - pdf) <= 1e-4f * pdf && environmentRadiance(d) == radiance;
      if (!same) ++mismatched;
    }
    std::printf("rotation %.1f: %d of %d samples off their texel\n", rotation, mismatched, sampled);
    EXPECT_GT(sampled, 199000);
    EXPECT_LE(mismatched, sampled / 10000);
  }
}

// Black texels are never drawn; the bright texel is drawn in proportion to its share.
TEST(EnvironmentPdf, BlackTexelsAreNeverSampled) {
  const Environment env = variedMap(12, 6, 0.0f);
  gEnvBuffer = buildEnvironmentBuffer(env, 0);
  chi2::Uniforms u(2);
  for (int i = 0; i < 100000; ++i) {
    float pdf;
    vec3 radiance;
    sampleEnvironment(u.next2(), pdf, radiance);
    if (pdf > 0.0f) EXPECT_GT(luminance(radiance), 0.0f);
  }
}

// The rotation turns the map about +Y, right-handed: the map's centre column (+Z in map space)
// lies at +Z rotated by R.
TEST(EnvironmentPdf, RotationTurnsTheMapAboutY) {
  Environment env = oneColour(8, 4, vec3(0.0f));
  env.radiance[size_t(2) * 8 + 4] = vec3(1.0f);  // just below the horizon, centre column: +Z
  env.rotation = float(kPi / 2.0);
  gEnvBuffer = buildEnvironmentBuffer(env, 0);
  const vec3 plusZTurned = glm::normalize(vec3(std::sin(kPi / 2.0), -0.1f, std::cos(kPi / 2.0)));
  EXPECT_EQ(environmentRadiance(plusZTurned), vec3(1.0f));
  EXPECT_EQ(environmentRadiance(glm::normalize(vec3(0.0f, -0.1f, 1.0f))), vec3(0.0f));
  float pdf;
  vec3 radiance;
  const vec3 d = sampleEnvironment(glm::vec2(0.5f, 0.5f), pdf, radiance);
  EXPECT_GT(d.x, 0.8f);
  EXPECT_LT(std::abs(d.z), 0.4f);  // (0.5, 0.5) is half a texel (22.5 degrees) from its left edge
  EXPECT_EQ(radiance, vec3(1.0f));
}

// The selection power comes from the map's luminance integral over the sphere: it equals the
// Monte Carlo estimate of the same integral with the sampler (an unbiased estimator: E[L / pdf]).
TEST(EnvironmentPower, LuminanceIntegralMatchesTheSamplerEstimate) {
  const Environment env = variedMap(16, 8, 0.3f);
  gEnvBuffer = buildEnvironmentBuffer(env, 0);
  chi2::Uniforms u(4);
  double sum = 0.0, sumSq = 0.0;
  const int n = 400000;
  for (int i = 0; i < n; ++i) {
    float pdf;
    vec3 radiance;
    sampleEnvironment(u.next2(), pdf, radiance);
    const double f = pdf > 0.0f ? double(luminance(radiance)) / pdf : 0.0;
    sum += f;
    sumSq += f * f;
  }
  const double mean = sum / n, sigma = std::sqrt((sumSq / n - mean * mean) / n);
  const double integral = environmentLuminanceIntegral(env);
  std::printf("integral %.6f, estimate %.6f +- %.6f\n", integral, mean, sigma);
  EXPECT_NEAR(mean, integral, 5.0 * sigma + 1e-4 * integral);
  // A uniform map of radiance 1 integrates to the sphere's solid angle (to the row quadrature).
  EXPECT_NEAR(environmentLuminanceIntegral(oneColour(64, 32, vec3(1.0f))), 4.0 * kPi, 4.0 * kPi * 1e-3);
}

// Without an environment the buffer is its header alone and says so.
TEST(EnvironmentBuffer, AbsentEnvironmentIsOnlyAHeader) {
  gEnvBuffer = buildEnvironmentBuffer(Environment{}, 3);
  EXPECT_EQ(gEnvBuffer.size(), size_t(kEnvHeaderFloats));
  EXPECT_FALSE(hasEnvironmentLight());
  gEnvBuffer = buildEnvironmentBuffer(oneColour(4, 2, vec3(1.0f)), -1);
  EXPECT_FALSE(hasEnvironmentLight());
  gEnvBuffer = buildEnvironmentBuffer(oneColour(4, 2, vec3(1.0f)), 2);
  EXPECT_TRUE(hasEnvironmentLight());
  EXPECT_EQ(environmentLight(), 2u);
}

}  // namespace
