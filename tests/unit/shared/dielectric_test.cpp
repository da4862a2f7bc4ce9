// Glass (shaders/shared/dielectric.h through bsdf.h, compiled as C++): the sampler against the pdf
// by chi-square over the whole sphere, at several roughness values and IORs, entering and leaving
// a volume and thin-walled, alone and mixed with the opaque lobes; smooth glass against Snell's law
// and the Fresnel equations; energy (R + T, with the radiance scale undone, is at most 1 and 1 for
// smooth glass); and finite values everywhere.
#include <cmath>
#include <cstdio>
#include <ostream>

#include <gtest/gtest.h>

#include "support/bsdf_sampler.h"
#include "support/chi2.h"
#include "shared/bsdf.h"

namespace {

using namespace mixtrace::shared;
using mixtrace::testing::bsdfSampler;
using glm::vec2;
using glm::vec3;

constexpr int kSamples = 1000000;

struct GlassCase {
  float roughness;
  float ior;
  bool thin;
  bool fromInside;
  float thetaO;
  float transmission = 1.0f;
  float metallic = 0.0f;
};

void PrintTo(const GlassCase& c, std::ostream* os) {
  *os << "roughness" << c.roughness << "_ior" << c.ior << (c.thin ? "_thin" : "_volume")
      << (c.fromInside ? "_inside" : "_outside") << "_thetaO" << c.thetaO << "_transmission" << c.transmission
      << "_metallic" << c.metallic;
}

const GlassCase kCases[] = {
    {0.1f, 1.5f, false, false, 0.4f},
    {0.1f, 1.5f, false, true, 0.4f},            // leaving the volume, below the critical angle
    {0.3f, 1.5f, false, true, 0.9f},            // beyond the critical angle (41.8 deg): mostly reflected
    {0.3f, 1.33f, false, false, 1.2f},
    {0.3f, 2.4f, false, true, 0.2f},
    {0.6f, 1.5f, false, false, 0.8f},
    {1.0f, 1.5f, false, true, 0.5f},
    {0.2f, 1.5f, true, false, 0.6f},
    {0.6f, 1.2f, true, true, 1.3f},
    {0.3f, 1.5f, false, false, 0.7f, 0.5f, 0.0f},    // half glass, half opaque dielectric
    {0.4f, 1.45f, false, true, 0.7f, 0.8f, 0.3f},    // glass, dielectric and metal
};
constexpr int kChiSquareTests = sizeof(kCases) / sizeof(kCases[0]);
const double kLevel = chi2::sidakLevel(kChiSquareTests);

vec3 directionAt(float theta, float phi) {
  return vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

BsdfParams glass(const GlassCase& c) {
  return withTransmission(makeBsdfParams(vec3(1.0f), c.metallic, c.roughness), c.transmission, c.ior, c.thin,
                          c.fromInside);
}

// Where the lobes peak: the mirror direction and the macro-surface transmission direction.
std::vector<vec3> peaksOf(const BsdfParams& m, const vec3& wo) {
  std::vector<vec3> peaks = {vec3(-wo.x, -wo.y, wo.z)};
  vec3 t;
  if (m.thin) peaks.push_back(-wo);
  else if (refractAbout(wo, vec3(0.0f, 0.0f, 1.0f), m.eta, t)) peaks.push_back(t);
  return peaks;
}

class GlassChi2 : public ::testing::TestWithParam<GlassCase> {};

TEST_P(GlassChi2, SamplesFollowThePdfOverTheSphere) {
  const GlassCase c = GetParam();
  const BsdfParams m = glass(c);
  const vec3 wo = directionAt(c.thetaO, 0.4f);
  const auto fit = chi2::testSamplerAgainstPdf(
      bsdfSampler(m, wo), [&](vec3 wi) { return double(bsdfPdf(m, wo, wi)); }, 2.0 * m.alpha, kSamples, 4321,
      peaksOf(m, wo));
  std::printf("    eta %.3f: p-value %.4f (chi2 %.1f, %d dof), pdf integral %.6f, failed %.6f\n", m.eta,
              fit.chi2.pValue, fit.chi2.statistic, fit.chi2.dof, fit.pdfIntegral, fit.failureFraction);
  EXPECT_GT(fit.chi2.pValue, kLevel) << "chi2 " << fit.chi2.statistic << " dof " << fit.chi2.dof;
  EXPECT_LE(fit.pdfIntegral, 1.0 + 1e-4);
  EXPECT_NEAR(fit.pdfIntegral, 1.0 - fit.failureFraction, chi2::successFractionTolerance(fit));
}

INSTANTIATE_TEST_SUITE_P(Cases, GlassChi2, ::testing::ValuesIn(kCases));

// The same machinery notices a transmission lobe that is slightly off: the pdf of an IOR 2 %
// higher than the sampler's.
TEST(GlassChi2Power, RejectsTheWrongIor) {
  const GlassCase c{0.2f, 1.5f, false, false, 0.6f};
  const BsdfParams m = glass(c);
  BsdfParams wrong = m;
  wrong.eta = 1.53f;
  const vec3 wo = directionAt(c.thetaO, 0.4f);
  const auto fit = chi2::testSamplerAgainstPdf(
      bsdfSampler(m, wo), [&](vec3 wi) { return double(bsdfPdf(wrong, wo, wi)); }, 2.0 * m.alpha, kSamples, 77,
      peaksOf(m, wo));
  EXPECT_LT(fit.chi2.pValue, 1e-6);
}

// ---------------------------------------------------------------------------------------------
TEST(Dielectric, FresnelMatchesTheEquationsAndTotalInternalReflection) {
  // Normal incidence: ((eta - 1) / (eta + 1))^2 from either side.
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.5f), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f / 1.5f), 0.04f, 1e-6f);
  // Brewster's angle atan(1.5): the parallel part vanishes, R = Rs / 2 = 0.0739 (tabulated).
  EXPECT_NEAR(fresnelDielectric(std::cos(std::atan(1.5f)), 1.5f), 0.0739f, 2e-4f);
  // Beyond the critical angle asin(1 / 1.5) = 41.8 deg from inside: everything reflects.
  EXPECT_EQ(fresnelDielectric(std::cos(0.74f), 1.0f / 1.5f), 1.0f);
  EXPECT_LT(fresnelDielectric(std::cos(0.72f), 1.0f / 1.5f), 1.0f);
  // Grazing: everything reflects.
  EXPECT_NEAR(fresnelDielectric(0.0f, 1.5f), 1.0f, 1e-6f);
}

