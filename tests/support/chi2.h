#pragma once
// Chi-square goodness-of-fit machinery for testing a sampling routine against its pdf (in the
// spirit of the pbrt-v4 and Mitsuba tests): histogram samples over cells of the sphere of
// directions, integrate the pdf over the same cells numerically to get expected counts, pool
// sparse cells, and turn the chi-square statistic into a p-value.
//
// Samples that fail (the sampler reports no direction) form one extra cell whose expected count
// is N (1 - integral of the pdf), so a pdf that does not integrate to the success probability is
// caught by the same test.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include <glm/glm.hpp>

namespace chi2 {

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------------
// Regularised upper incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a): the chi-square survival
// function is Q(dof / 2, statistic / 2). Series for x < a + 1, Lentz's continued fraction above,
// each converging fast in its own region.
inline double regularizedGammaQ(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double logPrefactor = a * std::log(x) - x - std::lgamma(a);
  const double tiny = 1e-300;
  if (x < a + 1.0) {
    // P(a, x) = x^a e^-x / Gamma(a + 1) * sum_n x^n / ((a + 1) ... (a + n))
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 100000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-16) break;
    }
    return std::max(0.0, 1.0 - sum * std::exp(logPrefactor));
  }
  // Q(a, x) = x^a e^-x / Gamma(a) * 1 / (x + 1 - a - 1 (1 - a) / (x + 3 - a - ...))
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int n = 1; n < 100000; ++n) {
    const double an = -n * (n - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return std::min(1.0, std::exp(logPrefactor) * h);
}

inline double chiSquarePValue(double statistic, int dof) {
  return regularizedGammaQ(0.5 * dof, 0.5 * statistic);
}

// ---------------------------------------------------------------------------------------------
// Adaptive Simpson quadrature. `initialIntervals` matters for peaked integrands: Simpson's error
// estimate cannot see a spike that falls between its first five points, so the caller splits the
// domain finely enough that every spike is sampled near its top before adaptivity takes over.
constexpr double kRelativeTolerance = 1e-6;

template <class F>
double simpsonStep(const F& f, double a, double b, double fa, double fm, double fb, double whole,
                   double eps, int depth) {
  const double m = 0.5 * (a + b);
  const double flm = f(0.5 * (a + m)), frm = f(0.5 * (m + b));
  const double left = (m - a) / 6.0 * (fa + 4.0 * flm + fm);
  const double right = (b - m) / 6.0 * (fm + 4.0 * frm + fb);
  const double delta = left + right - whole;
  // Absolute tolerance for the near-empty parts, relative for the peaks (where an absolute one
  // would ask for more digits than matter).
  const double tolerance = std::max(eps, kRelativeTolerance * std::abs(left + right));
  if (depth <= 0 || std::abs(delta) <= 15.0 * tolerance) return left + right + delta / 15.0;
  return simpsonStep(f, a, m, fa, flm, fm, left, 0.5 * eps, depth - 1) +
         simpsonStep(f, m, b, fm, frm, fb, right, 0.5 * eps, depth - 1);
}

template <class F>
double integrateSimpson(const F& f, double a, double b, int initialIntervals, double eps) {
  const int maxDepth = 12;
  double sum = 0.0;
  const double width = (b - a) / initialIntervals;
  double x0 = a, f0 = f(a);
  for (int i = 0; i < initialIntervals; ++i) {
    const double x1 = (i + 1 == initialIntervals) ? b : a + (i + 1) * width;
    const double xm = 0.5 * (x0 + x1);
    const double fm = f(xm), f1 = f(x1);
    const double whole = (x1 - x0) / 6.0 * (f0 + 4.0 * fm + f1);
    sum += simpsonStep(f, x0, x1, f0, fm, f1, whole, eps / initialIntervals, maxDepth);
    x0 = x1;
    f0 = f1;
  }
  return sum;
}

// ---------------------------------------------------------------------------------------------
// The sphere cut into thetaBins x phiBins cells of equal angle (theta from +z, phi from +x).
struct SphereGrid {
  int thetaBins = 10;
  int phiBins = 20;
  int cellCount() const { return thetaBins * phiBins; }
  int cellOf(const glm::dvec3& dir) const {
    const double z = std::clamp(dir.z / glm::length(dir), -1.0, 1.0);
    const double theta = std::acos(z);
    double phi = std::atan2(dir.y, dir.x);
    if (phi < 0.0) phi += 2.0 * kPi;
    const int i = std::min(int(theta / kPi * thetaBins), thetaBins - 1);
    const int j = std::min(int(phi / (2.0 * kPi) * phiBins), phiBins - 1);
    return i * phiBins + j;
  }
};

inline glm::vec3 directionFromAngles(double theta, double phi) {
  const double s = std::sin(theta);
  return glm::vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(std::cos(theta)));
}

