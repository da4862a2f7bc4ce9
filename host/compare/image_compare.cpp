#include "compare/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "output/exr_io.h"
#include "util/error.h"
#include "util/log.h"

namespace mixtrace {
namespace {

// Relative tolerance for values whose variance is exactly 0 in both images (float round-off in
// accumulation order is the only legitimate difference there).
constexpr double kExactRelativeTolerance = 1e-5;
// Relative difference that never fails the per-pixel test, whatever the variance estimate: the
// GPU film accumulates a running mean in float, which drifts by 1-3e-5 (relative) over 2048
// samples of a constant pixel (a directly seen emitter), where the variance estimate is itself
// round-off (measured: 312.5016 vs 312.5055 with sd 1e-4, CPU double vs GPU float).
constexpr double kRoundOffRelativeTolerance = 1e-4;
// Default per-pixel allowance for heavy-tailed outliers (see the header).
constexpr double kDefaultFailFraction = 1e-3;
constexpr size_t kMinimumAllowedFailures = 2;
// Fraction of largest per-pixel errors dropped by relMSE (docs/estimator.md §8) and its denominator
// floor.
constexpr double kRelMseTrimFraction = 1e-3;
constexpr double kRelMseEpsilon = 1e-4;
// Below this many samples per pixel the per-pixel z-scores follow Student-t tails with a handful
// of degrees of freedom (the variance itself is estimated from a few samples), and the default
// allowance is exceeded on unbiased renders (measured: 4 spp fails on most shipped scenes,
// 16 spp on none). We warn rather than refuse.
constexpr int kReliableSpp = 16;

bool agreeExactly(double a, double b) {
  return std::abs(a - b) <= kExactRelativeTolerance * std::max(std::abs(a), std::abs(b));
}

std::string sizeText(const Image& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height);
}

bool sameSize(const Image& x, const Image& y) {
  return x.width == y.width && x.height == y.height && x.rgb.size() == y.rgb.size();
}

void checkInputs(const Image& a, const Image& varA, const Image& b, const Image& varB) {
  if (!sameSize(a, b))
    throw Error("cannot compare images of different sizes (" + sizeText(a) + " and " + sizeText(b) + ")");
  if (a.rgb.size() != a.pixelCount() * 3) throw Error("malformed image: pixel data does not match its size");
  const Image* variances[2] = {&varA, &varB};
  const char* names[2] = {"first", "second"};
  for (int i = 0; i < 2; ++i) {
    if (variances[i]->width == 0 || variances[i]->rgb.empty())
      throw Error(std::string("the ") + names[i] +
                  " image has no variance channels (render it with --variance to compare)");
    if (!sameSize(*variances[i], a))
      throw Error(std::string("the ") + names[i] + " image's variance is " + sizeText(*variances[i]) +
                  ", not " + sizeText(a));
  }
}

}  // namespace

double normalUpperQuantile(double p) {
  if (!(p > 0.0 && p < 1.0)) throw Error("normal quantile needs a probability in (0, 1)");
  // P(Z > z) = erfc(z / sqrt 2) / 2 decreases monotonically in z; bisect until the interval stops
  // shrinking. erfc keeps full relative precision in the upper tail, which is where the corrected
  // thresholds live (p ~ 1e-6 .. 1e-9). |z| <= 38 covers every p representable above 1e-300.
  double lo = -38.5, hi = 38.5;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    if (0.5 * std::erfc(mid / std::sqrt(2.0)) > p) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

double sidakTwoSidedThreshold(double alpha, size_t tests) {
  if (!(alpha > 0.0 && alpha < 1.0)) throw Error("significance alpha must be in (0, 1)");
  tests = std::max<size_t>(tests, 1);
  // 1 - (1 - alpha)^(1/n) without cancellation for large n.
  const double perTest = -std::expm1(std::log1p(-alpha) / double(tests));
  return normalUpperQuantile(0.5 * perTest);
}

std::vector<double> relativeSquaredErrors(const Image& image, const Image& reference) {
  if (!sameSize(image, reference))
    throw Error("cannot compare images of different sizes (" + sizeText(image) + " and " + sizeText(reference) +
                ")");
  const size_t pixels = image.pixelCount();
  std::vector<double> perPixel(pixels);
  for (size_t p = 0; p < pixels; ++p) {
    double sum = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double img = image.rgb[3 * p + c], ref = reference.rgb[3 * p + c];
      sum += (img - ref) * (img - ref) / (ref * ref + kRelMseEpsilon);
    }
    perPixel[p] = sum / 3.0;
  }
  return perPixel;
}