// Smooth glass (roughness 0, alpha kMinAlpha): samples leave along Snell's and the mirror's
// directions, transmitted with probability 1 - F and a weight of 1 / eta^2 (radiance).
TEST(Dielectric, SmoothGlassFollowsSnellAndFresnel) {
  for (const bool inside : {false, true}) {
    const float ior = 1.5f;
    const BsdfParams m = withTransmission(makeBsdfParams(vec3(1.0f), 0.0f, 0.0f), 1.0f, ior, false, inside);
    const float thetaO = 0.5f;   // below the critical angle from inside too
    const vec3 wo = directionAt(thetaO, 0.0f);
    const float eta = inside ? 1.0f / ior : ior;
    const float sinT = std::sin(thetaO) / eta;
    const vec3 snell(-sinT, 0.0f, -std::sqrt(1.0f - sinT * sinT));
    const vec3 mirror(-wo.x, -wo.y, wo.z);
    chi2::Uniforms u(5);
    int reflected = 0, transmitted = 0, astray = 0, close = 0;
    double transmittedWeight = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      vec3 wi;
      float pdf;
      if (!bsdfSample(m, wo, u.next2(), u.next(), wi, pdf)) continue;
      const vec3 f = bsdfEval(m, wo, wi);
      if (wi.z > 0.0f) {
        ++reflected;
        astray += glm::length(wi - mirror) > 0.1f;
        close += glm::length(wi - mirror) < 0.01f;
      } else {
        ++transmitted;
        astray += glm::length(wi - snell) > 0.1f;
        close += glm::length(wi - snell) < 0.01f;
        transmittedWeight += f.x * -wi.z / pdf;
      }
    }
    const double fresnel = fresnelDielectric(std::cos(thetaO), eta);
    const double expected = fresnel * n;
    EXPECT_NEAR(reflected, expected, 5.0 * std::sqrt(expected)) << "inside " << inside;
    // The weight of a transmission is G2 / G1 / eta^2 ~ 1 / eta^2 for a near-mirror.
    EXPECT_NEAR(transmittedWeight / transmitted, 1.0 / (eta * eta), 0.01 / (eta * eta)) << "inside " << inside;
    EXPECT_GT(reflected + transmitted, n * 0.999);
    // GGX at alpha 0.002 is narrow with heavy tails (P(theta_m > t) = a^2 / (a^2 + tan^2 t)):
    // most directions within 0.01 rad, a fraction of a percent beyond 0.1 rad.
    EXPECT_GT(close, n * 3 / 4) << "inside " << inside;
    EXPECT_LT(astray, n / 200) << "inside " << inside;
  }
}