// Integral over [a, b] split at the given points (those inside), with about one initial
// interval per `spacing`. A break at the top of a spike puts a quadrature node exactly there.
template <class F>
double integrateWithBreaks(const F& f, double a, double b, const std::vector<double>& breaks,
                           double spacing, double eps) {
  std::vector<double> points = {a};
  for (double x : breaks)
    if (x > a && x < b) points.push_back(x);
  points.push_back(b);
  std::sort(points.begin(), points.end());
  double sum = 0.0;
  for (size_t k = 0; k + 1 < points.size(); ++k) {
    const double length = points[k + 1] - points[k];
    const int intervals = std::clamp(int(std::ceil(length / spacing)), 2, 400);
    sum += integrateSimpson(f, points[k], points[k + 1], intervals, eps * length / (b - a));
  }
  return sum;
}

// Integral of a solid-angle density over each cell. featureAngle: the angular width of the
// narrowest peak of the density (about the GGX alpha for microfacet lobes), which sets how
// finely the quadrature starts out. peaks: directions where the density has narrow maxima (e.g.
// the mirror direction of a glossy lobe); the quadrature puts nodes on their theta and phi, a
// safeguard for lobes squeezed narrower than featureAngle in one direction (glossy reflection at
// grazing incidence is thin in azimuth) that the initial spacing alone might step over.
inline std::vector<double> integrateOverCells(const SphereGrid& grid,
                                              const std::function<double(glm::vec3)>& density,
                                              double featureAngle,
                                              const std::vector<glm::vec3>& peaks = {},
                                              double eps = 1e-7) {
  const double dTheta = kPi / grid.thetaBins, dPhi = 2.0 * kPi / grid.phiBins;
  std::vector<double> thetaBreaks, phiBreaks;
  for (const glm::vec3& p : peaks) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(p));
    thetaBreaks.push_back(std::acos(std::clamp(d.z, -1.0, 1.0)));
    double phi = std::atan2(d.y, d.x);
    phiBreaks.push_back(phi < 0.0 ? phi + 2.0 * kPi : phi);
  }
  // Initial spacing of twice the feature angle: a spike of that width is then sampled within
  // half its width of its top. A phi interval at polar angle theta spans dPhi sin(theta).
  const double spacing = 2.0 * featureAngle;
  std::vector<double> integrals(grid.cellCount());
  for (int i = 0; i < grid.thetaBins; ++i) {
    for (int j = 0; j < grid.phiBins; ++j) {
      const double phi0 = j * dPhi, phi1 = (j + 1) * dPhi;
      auto overPhi = [&](double theta) {
        const double s = std::sin(theta);
        if (s == 0.0) return 0.0;
        auto atPhi = [&](double phi) { return density(directionFromAngles(theta, phi)); };
        // The inner error, integrated over the theta range, stays at a tenth of the outer
        // tolerance, so the outer recursion does not chase it as if it were structure.
        return s * integrateWithBreaks(atPhi, phi0, phi1, phiBreaks, spacing / s, 0.1 * eps / dTheta);
      };
      integrals[i * grid.phiBins + j] =
          integrateWithBreaks(overPhi, i * dTheta, (i + 1) * dTheta, thetaBreaks, spacing, eps);
    }
  }
  return integrals;
}

// ---------------------------------------------------------------------------------------------
// Uniform floats in [0, 1) from a fixed-seed Mersenne Twister, 24 bits like rng.h (so never 1).
// std::uniform_real_distribution is avoided: its output differs between standard libraries.
class Uniforms {
 public:
  explicit Uniforms(uint32_t seed) : engine_(seed) {}
  float next() { return float(engine_() >> 8) * (1.0f / 16777216.0f); }
  glm::vec2 next2() {
    const float a = next();
    return glm::vec2(a, next());
  }

 private:
  std::mt19937 engine_;
};