double relativeMse(const Image& image, const Image& reference) {
  std::vector<double> perPixel = relativeSquaredErrors(image, reference);
  const size_t pixels = perPixel.size();
  if (pixels == 0) return 0.0;
  // Drop the largest 0.1%: a handful of fireflies would otherwise dominate the mean. NaN errors
  // sort as largest (so they are dropped first) by treating them as +infinity.
  for (double& e : perPixel)
    if (std::isnan(e)) e = INFINITY;
  const size_t dropped = static_cast<size_t>(std::floor(kRelMseTrimFraction * double(pixels)));
  const size_t kept = pixels - dropped;
  std::nth_element(perPixel.begin(), perPixel.begin() + (kept - 1), perPixel.end());
  double total = 0.0;
  for (size_t i = 0; i < kept; ++i) total += perPixel[i];
  return total / double(kept);
}

ComparisonResult compareImages(const Image& a, const Image& seA, const Image& b, const Image& seB, double alpha,
                               double maxFailFraction) {
  checkInputs(a, seA, b, seB);
  if (!(alpha > 0.0 && alpha < 1.0)) throw Error("significance alpha must be in (0, 1)");
  if (maxFailFraction > 1.0) throw Error("the tolerated fail fraction must be in [0, 1]");

  ComparisonResult r;
  r.width = a.width;
  r.height = a.height;
  r.alpha = alpha;
  r.pixels = a.pixelCount();
  r.channels = 3 * r.pixels;
  r.zThreshold = sidakTwoSidedThreshold(alpha, r.channels);
  r.meanZThreshold = sidakTwoSidedThreshold(alpha, 3);
  r.allowedFailures = maxFailFraction >= 0.0
                          ? static_cast<size_t>(std::floor(maxFailFraction * double(r.channels)))
                          : std::max(kMinimumAllowedFailures,
                                     static_cast<size_t>(std::floor(kDefaultFailFraction * double(r.channels))));

  double sumA[3] = {0, 0, 0}, sumB[3] = {0, 0, 0}, sumVar[3] = {0, 0, 0};
  for (size_t i = 0; i < r.channels; ++i) {
    // The inputs are standard errors (exr_io.h); squared in double, which holds the square of
    // any float, so images of 1e20 or 1e-30 are compared as well as images of 1.
    const double x = a.rgb[i], y = b.rgb[i], sx = seA.rgb[i], sy = seB.rgb[i], vx = sx * sx, vy = sy * sy;
    const int c = static_cast<int>(i % 3);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(sx) || !std::isfinite(sy) || sx < 0.0 ||
        sy < 0.0) {
      ++r.nonFinite;
      ++r.failed;
      continue;  // kept out of the image means, which it would otherwise poison
    }
    sumA[c] += x;
    sumB[c] += y;
    sumVar[c] += vx + vy;
    const double v = vx + vy;
    const bool withinRoundOff = std::abs(x - y) <= kRoundOffRelativeTolerance * std::max(std::abs(x), std::abs(y));
    const bool fails = v > 0.0 ? std::abs(x - y) > r.zThreshold * std::sqrt(v) && !withinRoundOff : !agreeExactly(x, y);
    if (fails) ++r.failed;
  }
  r.failFraction = r.channels ? double(r.failed) / double(r.channels) : 0.0;
  r.pixelTestPassed = r.failed <= r.allowedFailures && r.nonFinite == 0;

  r.meanTestPassed = true;
  const double n = double(std::max<size_t>(r.pixels, 1));
  for (int c = 0; c < 3; ++c) {
    r.meanA[c] = sumA[c] / n;
    r.meanB[c] = sumB[c] / n;
    if (sumB[c] != 0.0) r.meanRatio[c] = sumA[c] / sumB[c];
    else r.meanRatio[c] = sumA[c] == 0.0 ? 1.0 : INFINITY;
    // Var(mean) = sum of per-pixel variances / P^2, so z = (sumA - sumB) / sqrt(sumVar).
    if (sumVar[c] > 0.0) r.meanRatioZ[c] = (sumA[c] - sumB[c]) / std::sqrt(sumVar[c]);
    else r.meanRatioZ[c] = agreeExactly(sumA[c], sumB[c]) ? 0.0 : std::copysign(INFINITY, sumA[c] - sumB[c]);
    if (!(std::abs(r.meanRatioZ[c]) < r.meanZThreshold)) r.meanTestPassed = false;
    // |sumA - sumB| = delta |sumB| is found with probability kDetectionPower when it is
    // (threshold + z_power) standard deviations, sqrt(sumVar), of the difference.
    const double reference = sumB[c] != 0.0 ? std::abs(sumB[c]) : std::abs(sumA[c]);
    if (sumVar[c] > 0.0)
      r.minDetectable[c] = reference > 0.0 ? (r.meanZThreshold + normalUpperQuantile(1.0 - kDetectionPower)) *
                                                 std::sqrt(sumVar[c]) / reference
                                           : INFINITY;
    r.minDetectableDifference = std::max(r.minDetectableDifference, r.minDetectable[c]);
  }
  r.agree = r.pixelTestPassed && r.meanTestPassed;
  r.inconclusive = r.agree && !(r.minDetectableDifference <= kInconclusiveDifference);
  r.relMse = relativeMse(a, b);
  return r;
}