// Hemispherical-spherical albedo of white glass by quadrature over the sphere: reflection plus
// transmission, the latter times eta^2 to undo radiance's 1 / eta^2 (what is left is the energy
// that crosses). At most 1 for every roughness, side and angle (single-scattering microfacets
// lose the energy of their inter-reflections, more the rougher), and 1 for smooth glass.
double glassEnergy(const BsdfParams& m, const vec3& wo) {
  chi2::SphereGrid grid;
  grid.thetaBins = 8;
  grid.phiBins = 8;
  const double crossing = m.thin ? 1.0 : double(m.eta) * m.eta;
  const auto cells = chi2::integrateOverCells(
      grid,
      [&](vec3 wi) {
        const double f = bsdfEval(m, wo, wi).x * std::abs(wi.z);
        return wi.z < 0.0f ? f * crossing : f;
      },
      2.0 * m.alpha, peaksOf(m, wo), 1e-6);
  double total = 0.0;
  for (double c : cells) total += c;
  return total;
}

TEST(Dielectric, WhiteGlassConservesEnergy) {
  for (const bool thin : {false, true}) {
    for (const bool inside : {false, true}) {
      for (const float roughness : {0.05f, 0.3f, 0.6f, 1.0f}) {
        for (const float thetaO : {0.0f, 0.6f, 1.2f}) {
          const BsdfParams m = withTransmission(makeBsdfParams(vec3(1.0f), 0.0f, roughness), 1.0f, 1.5f, thin, inside);
          const double e = glassEnergy(m, directionAt(thetaO, 0.0f));
          EXPECT_LE(e, 1.0 + 2e-3) << "thin " << thin << " inside " << inside << " roughness " << roughness
                                   << " theta " << thetaO;
          // Single scattering keeps most of it at moderate roughness.
          if (roughness <= 0.3f && thetaO < 1.0f)
            EXPECT_GT(e, 0.95) << "thin " << thin << " inside " << inside << " roughness " << roughness
                               << " theta " << thetaO;
        }
      }
    }
  }
  // Near-smooth glass keeps all of it.
  const BsdfParams smooth = withTransmission(makeBsdfParams(vec3(1.0f), 0.0f, 0.05f), 1.0f, 1.5f, false, false);
  EXPECT_NEAR(glassEnergy(smooth, directionAt(0.3f, 0.0f)), 1.0, 5e-3);
}