// One draw: returns false for a failed sample, else the direction in `dir`.
using DirectionSampler = std::function<bool(Uniforms&, glm::vec3& dir)>;

struct Histogram {
  std::vector<double> counts;  // per cell
  double failures = 0.0;
  int total = 0;
};

inline Histogram histogramSamples(const SphereGrid& grid, const DirectionSampler& sample,
                                  int sampleCount, uint32_t seed) {
  Histogram histogram;
  histogram.counts.assign(grid.cellCount(), 0.0);
  histogram.total = sampleCount;
  Uniforms uniforms(seed);
  for (int k = 0; k < sampleCount; ++k) {
    glm::vec3 dir;
    if (sample(uniforms, dir))
      histogram.counts[grid.cellOf(glm::dvec3(dir))] += 1.0;
    else
      histogram.failures += 1.0;
  }
  return histogram;
}

struct ChiSquareResult {
  double statistic = 0.0;
  int dof = 0;
  double pValue = 0.0;
};

// Pearson's test of observed against expected counts. Cells expected below 5 are pooled into one
// (the chi-square approximation needs them); a count where exactly nothing is expected is an
// outright failure.
inline ChiSquareResult chiSquareTest(const std::vector<double>& observed, const std::vector<double>& expected) {
  const double kMinExpected = 5.0;
  std::vector<size_t> order(observed.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });

  ChiSquareResult result;
  double pooledObserved = 0.0, pooledExpected = 0.0;
  int cells = 0;
  for (size_t i : order) {
    if (expected[i] <= 0.0 && observed[i] > 0.0) {
      result.statistic = HUGE_VAL;
      result.pValue = 0.0;
      return result;
    }
    if (expected[i] < kMinExpected || (pooledExpected > 0.0 && pooledExpected < kMinExpected)) {
      // Sorted ascending, so the pool absorbs the sparse cells and, if they do not reach the
      // threshold together, the next (smallest) regular cell too.
      pooledObserved += observed[i];
      pooledExpected += expected[i];
      continue;
    }
    const double diff = observed[i] - expected[i];
    result.statistic += diff * diff / expected[i];
    ++cells;
  }
  if (pooledExpected > 0.0) {
    const double diff = pooledObserved - pooledExpected;
    result.statistic += diff * diff / pooledExpected;
    ++cells;
  }
  result.dof = std::max(cells - 1, 1);
  result.pValue = chiSquarePValue(result.statistic, result.dof);
  return result;
}

// Everything one goodness-of-fit case produces.
struct FitResult {
  ChiSquareResult chi2;
  double pdfIntegral = 0.0;      // integral of the pdf over the sphere
  double failureFraction = 0.0;  // failed samples / samples
  int sampleCount = 0;
};

inline FitResult testSamplerAgainstPdf(const DirectionSampler& sample,
                                       const std::function<double(glm::vec3)>& pdf,
                                       double featureAngle, int sampleCount, uint32_t seed,
                                       const std::vector<glm::vec3>& peaks = {},
                                       SphereGrid grid = SphereGrid()) {
  FitResult fit;
  fit.sampleCount = sampleCount;
  const Histogram histogram = histogramSamples(grid, sample, sampleCount, seed);
  std::vector<double> expected = integrateOverCells(grid, pdf, featureAngle, peaks);
  for (double& e : expected) {
    fit.pdfIntegral += e;
    e *= sampleCount;
  }
  fit.failureFraction = histogram.failures / sampleCount;
  std::vector<double> observed = histogram.counts;
  // The failure cell. Clamped: quadrature error can push the integral a hair above 1.
  observed.push_back(histogram.failures);
  expected.push_back(std::max(0.0, 1.0 - fit.pdfIntegral) * sampleCount);
  fit.chi2 = chiSquareTest(observed, expected);
  return fit;
}

// Tolerance for comparing the pdf integral with the observed success fraction: 5 binomial
// standard deviations plus room for the quadrature.
inline double successFractionTolerance(const FitResult& fit) {
  const double p = std::clamp(fit.failureFraction, 1.0 / fit.sampleCount, 1.0);
  return 5.0 * std::sqrt(p * (1.0 - p) / fit.sampleCount) + 1e-4;
}

// Šidák-corrected significance level for one of `testCount` tests at an overall level of 1%.
inline double sidakLevel(int testCount) {
  return 1.0 - std::pow(1.0 - 0.01, 1.0 / testCount);
}

}  // namespace chi2
