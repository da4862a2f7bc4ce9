#pragma once
// Statistical comparison of two Monte Carlo renders of the same scene: do they estimate the same
// image, given each pixel's standard error of the mean (what `render --variance` writes)?
//
// The rule (all of it is in compareImages):
//
//  1. Per pixel-channel test, for local differences (a missing light, a wrong material on one
//     object): z = (a - b) / sqrt(varA + varB). When both variances are 0 (a pixel that sees only
//     background or a constant emitter) the values must agree within a relative 1e-5
//     (|a - b| <= 1e-5 * max(|a|, |b|)), else that pixel-channel fails.
//     All N = 3 * width * height pixel-channels are tested, and the two-sided threshold is Šidák
//     corrected so that the family-wise false-alarm rate is alpha under exact normality:
//         alpha1 = 1 - (1 - alpha)^(1/N),   zThreshold = Phi^-1(1 - alpha1 / 2).
//     Monte Carlo pixel means at low spp are heavy-tailed (a firefly in one image; or a pixel whose
//     rare bright paths were never sampled, so its variance estimate is far too small), so the
//     normal approximation is poor in the far tail. We therefore tolerate a few failures:
//         allowedFailures = max(2, floor(1e-3 * N))          (default), or
//         allowedFailures = floor(maxFailFraction * N)       (when maxFailFraction >= 0).
//     A genuine local difference fails a coherent patch of pixels (tens to hundreds at small
//     resolutions), far above that allowance; a few isolated outliers are what heavy tails give.
//     Measured on the shipped scenes (48x36, 10 seed pairs each): no false "differ" at 16 or 64
//     spp; at 4 spp most pairs exceed the allowance (the variance is itself estimated from 4
//     samples, so z has Student-t tails), hence compareExrFiles warns below 16 spp.
//
//  2. Image-mean test, for small global biases (a 2% scale error, a wrong normalisation) that hide
//     in per-pixel noise: per channel c, z_c = (mean(A) - mean(B)) / sqrt(sum_p (varA + varB)) * P,
//     i.e. the pixel estimates are independent, so the variance of the image mean is the sum of the
//     per-pixel variances over P^2. The threshold is Šidák corrected for the 3 channels at alpha.
//     Pooling P pixels makes this test sqrt(P) times more sensitive to a uniform bias than any
//     single pixel, and the sum of many variance estimates is well behaved even where single ones
//     are not. If both summed variances are 0, the means must agree within a relative 1e-5.
//     Caveat: the unweighted mean is dominated by the noisiest pixels. In the Cornell box at
//     48x36 the anti-aliased edge of the visible light holds >99% of the summed variance, so a
//     2% bias needs thousands of spp there; scenes without visible emitter edges (or larger
//     images, where edges are a smaller share) need far fewer.
//
//  agree = (failed <= allowedFailures) AND (|meanRatioZ[c]| < meanZThreshold for every c)
//          AND no non-finite value (NaN/Inf) or negative variance in any of the four images
//          (such pixel-channels also count as failed and are left out of the image means).
//
//  3. Power, for "inconclusive": finding no difference means little when the test could not
//     have found one (two 16-spp renders of a hard scene "agreed" with relMSE 7). A power
//     analysis of the image-mean test gives, per channel, the smallest relative difference of the
//     image means it detects with probability kDetectionPower = 80 %:
//         minDetectable_c = (meanZThreshold + Phi^-1(0.8)) * sqrt(sum_p (varA + varB)) / |sum_p b|
//     (0 for a channel compared exactly; the far opposite tail is neglected). The image mean is
//     the most sensitive part of the rule to any difference that brightens or darkens the image,
//     so when it cannot resolve kInconclusiveDifference = 10 % neither can the rest:
//         inconclusive = agree AND max_c minDetectable_c > 10 %
//     (verdict "inconclusive", exit status 3: render more spp or a larger image; the detectable
//     difference shrinks as 1/sqrt(spp * pixels)). "differ" is never inconclusive: a significant
//     difference is evidence whatever the power.
//
// relMse follows the paper's protocol (docs/estimator.md §8), with B as the reference: per pixel
// e = (1/3) sum_c (a - b)^2 / (b^2 + 1e-4); the floor(0.001 * P) largest e are dropped (none for
// images under 1000 pixels) and the rest averaged.
#include <cstddef>
#include <string>

