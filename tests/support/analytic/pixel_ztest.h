#pragma once
// Compares a rendered image with a computed expectation, pixel channel by pixel channel, using
// the renderer's own estimate of the variance of each pixel mean:
//   z = max(0, |measured - expected| - tolerance) / sqrt(variance)
// against a Bonferroni-corrected quantile (family-wise false alarm rate `familyAlpha` over all
// compared channels) of Student's t with spp - 1 degrees of freedom, since the variance is
// estimated from the same samples as the mean (at 128 spp and z ~ 5 the normal quantile would
// be too small by ~5%), plus the same test on the image mean, which is far more sensitive to a
// small bias than any single pixel. `tolerance` = relTolerance * |expected| absorbs the known
// modelling error of the expectation (tessellation, quadrature, float arithmetic); a channel with
// zero variance (every sample identical) must match within that tolerance alone.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "output/image.h"

namespace mixtrace::testing::analytic {

struct Expectation {
  Image value;                  // expected pixel means
  std::vector<uint8_t> tested;  // per pixel: 1 = compared, 0 = left out (e.g. a pixel straddling an edge)
  Expectation() = default;
  Expectation(int w, int h) : value(w, h), tested(size_t(w) * size_t(h), 1) {}
};

// z with P(|N(0,1)| > z) = p, by bisection on erfc (monotone, no tables).
inline double twoSidedNormalQuantile(double p) {
  double lo = 0.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::sqrt(2.0)) > p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Student's t quantile for the same two-sided tail, by the Cornish-Fisher expansion around the
// normal quantile (Abramowitz & Stegun 26.7.5); accurate to well under 1% for dof >= 30.
inline double twoSidedStudentQuantile(double p, double dof) {
  const double z = twoSidedNormalQuantile(p);
  const double z3 = z * z * z, z5 = z3 * z * z, z7 = z5 * z * z;
  return z + (z3 + z) / (4.0 * dof) + (5.0 * z5 + 16.0 * z3 + 3.0 * z) / (96.0 * dof * dof) +
         (3.0 * z7 + 19.0 * z5 + 17.0 * z3 - 15.0 * z) / (384.0 * dof * dof * dof);
}

struct ZTestResult {
  size_t channels = 0;   // pixel channels compared
  size_t leftOut = 0;    // pixels not compared
  size_t failures = 0;   // channels beyond the threshold
  double threshold = 0.0;
  double worstZ = 0.0;
  int worstX = -1, worstY = -1, worstChannel = -1;
  double measuredMean = 0.0, expectedMean = 0.0;
  double meanZ = 0.0;    // excess z of the image mean (0 when within the tolerance)
  double rawMeanZ = 0.0; // signed z of the image mean ignoring the tolerance (for the log)
  double meanThreshold = 0.0;
  bool passed() const { return failures == 0 && meanZ <= meanThreshold; }
  std::string summary() const {
    std::ostringstream s;
    s << failures << " of " << channels << " pixel channels beyond z " << threshold << " (" << leftOut
      << " pixels left out; worst z " << worstZ << " at (" << worstX << ", " << worstY << ") channel " << worstChannel
      << "); image mean " << measuredMean << " vs expected " << expectedMean << " (relative "
      << (expectedMean != 0.0 ? measuredMean / expectedMean - 1.0 : 0.0) << ", z " << rawMeanZ << ", excess z " << meanZ
      << ", threshold " << meanThreshold << ")";
    return s.str();
  }
};

// `scale` multiplies the expectation: the tests pass 1.05 / 0.95 to show that the check rejects
// an expectation 5% off, i.e. that it has the power to see a real bias of that size.
inline ZTestResult zTest(const Image& mean, const Image& variance, int spp, const Expectation& e, double relTolerance,
                         double scale = 1.0, double familyAlpha = 1e-3) {
  ZTestResult r;
  const size_t pixels = e.value.pixelCount();
  for (size_t p = 0; p < pixels; ++p)
    if (e.tested[p]) r.channels += 3; else ++r.leftOut;
  r.threshold = twoSidedStudentQuantile(familyAlpha / double(std::max<size_t>(r.channels, 1)), std::max(spp - 1, 30));
  // The image mean pools many pixels: normal, at a single-test rate.
  r.meanThreshold = twoSidedNormalQuantile(1e-4);
  double diffSum = 0.0, varSum = 0.0, expectedSum = 0.0, measuredSum = 0.0, toleranceSum = 0.0;
  for (size_t p = 0; p < pixels; ++p) {
    if (!e.tested[p]) continue;
    for (int c = 0; c < 3; ++c) {
      const size_t i = 3 * p + c;
      const double expected = scale * double(e.value.rgb[i]);
      const double measured = mean.rgb[i];
      const double var = double(variance.rgb[i]) * variance.rgb[i];  // readExr gives standard errors
      const double tolerance = relTolerance * std::abs(expected) + 1e-7;
      const double excess = std::max(0.0, std::abs(measured - expected) - tolerance);
      const double z = var > 0.0 ? excess / std::sqrt(var) : (excess > 0.0 ? 1e30 : 0.0);
      if (!(z <= r.threshold)) ++r.failures;  // NaN fails too
      if (!(z <= r.worstZ)) {
        r.worstZ = z;
        r.worstX = int(p % size_t(e.value.width));
        r.worstY = int(p / size_t(e.value.width));
        r.worstChannel = c;
      }
      diffSum += measured - expected;
      varSum += var;
      expectedSum += expected;
      measuredSum += measured;
      toleranceSum += tolerance;
    }
  }
  const double n = double(std::max<size_t>(r.channels, 1));
  r.measuredMean = measuredSum / n;
  r.expectedMean = expectedSum / n;
  const double excess = std::max(0.0, std::abs(diffSum) - toleranceSum) / n;
  const double sigma = std::sqrt(varSum) / n;
  r.meanZ = sigma > 0.0 ? excess / sigma : (excess > 0.0 ? 1e30 : 0.0);
  r.rawMeanZ = sigma > 0.0 ? diffSum / n / sigma : 0.0;
  if (!std::isfinite(diffSum)) r.meanZ = 1e30;
  return r;
}

}  // namespace mixtrace::testing::analytic