// A black base colour keeps the glass's reflection and absorbs its transmission.
TEST(Dielectric, BaseColourTintsTransmissionOnly) {
  const BsdfParams clear = withTransmission(makeBsdfParams(vec3(1.0f), 0.0f, 0.3f), 1.0f, 1.5f, false, false);
  const BsdfParams tinted = withTransmission(makeBsdfParams(vec3(0.2f, 0.5f, 1.0f), 0.0f, 0.3f), 1.0f, 1.5f, false, false);
  const vec3 wo = directionAt(0.5f, 0.0f);
  const vec3 up = directionAt(0.5f, 3.14159265f);
  const vec3 down = -directionAt(0.35f, 0.0f);   // near Snell's direction (0.325 rad)
  EXPECT_EQ(bsdfEval(clear, wo, up), bsdfEval(tinted, wo, up));
  const vec3 a = bsdfEval(clear, wo, down), b = bsdfEval(tinted, wo, down);
  ASSERT_GT(a.x, 0.0f);
  EXPECT_NEAR(b.x / a.x, 0.2f, 1e-5f);
  EXPECT_NEAR(b.y / a.y, 0.5f, 1e-5f);
  EXPECT_NEAR(b.z / a.z, 1.0f, 1e-5f);
}

// KHR_materials_ior alone changes the opaque dielectric's F0: ((ior - 1) / (ior + 1))^2.
TEST(Dielectric, IorSetsTheOpaqueDielectricsF0) {
  const BsdfParams plain = makeBsdfParams(vec3(0.0f), 0.0f, 0.3f);
  const BsdfParams dense = withTransmission(plain, 0.0f, 2.0f, true, false);
  EXPECT_NEAR(dense.f0, 1.0f / 9.0f, 1e-6f);
  const vec3 wo = directionAt(0.2f, 0.0f), wi = directionAt(0.2f, 3.14159265f);
  EXPECT_NEAR(bsdfEval(dense, wo, wi).x / bsdfEval(plain, wo, wi).x, (1.0f / 9.0f) / 0.04f, 0.01f);
  EXPECT_EQ(bsdfEval(dense, wo, -wi), vec3(0.0f)) << "no transmission without the extension";
}

TEST(Dielectric, FiniteEverywhere) {
  chi2::Uniforms u(23);
  for (const bool thin : {false, true})
    for (const bool inside : {false, true})
      for (const float roughness : {0.0f, 0.05f, 0.5f, 1.0f})
        for (const float ior : {1.0f, 1.01f, 1.5f, 3.0f}) {
          if (!thin && ior < kMinVolumeIor) continue;   // the loader keeps volumes above it
          const BsdfParams m = withTransmission(makeBsdfParams(vec3(0.7f), 0.0f, roughness), 1.0f, ior, thin, inside);
          for (const float z : {1e-6f, 1e-4f, 0.05f, 0.7f, 1.0f}) {
            const vec3 wo(std::sqrt(1.0f - z * z), 0.0f, z);
            for (int i = 0; i < 3000; ++i) {
              vec3 wi;
              float pdf = 0.0f;
              const bool ok = bsdfSample(m, wo, u.next2(), u.next(), wi, pdf);
              ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0.0f);
              if (!ok) continue;
              ASSERT_NEAR(glm::length(wi), 1.0f, 1e-4f);
              ASSERT_EQ(pdf, bsdfPdf(m, wo, wi));
              const vec3 f = bsdfEval(m, wo, wi);
              for (int k = 0; k < 3; ++k) ASSERT_TRUE(std::isfinite(f[k]) && f[k] >= 0.0f);
              ASSERT_TRUE(std::isfinite(f.x * std::abs(wi.z) / pdf)) << "thin " << thin << " ior " << ior;
            }
            for (const vec3 wi : {vec3(-wo.x, 0.0f, -z), vec3(0.0f, 0.0f, -1.0f), -wo}) {
              ASSERT_TRUE(std::isfinite(bsdfEval(m, wo, wi).x) && std::isfinite(bsdfPdf(m, wo, wi)));
            }
          }
        }
}

}  // namespace
