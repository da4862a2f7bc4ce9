// Statistical and exact checks of shaders/shared/sampling.h, compiled as C++.
#include <cmath>
#include <cstdio>
#include <ostream>
#include <vector>

#include <gtest/gtest.h>

#include "support/chi2.h"
#include "shared/sampling.h"

namespace {

using namespace mixtrace::shared;
using glm::vec2;
using glm::vec3;

constexpr int kSamples = 1000000;
// Chi-square tests in this executable that are expected to pass; each gets a Šidák share of 1%.
constexpr int kChiSquareTests = 2 + 6 + 6 + 1;
const double kLevel = chi2::sidakLevel(kChiSquareTests);

void expectFits(const chi2::FitResult& fit) {
  std::printf("    p-value %.4f (chi2 %.1f, %d dof), pdf integral %.6f, failed %.6f\n", fit.chi2.pValue,
              fit.chi2.statistic, fit.chi2.dof, fit.pdfIntegral, fit.failureFraction);
  EXPECT_GT(fit.chi2.pValue, kLevel) << "chi2 " << fit.chi2.statistic << " dof " << fit.chi2.dof;
  EXPECT_NEAR(fit.pdfIntegral, 1.0 - fit.failureFraction, chi2::successFractionTolerance(fit));
}

vec3 unitFromAngles(float theta, float phi) {
  return vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

// ---------------------------------------------------------------------------------------------
TEST(OrthonormalBasis, IsOrthonormalRightHandedAndInvertible) {
  chi2::Uniforms uniforms(7);
  std::vector<vec3> normals = {vec3(0, 0, 1), vec3(0, 0, -1), vec3(1, 0, 0), vec3(0, -1, 0),
                               glm::normalize(vec3(1e-4f, 2e-4f, -1.0f)),
                               glm::normalize(vec3(-1e-4f, 0.0f, 1.0f))};
  for (int i = 0; i < 1000; ++i) normals.push_back(sampleUniformSphere(uniforms.next2()));
  for (const vec3& n : normals) {
    const OrthonormalBasis b = makeOrthonormalBasis(n);
    EXPECT_NEAR(glm::length(b.tangent), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(b.bitangent), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(b.tangent, b.bitangent), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(b.tangent, n), 0.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(b.bitangent, n), 0.0f, 1e-5f);
    EXPECT_LT(glm::length(glm::cross(b.tangent, b.bitangent) - n), 1e-5f);
    const vec3 local = toLocal(b, n);
    EXPECT_NEAR(local.z, 1.0f, 1e-5f);
    const vec3 v = sampleUniformSphere(uniforms.next2());
    EXPECT_LT(glm::length(toWorld(b, toLocal(b, v)) - v), 1e-5f);
  }
}

TEST(Colour, LuminanceAndSrgb) {
  EXPECT_NEAR(luminance(vec3(1.0f)), 1.0f, 1e-6f);
  EXPECT_NEAR(luminance(vec3(0.0f, 1.0f, 0.0f)), 0.7152f, 1e-6f);
  EXPECT_EQ(srgbToLinear(0.0f), 0.0f);
  EXPECT_NEAR(srgbToLinear(1.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(srgbToLinear(0.5f), 0.21404f, 1e-4f);
  EXPECT_NEAR(srgbToLinear(0.04f), 0.04f / 12.92f, 1e-7f);
  // The two pieces of the curve meet (continuity at the threshold).
  EXPECT_NEAR(srgbToLinear(0.04045f), srgbToLinear(0.0404501f), 1e-6f);
}

// The rational fit of the power segment against the curve itself, in double: at every 8-bit value
// (what textures hold) and on a fine grid between them.
TEST(Colour, SrgbDecodeMatchesTheCurveAtEveryByteAndBetween) {
  const auto curve = [](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); };
  for (int k = 0; k <= 255; ++k) {
    const double c = k / 255.0;
    const double exact = curve(float(c));
    EXPECT_LE(std::abs(srgbToLinear(float(c)) - exact), 7e-7 * exact) << "byte " << k;
  }
  for (int i = 0; i <= 100000; ++i) {
    const float c = float(i) / 100000.0f;
    const double exact = curve(c);
    ASSERT_LE(std::abs(srgbToLinear(c) - exact), 1.5e-6 * exact + 1e-12) << "c " << c;
  }
}

// ---------------------------------------------------------------------------------------------
TEST(SamplingChi2, CosineHemisphere) {
  const auto fit = chi2::testSamplerAgainstPdf(
      [](chi2::Uniforms& u, vec3& dir) {
        dir = sampleCosineHemisphere(u.next2());
        return dir.z > 0.0f;
      },
      [](vec3 dir) { return double(cosineHemispherePdf(dir.z)); }, 0.5, kSamples, 11);
  expectFits(fit);
  EXPECT_NEAR(fit.pdfIntegral, 1.0, 1e-5);
}

TEST(SamplingChi2, CosineHemisphereSamplesAreUnit) {
  chi2::Uniforms uniforms(3);
  for (int i = 0; i < 10000; ++i) {
    const vec3 d = sampleCosineHemisphere(uniforms.next2());
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
    EXPECT_GE(d.z, 0.0f);
  }
  EXPECT_EQ(sampleConcentricDisk(vec2(0.5f, 0.5f)), vec2(0.0f));
}

TEST(SamplingChi2, UniformSphere) {
  const auto fit = chi2::testSamplerAgainstPdf(
      [](chi2::Uniforms& u, vec3& dir) {
        dir = sampleUniformSphere(u.next2());
        return true;
      },
      [](vec3) { return double(uniformSpherePdf()); }, 0.5, kSamples, 12);
  expectFits(fit);
  EXPECT_NEAR(fit.pdfIntegral, 1.0, 1e-5);
}

// ---------------------------------------------------------------------------------------------
// GGX: the visible-normal distribution and the reflected directions, both against their pdfs.
struct GgxCase {
  float alpha;
  float thetaO;  // polar angle of wo
};

void PrintTo(const GgxCase& c, std::ostream* os) {
  *os << "alpha" << c.alpha << "_thetaO" << c.thetaO;  // no spaces: CTest names cases after it
}

class GgxChi2 : public ::testing::TestWithParam<GgxCase> {};

TEST_P(GgxChi2, VisibleNormals) {
  const GgxCase c = GetParam();
  const vec3 wo = unitFromAngles(c.thetaO, 0.7f);
  const auto fit = chi2::testSamplerAgainstPdf(
      [&](chi2::Uniforms& u, vec3& h) {
        h = sampleGgxVisibleNormal(wo, c.alpha, u.next2());
        return true;
      },
      [&](vec3 h) { return double(ggxVisibleNormalPdf(wo, h, c.alpha)); }, c.alpha, kSamples, 21);
  expectFits(fit);
  // Visible normals always lie on the upper hemisphere and D_wo is normalised.
  EXPECT_EQ(fit.failureFraction, 0.0);
  EXPECT_NEAR(fit.pdfIntegral, 1.0, 1e-4);
}

TEST_P(GgxChi2, ReflectedDirections) {
  const GgxCase c = GetParam();
  const vec3 wo = unitFromAngles(c.thetaO, 2.0f);
  const auto fit = chi2::testSamplerAgainstPdf(
      [&](chi2::Uniforms& u, vec3& wi) {
        wi = reflectAbout(wo, sampleGgxVisibleNormal(wo, c.alpha, u.next2()));
        return wi.z > 0.0f;
      },
      [&](vec3 wi) { return double(ggxReflectionPdf(wo, wi, c.alpha)); }, 2.0 * c.alpha, kSamples, 22,
      {vec3(-wo.x, -wo.y, wo.z)});
  expectFits(fit);
}

INSTANTIATE_TEST_SUITE_P(Cases, GgxChi2,
                         ::testing::Values(GgxCase{kMinAlpha, 0.0f}, GgxCase{0.0025f, 0.9f}, GgxCase{0.0025f, 1.52f}, GgxCase{0.09f, 0.8f},
                                           GgxCase{0.5f, 1.2f}, GgxCase{1.0f, 1.52f}));

TEST(Ggx, DistributionIsNormalisedOverProjectedArea) {
  // The defining property of a microfacet distribution: integral of D(h) h.z over h is 1.
  for (float alpha : {0.01f, 0.2f, 1.0f}) {
    const auto cells = chi2::integrateOverCells(
        chi2::SphereGrid(), [&](vec3 h) { return double(ggxD(h, alpha)) * std::max(h.z, 0.0f); }, alpha);
    double total = 0.0;
    for (double v : cells) total += v;
    EXPECT_NEAR(total, 1.0, 1e-4) << "alpha " << alpha;
  }
}

TEST(Ggx, GrazingAndMinimumAlphaStayFinite) {
  chi2::Uniforms uniforms(5);
  for (float alpha : {kMinAlpha, 0.3f, 1.0f}) {
    for (float z : {1e-6f, 1e-3f, 0.5f, 1.0f}) {
      const vec3 wo = glm::normalize(vec3(std::sqrt(1.0f - z * z), 0.0f, z));
      for (int i = 0; i < 2000; ++i) {
        const vec3 h = sampleGgxVisibleNormal(wo, alpha, uniforms.next2());
        ASSERT_TRUE(std::isfinite(h.x) && std::isfinite(h.y) && std::isfinite(h.z));
        ASSERT_GE(h.z, 0.0f);
        const float pdf = ggxVisibleNormalPdf(wo, h, alpha);
        ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0.0f);
        const vec3 wi = reflectAbout(wo, h);
        const float rpdf = ggxReflectionPdf(wo, wi, alpha);
        ASSERT_TRUE(std::isfinite(rpdf) && rpdf >= 0.0f);
        ASSERT_TRUE(std::isfinite(ggxG1(wo, alpha)));
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Uniform triangle sampling: histogram of barycentrics (b1, b2) on a K x K grid of the unit
// square; a cell below the diagonal holds 2/K^2 of the probability, a cell on it (cut in half)
// 1/K^2, a cell above it none.
TEST(SamplingChi2, UniformTriangle) {
  const int k = 20;
  std::vector<double> observed(k * k, 0.0), expected(k * k, 0.0);
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      expected[i * k + j] = (i + j < k - 1 ? 2.0 : i + j == k - 1 ? 1.0 : 0.0) / (k * k) * kSamples;
  chi2::Uniforms uniforms(31);
  for (int s = 0; s < kSamples; ++s) {
    const vec3 b = sampleTriangleBarycentrics(uniforms.next2());
    ASSERT_NEAR(b.x + b.y + b.z, 1.0f, 1e-6f);
    ASSERT_TRUE(b.x >= 0.0f && b.y >= 0.0f && b.z >= 0.0f);
    const int i = std::min(int(b.y * k), k - 1), j = std::min(int(b.z * k), k - 1);
    observed[i * k + j] += 1.0;
  }
  const auto result = chi2::chiSquareTest(observed, expected);
  EXPECT_GT(result.pValue, kLevel) << "chi2 " << result.statistic << " dof " << result.dof;
}

TEST(Sampling, TrianglePointIsTheBarycentricCombination) {
  const vec3 v0(1, 2, 3), v1(-4, 0, 2), v2(0.5f, 7, -1);
  chi2::Uniforms uniforms(41);
  for (int i = 0; i < 100; ++i) {
    const vec2 u = uniforms.next2();
    const vec3 b = sampleTriangleBarycentrics(u);
    EXPECT_LT(glm::length(sampleTrianglePoint(v0, v1, v2, u) - (b.x * v0 + b.y * v1 + b.z * v2)), 1e-5f);
  }
  EXPECT_EQ(sampleTrianglePoint(v0, v1, v2, vec2(0.0f, 0.0f)), v0);
}

// ---------------------------------------------------------------------------------------------
// The machinery must be able to say no.
TEST(SamplingChi2Power, RejectsAWrongPdf) {
  // GGX visible normals explained by the cosine pdf.
  const vec3 wo = unitFromAngles(0.6f, 0.0f);
  const auto wrongShape = chi2::testSamplerAgainstPdf(
      [&](chi2::Uniforms& u, vec3& h) {
        h = sampleGgxVisibleNormal(wo, 0.5f, u.next2());
        return true;
      },
      [&](vec3 h) { return double(cosineHemispherePdf(h.z)); }, 0.5, kSamples, 51);
  EXPECT_LT(wrongShape.chi2.pValue, 1e-12);

  // A subtly wrong alpha (3% off) is still detected at this sample count.
  const auto wrongAlpha = chi2::testSamplerAgainstPdf(
      [&](chi2::Uniforms& u, vec3& h) {
        h = sampleGgxVisibleNormal(wo, 0.3f, u.next2());
        return true;
      },
      [&](vec3 h) { return double(ggxVisibleNormalPdf(wo, h, 0.3f * 1.03f)); }, 0.3, kSamples, 52);
  EXPECT_LT(wrongAlpha.chi2.pValue, 1e-6);

  // Uniform-sphere samples against the uniform pdf scaled by 1.02.
  const auto wrongScale = chi2::testSamplerAgainstPdf(
      [](chi2::Uniforms& u, vec3& dir) {
        dir = sampleUniformSphere(u.next2());
        return true;
      },
      [](vec3) { return 1.02 * uniformSpherePdf(); }, 0.5, kSamples, 53);
  EXPECT_LT(wrongScale.chi2.pValue, 1e-6);
}

TEST(ChiSquare, PValueMatchesKnownQuantiles) {
  // Reference quantiles of the chi-square distribution.
  EXPECT_NEAR(chi2::chiSquarePValue(3.841459, 1), 0.05, 1e-6);
  EXPECT_NEAR(chi2::chiSquarePValue(18.307038, 10), 0.05, 1e-6);
  EXPECT_NEAR(chi2::chiSquarePValue(135.806723, 100), 0.01, 1e-6);
  // Even dof have a closed form, Q(m, y) = e^-y sum_{i<m} y^i / i!: check both branches of the
  // incomplete gamma (series below a + 1, continued fraction above) at 200 dof.
  for (double x : {180.0, 210.0, 260.0}) {
    const double y = 0.5 * x;
    double term = std::exp(-y), sum = 0.0;
    for (int i = 0; i < 100; ++i) {
      sum += term;
      term *= y / (i + 1);
    }
    EXPECT_NEAR(chi2::chiSquarePValue(x, 200), sum, 1e-9 * std::max(sum, 1e-3)) << x;
  }
  EXPECT_NEAR(chi2::chiSquarePValue(2.0, 2), std::exp(-1.0), 1e-12);
  EXPECT_EQ(chi2::chiSquarePValue(0.0, 5), 1.0);
}

}  // namespace