ComparisonResult compareExrFiles(const std::string& pathA, const std::string& pathB, double alpha,
                                 double maxFailFraction) {
  Image varA, varB;
  ExrMetadata metaA, metaB;
  const Image a = readExr(pathA, &metaA, &varA);
  const Image b = readExr(pathB, &metaB, &varB);
  for (const auto* file : {&pathA, &pathB}) {
    const ExrMetadata& meta = file == &pathA ? metaA : metaB;
    const auto spp = meta.ints.find("spp");
    if (spp != meta.ints.end() && spp->second < kReliableSpp)
      warn("'" + *file + "' has " + std::to_string(spp->second) + " spp; below " + std::to_string(kReliableSpp) +
           " the per-pixel test reports false differences (use more spp or --max-fail-fraction)");
  }
  // Name the file here: compareImages only knows "first" and "second".
  if (varA.width == 0) throw Error("'" + pathA + "' has no variance channels (render it with --variance to compare)");
  if (varB.width == 0) throw Error("'" + pathB + "' has no variance channels (render it with --variance to compare)");
  if (!sameSize(a, b))
    throw Error("cannot compare images of different sizes ('" + pathA + "' is " + sizeText(a) + ", '" + pathB +
                "' is " + sizeText(b) + ")");
  return compareImages(a, varA, b, varB, alpha, maxFailFraction);
}

double relativeMseOfExrFiles(const std::string& pathA, const std::string& pathB) {
  const Image a = readExr(pathA, nullptr, nullptr);
  const Image b = readExr(pathB, nullptr, nullptr);
  if (!sameSize(a, b))
    throw Error("cannot compare images of different sizes ('" + pathA + "' is " + sizeText(a) + ", '" + pathB +
                "' is " + sizeText(b) + ")");
  return relativeMse(a, b);
}

const char* ComparisonResult::verdict() const { return !agree ? "differ" : inconclusive ? "inconclusive" : "agree"; }

std::string ComparisonResult::summary() const {
  char line[640];
  std::snprintf(line, sizeof(line),
                "%s: %zu of %zu pixel-channels fail |z| > %.2f (%.3f%%, %zu allowed), relMSE %.4g, "
                "mean ratio R %.4f G %.4f B %.4f (z %.2f %.2f %.2f, limit %.2f), "
                "detectable mean difference %.3g%% (at most %.0f%% for a verdict)",
                verdict(), failed, channels, zThreshold, 100.0 * failFraction, allowedFailures, relMse,
                meanRatio[0], meanRatio[1], meanRatio[2], meanRatioZ[0], meanRatioZ[1], meanRatioZ[2], meanZThreshold,
                100.0 * minDetectableDifference, 100.0 * kInconclusiveDifference);
  std::string text = line;
  if (nonFinite) text += ", " + std::to_string(nonFinite) + " non-finite values";
  if (inconclusive) text += "; too little power to tell: render more spp or a larger image";
  return text;
}

void writeComparisonJson(const std::string& path, const ComparisonResult& r, const std::string& pathA,
                         const std::string& pathB) {
  // JSON has no Inf/NaN; nlohmann writes them as null, which is what a reader should see.
  nlohmann::json j;
  j["a"] = pathA;
  j["b"] = pathB;
  j["width"] = r.width;
  j["height"] = r.height;
  j["pixels"] = r.pixels;
  j["channels"] = r.channels;
  j["failed"] = r.failed;
  j["allowed_failures"] = r.allowedFailures;
  j["non_finite"] = r.nonFinite;
  j["fail_fraction"] = r.failFraction;
  j["alpha"] = r.alpha;
  j["z_threshold"] = r.zThreshold;
  j["mean_z_threshold"] = r.meanZThreshold;
  j["rel_mse"] = r.relMse;
  j["mean_a"] = {r.meanA[0], r.meanA[1], r.meanA[2]};
  j["mean_b"] = {r.meanB[0], r.meanB[1], r.meanB[2]};
  j["mean_ratio"] = {r.meanRatio[0], r.meanRatio[1], r.meanRatio[2]};
  j["mean_ratio_z"] = {r.meanRatioZ[0], r.meanRatioZ[1], r.meanRatioZ[2]};
  j["pixel_test_passed"] = r.pixelTestPassed;
  j["mean_test_passed"] = r.meanTestPassed;
  j["agree"] = r.agree;
  j["inconclusive"] = r.inconclusive;
  j["verdict"] = r.verdict();
  j["min_detectable"] = {r.minDetectable[0], r.minDetectable[1], r.minDetectable[2]};
  j["min_detectable_difference"] = r.minDetectableDifference;
  j["summary"] = r.summary();
  std::ofstream out(path);
  if (!out) throw Error("cannot write comparison report '" + path + "'");
  out << j.dump(2) << "\n";
  if (!out) throw Error("failed writing comparison report '" + path + "'");
}

}  // namespace mixtrace