#include "output/image.h"

namespace mixtrace {

// The power analysis behind "inconclusive" (rule 3 above): the relative difference of the image
// means that must be detectable, and with what probability. (--help quotes them.)
constexpr double kInconclusiveDifference = 0.10;
constexpr double kDetectionPower = 0.80;

struct ComparisonResult {
  int width = 0, height = 0;
  size_t pixels = 0;            // width * height
  size_t channels = 0;          // tested pixel-channels: 3 * pixels
  size_t failed = 0;            // pixel-channels failing the corrected per-pixel test (or non-finite)
  size_t allowedFailures = 0;   // failures tolerated by the per-pixel part of the verdict
  size_t nonFinite = 0;         // pixel-channels with a NaN/infinite value or a NaN/infinite/negative variance
  double failFraction = 0.0;    // failed / channels
  double alpha = 0.01;          // family-wise significance used
  double zThreshold = 0.0;      // per-pixel two-sided threshold after the correction over `channels`
  double meanZThreshold = 0.0;  // image-mean two-sided threshold after the correction over 3 channels
  double relMse = 0.0;          // docs/estimator.md §8, A against B as the reference
  double meanA[3] = {0, 0, 0}, meanB[3] = {0, 0, 0};  // per-channel image means
  double meanRatio[3] = {1, 1, 1};   // per channel: mean(A) / mean(B) (1 when both are 0)
  double meanRatioZ[3] = {0, 0, 0};  // z-score of the image-mean difference (from the summed variances)
  double minDetectable[3] = {0, 0, 0};  // per channel: relative mean difference found with 80 % power
  double minDetectableDifference = 0;   // the largest of minDetectable
  bool pixelTestPassed = true;
  bool meanTestPassed = true;
  bool agree = true;            // no significant difference (also when inconclusive)
  bool inconclusive = false;    // agree, but a 10 % difference of the image means could go unseen

  // "agree", "differ" or "inconclusive".
  const char* verdict() const;
  // One line: verdict, fraction failing, relMSE, per-channel mean ratios and their z-scores, and
  // the smallest detectable difference of the image means.
  std::string summary() const;
};

// `seA`, `seB` hold the standard error of each pixel's mean (what readExr returns; the formulas
// above use its square, the variance of the mean, formed in double). All four images must have the same size;
// throws mixtrace::Error (one line) otherwise, or when a variance image is empty ("render with
// --variance"). `alpha` must be in (0, 1); `maxFailFraction` < 0 selects the default allowance.
ComparisonResult compareImages(const Image& a, const Image& seA, const Image& b, const Image& seB,
                               double alpha = 0.01, double maxFailFraction = -1.0);

// Loads two EXR files written by `render --variance` and compares them. Throws mixtrace::Error
// when a file cannot be read or has no variance channels.
ComparisonResult compareExrFiles(const std::string& pathA, const std::string& pathB, double alpha = 0.01,
                                 double maxFailFraction = -1.0);

// Writes the result as a JSON object (every field above plus the two paths, which may be empty).
void writeComparisonJson(const std::string& path, const ComparisonResult& result, const std::string& pathA = "",
                         const std::string& pathB = "");

// Upper-tail standard normal quantile: the z with P(Z > z) = p, for p in (0, 1). Accurate to
// ~1e-12 relative down to p ~ 1e-300 (bisection on erfc); exposed for tests.
double normalUpperQuantile(double p);

// Two-sided threshold z with P(|Z| > z) = 1 - (1 - alpha)^(1/tests) (Šidák), so that `tests`
// independent two-sided tests have family-wise false-alarm rate alpha.
double sidakTwoSidedThreshold(double alpha, size_t tests);

// The relMSE of `image` against `reference` alone (docs/estimator.md §8); same size required.
double relativeMse(const Image& image, const Image& reference);
// The same for two EXR files (B the reference); throws Error for unreadable or mismatched files.
double relativeMseOfExrFiles(const std::string& pathA, const std::string& pathB);

// The per-pixel terms relMSE averages (before trimming): the relative squared error of each pixel,
// averaged over its channels, in row-major order.
std::vector<double> relativeSquaredErrors(const Image& image, const Image& reference);

}  // namespace mixtrace
