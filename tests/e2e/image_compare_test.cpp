// Statistical image comparison (compare/image_compare.h and `mixtrace compare`): real renders that
// must agree (different seeds) or differ (a 2% scale error, a missing light), synthetic Gaussian
// images with known mean and variance, the relMSE definition with its 0.1% trimming, the
// threshold arithmetic, input errors and the command line's exit codes.
#include "compare/image_compare.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "output/exr_io.h"
#include "support/run_binary.h"
#include "util/error.h"

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

namespace {

std::string sceneFile(const std::string& name) { return (fs::path(MIXTRACE_SOURCE_DIR) / "scenes" / name).string(); }

struct Render {
  std::string path;
  Image mean, variance;
};

Render render(const std::string& scene, const std::string& args, const fs::path& out) {
  RunResult r = runMixtrace("render " + scene + " " + args + " --variance -q --no-png --out " + out.string());
  if (r.exitCode != 0) throw std::runtime_error("render failed: " + r.stderrText);
  Render result;
  result.path = out.string();
  result.mean = readExr(result.path, nullptr, &result.variance);
  return result;
}

struct CliResult {
  int exitCode = -1;
  std::string out, err;
};

// runMixtrace discards stdout; the summary line lives there, so capture both streams here.
CliResult runCompare(const std::string& args) {
  const fs::path dir = scratchDir("compare-cli");
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd = std::string("timeout 60 ") + MIXTRACE_BINARY + " compare " + args + " > " + out.string() +
                          " 2> " + err.string();
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  const auto slurp = [](const fs::path& p) {
    std::ifstream f(p);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
  };
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

size_t lineCount(const std::string& text) {
  size_t lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

Image scaled(const Image& image, double factor) {
  Image result = image;
  for (float& v : result.rgb) v = float(v * factor);
  return result;
}

// z of a given relative scale error in the image mean of `r` (compared with an independent
// render of the same variance): the power of the image-mean test.
double expectedMeanZ(const Render& r, double relativeError, int channel) {
  double sum = 0.0, var = 0.0;
  for (size_t p = 0; p < r.mean.pixelCount(); ++p) {
    sum += r.mean.rgb[3 * p + channel];
    var += double(r.variance.rgb[3 * p + channel]) * r.variance.rgb[3 * p + channel];  // standard errors
  }
  return relativeError * sum / std::sqrt(2.0 * var);
}

// Renders shared by the tests below, each made on first use (ctest runs every test case in its
// own process, so a suite-wide set-up would render everything once per case):
//  * textured.glb, direct light only, 96x72 at 64 spp, seeds 1 and 2: low enough variance in the
//    image mean that a 2% scale error is ~13 sigma (checked in the test). (Cornell box is a poor
//    choice here: the anti-aliased edge of its visible light carries >99% of the image-mean
//    variance at this size.)
//  * many_lights.gltf at 48x36, 128 spp, and the same scene with its strongest light (light_29,
//    green, strength 100, visible through a doorway) switched off by zeroing its emissiveFactor.
class RenderedImages : public ::testing::Test {
 protected:
  static const fs::path& dir() {
    static const fs::path path = scratchDir("image-compare");
    return path;
  }
  static const Render& textured(int seed) {
    static Render renders[2];
    Render& r = renders[seed - 1];
    if (r.path.empty())
      r = render(sceneFile("textured.glb"), "--width 96 --height 72 --spp 64 --max-depth 2 --seed " + std::to_string(seed),
                 dir() / ("textured" + std::to_string(seed) + ".exr"));
    return r;
  }
  static const Render& allLights() {
    static const Render r = render(sceneFile("many_lights.gltf"), kLightsArgs + " --seed 1", dir() / "lights_all.exr");
    return r;
  }
  static const Render& oneLightMissing() {
    static const Render r = [] {
      nlohmann::json scene;
      std::ifstream(sceneFile("many_lights.gltf")) >> scene;
      bool found = false;
      for (auto& material : scene["materials"])
        if (material.value("name", "") == "light_29") {
          material["emissiveFactor"] = {0.0, 0.0, 0.0};
          found = true;
        }
      if (!found) throw std::runtime_error("many_lights.gltf has no material light_29");
      const fs::path dimmed = dir() / "many_lights_without_29.gltf";
      std::ofstream(dimmed) << scene.dump();
      return render(dimmed.string(), kLightsArgs + " --seed 2", dir() / "lights_missing.exr");
    }();
    return r;
  }
  static void TearDownTestSuite() {
    std::error_code ignored;
    fs::remove_all(dir(), ignored);
  }
  static inline const std::string kLightsArgs = "--width 48 --height 36 --spp 128";
};

TEST_F(RenderedImages, DifferentSeedsAgree) {
  const ComparisonResult r = compareImages(textured(1).mean, textured(1).variance, textured(2).mean, textured(2).variance);
  EXPECT_TRUE(r.agree) << r.summary();
  EXPECT_EQ(r.pixels, 96u * 72u);
  EXPECT_EQ(r.channels, 3u * 96u * 72u);
  EXPECT_LE(r.failed, r.allowedFailures);
  for (int c = 0; c < 3; ++c) {
    EXPECT_LT(std::abs(r.meanRatioZ[c]), r.meanZThreshold);
    EXPECT_NEAR(r.meanRatio[c], 1.0, 0.01);
  }
  // Two 64-spp renders of the same scene: small but nonzero relMSE.
  EXPECT_GT(r.relMse, 0.0);
  EXPECT_LT(r.relMse, 1.0);

  const CliResult cli = runCompare(textured(1).path + " " + textured(2).path);
  EXPECT_EQ(cli.exitCode, 0) << cli.out << cli.err;
  EXPECT_EQ(lineCount(cli.out), 1u) << cli.out;
  EXPECT_EQ(cli.out, r.summary() + "\n");
  EXPECT_EQ(cli.out.rfind("agree: ", 0), 0u) << cli.out;
  EXPECT_EQ(cli.err, "");
}

TEST_F(RenderedImages, TwoPercentScaleErrorIsCaughtByTheImageMeanTest) {
  // Precondition that makes the test meaningful: at this scene and spp a 2% bias is far beyond
  // the corrected image-mean threshold (~2.9), so it is caught whatever the seeds.
  for (int c = 0; c < 3; ++c) EXPECT_GT(expectedMeanZ(textured(2), 0.02, c), 8.0) << "channel " << c;

  const Image biased = scaled(textured(2).mean, 1.02), biasedVariance = scaled(textured(2).variance, 1.02);  // standard errors
  const ComparisonResult r = compareImages(biased, biasedVariance, textured(1).mean, textured(1).variance);
  EXPECT_FALSE(r.agree) << r.summary();
  EXPECT_FALSE(r.meanTestPassed);
  // (The per-pixel part fails too, but only because of the directly seen emitter, whose pixels
  // have zero variance and so must match exactly; 2% is far below each other pixel's noise.)
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(r.meanRatio[c], 1.02, 0.01);
    EXPECT_GT(r.meanRatioZ[c], r.meanZThreshold);
  }

  const fs::path file = dir() / "textured2_biased.exr";
  writeExr(file.string(), biased, ExrMetadata{}, &biasedVariance);
  const CliResult cli = runCompare(file.string() + " " + textured(1).path);
  EXPECT_EQ(cli.exitCode, 1) << cli.out << cli.err;
  EXPECT_EQ(cli.out.rfind("differ: ", 0), 0u) << cli.out;
  EXPECT_EQ(lineCount(cli.out), 1u) << cli.out;
}

TEST_F(RenderedImages, MissingLightIsCaughtPerPixel) {
  const ComparisonResult r =
      compareImages(oneLightMissing().mean, oneLightMissing().variance, allLights().mean, allLights().variance);
  EXPECT_FALSE(r.agree) << r.summary();
  // The light's patch of pixels fails the per-pixel test, far beyond the outlier allowance.
  EXPECT_GT(r.failed, 3 * r.allowedFailures) << r.summary();
  EXPECT_FALSE(r.pixelTestPassed);
  // It was a green light: green loses most.
  EXPECT_LT(r.meanRatio[1], r.meanRatio[0]);
  EXPECT_LT(r.meanRatio[1], 0.95);

  const CliResult cli = runCompare(oneLightMissing().path + " " + allLights().path + " -q");
  EXPECT_EQ(cli.exitCode, 1) << cli.err;
  EXPECT_EQ(cli.out, "") << "-q prints no summary";
}

TEST_F(RenderedImages, JsonReportHoldsTheResult) {
  const fs::path report = dir() / "report.json";
  const CliResult cli =
      runCompare(oneLightMissing().path + " " + allLights().path + " --alpha 0.001 --json " + report.string());
  EXPECT_EQ(cli.exitCode, 1);
  nlohmann::json j;
  std::ifstream(report) >> j;
  const ComparisonResult r =
      compareImages(oneLightMissing().mean, oneLightMissing().variance, allLights().mean, allLights().variance, 0.001);
  EXPECT_EQ(j["agree"].get<bool>(), false);
  EXPECT_EQ(j["failed"].get<size_t>(), r.failed);
  EXPECT_EQ(j["channels"].get<size_t>(), r.channels);
  EXPECT_DOUBLE_EQ(j["alpha"].get<double>(), 0.001);
  EXPECT_DOUBLE_EQ(j["z_threshold"].get<double>(), r.zThreshold);
  EXPECT_DOUBLE_EQ(j["rel_mse"].get<double>(), r.relMse);
  EXPECT_DOUBLE_EQ(j["mean_ratio"][1].get<double>(), r.meanRatio[1]);
  EXPECT_EQ(j["a"].get<std::string>(), oneLightMissing().path);
  EXPECT_EQ(j["summary"].get<std::string>() + "\n", cli.out);
}

// --error-only: just the relMSE of A against B, for images without variance channels too.
TEST_F(RenderedImages, ErrorOnlyPrintsTheRelMse) {
  const CliResult cli = runCompare(oneLightMissing().path + " " + allLights().path + " --error-only");
  EXPECT_EQ(cli.exitCode, 0) << cli.err;
  const double expected = relativeMse(oneLightMissing().mean, allLights().mean);
  ASSERT_EQ(cli.out.rfind("relMSE ", 0), 0u) << cli.out;
  EXPECT_NEAR(std::stod(cli.out.substr(7)), expected, 1e-5 * expected);
  EXPECT_GT(expected, 0.0);
  const fs::path plain = dir() / "no_variance.exr";
  writeExr(plain.string(), allLights().mean, ExrMetadata{});
  const CliResult same = runCompare(plain.string() + " " + allLights().path + " --error-only");
  EXPECT_EQ(same.exitCode, 0) << same.err;
  EXPECT_EQ(same.out, "relMSE 0\n");
}

// --error-map writes relMSE's per-pixel terms as a PFM (rows bottom to top): they average to the
// untrimmed relMSE, and each matches the formula for its pixel.
TEST_F(RenderedImages, ErrorMapHoldsThePerPixelTerms) {
  const fs::path map = dir() / "error.pfm";
  const CliResult cli =
      runCompare(oneLightMissing().path + " " + allLights().path + " --error-only --error-map " + map.string());
  ASSERT_EQ(cli.exitCode, 0) << cli.err;
  std::ifstream in(map, std::ios::binary);
  std::string kind;
  int width = 0, height = 0;
  double scale = 0.0;
  in >> kind >> width >> height >> scale;
  in.get();
  ASSERT_EQ(kind, "Pf");
  const Image& a = oneLightMissing().mean;
  const Image& b = allLights().mean;
  ASSERT_EQ(width, a.width);
  ASSERT_EQ(height, a.height);
  EXPECT_LT(scale, 0.0) << "little-endian";
  std::vector<float> rows(size_t(width) * height);
  in.read(reinterpret_cast<char*>(rows.data()), std::streamsize(rows.size() * sizeof(float)));
  ASSERT_TRUE(in) << "short PFM";
  const std::vector<double> expected = relativeSquaredErrors(a, b);
  double sum = 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float value = rows[size_t(height - 1 - y) * width + x];
      const double want = expected[size_t(y) * width + x];
      ASSERT_NEAR(value, want, 1e-5 * want + 1e-12) << x << "," << y;
      sum += value;
    }
  EXPECT_GT(sum, 0.0);
  const double r0 = (double(a.rgb[0]) - b.rgb[0]) * (double(a.rgb[0]) - b.rgb[0]) / (double(b.rgb[0]) * b.rgb[0] + 0.01);
  EXPECT_LE(r0 / 3.0, expected[0] + 1e-12) << "a pixel's term averages its channels";
  EXPECT_NE(runCompare(oneLightMissing().path + " " + allLights().path + " --error-map " + map.string()).exitCode, 0)
      << "--error-map without --error-only";
}

TEST_F(RenderedImages, CliInputErrorsExitWithTwo) {
  const auto expectError = [](const CliResult& r, const std::string& needle) {
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("mixtrace: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  };
  expectError(runCompare(textured(1).path + " " + (dir() / "absent.exr").string()), "absent.exr");
  const fs::path small = dir() / "small.exr";
  const Image tiny(8, 6);
  writeExr(small.string(), tiny, ExrMetadata{}, &tiny);
  expectError(runCompare(textured(1).path + " " + small.string()), "different sizes");
  expectError(runCompare(textured(1).path), "two images");
  expectError(runCompare(textured(1).path + " " + textured(2).path + " --alpha 2"), "--alpha");

  const fs::path plain = dir() / "no_variance.exr";
  writeExr(plain.string(), textured(1).mean, ExrMetadata{});
  expectError(runCompare(textured(1).path + " " + plain.string()), "--variance");
}

// The case: two 16-spp renders of a hard scene (Veach MIS, relMSE ~4-7) "agreed", though
// the image means were only known to ~20 %: the verdict is "inconclusive", exit status 3.
TEST_F(RenderedImages, TooLittlePowerIsInconclusive) {
  const std::string args = "--width 48 --height 36 --spp 16 --seed ";
  const Render a = render(sceneFile("veach_mis.gltf"), args + "1", dir() / "veach1.exr");
  const Render b = render(sceneFile("veach_mis.gltf"), args + "2", dir() / "veach2.exr");
  const ComparisonResult r = compareImages(a.mean, a.variance, b.mean, b.variance);
  EXPECT_TRUE(r.agree) << "no significant difference: " << r.summary();
  EXPECT_TRUE(r.inconclusive) << r.summary();
  EXPECT_GT(r.minDetectableDifference, kInconclusiveDifference);
  const CliResult cli = runCompare(a.path + " " + b.path);
  EXPECT_EQ(cli.exitCode, 3) << cli.out << cli.err;
  EXPECT_EQ(cli.out.rfind("inconclusive: ", 0), 0u) << cli.out;
  EXPECT_EQ(lineCount(cli.out), 1u) << cli.out;
  // The renders that agree above are powerful enough for a verdict.
  const ComparisonResult strong =
      compareImages(textured(1).mean, textured(1).variance, textured(2).mean, textured(2).variance);
  EXPECT_FALSE(strong.inconclusive) << strong.summary();
  EXPECT_STREQ(strong.verdict(), "agree");
}

// --- Synthetic images: Gaussian pixel estimates with known mean and standard error of the mean
// (`var` below: what compareImages takes, exr_io.h).

constexpr int kW = 64, kH = 48;

// A smooth positive "scene" with a spread of brightness, and per-pixel standard deviations of
// 5%..20% of the mean (as a Monte Carlo render would have).
void groundTruth(Image& mean, Image& variance) {
  mean = Image(kW, kH);
  variance = Image(kW, kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) {
        const double mu = 0.2 + 1.5 * (x + 1) / kW * (1.0 + 0.3 * c) + 0.5 * std::sin(0.3 * y);
        const double relSd = 0.05 + 0.15 * ((x * 7 + y * 13 + c) % 10) / 9.0;
        mean.pixel(x, y)[c] = float(mu);
        variance.pixel(x, y)[c] = float(std::abs(mu) * relSd);
      }
}

Image draw(const Image& mean, const Image& variance, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Image image(mean.width, mean.height);
  for (size_t i = 0; i < image.rgb.size(); ++i)
    image.rgb[i] = float(mean.rgb[i] + double(variance.rgb[i]) * normal(rng));
  return image;
}

TEST(CompareImagesSynthetic, SameMeanAgreesAtTheNominalRate) {
  Image mu, var;
  groundTruth(mu, var);
  int disagreements = 0;
  size_t beyond99 = 0, tested = 0;
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    const Image a = draw(mu, var, 2 * seed), b = draw(mu, var, 2 * seed + 1);
    const ComparisonResult r = compareImages(a, var, b, var, 0.01);
    disagreements += !r.agree;
    EXPECT_LE(r.failed, 1u) << "seed " << seed << ": " << r.summary();
    for (size_t i = 0; i < a.rgb.size(); ++i) {
      beyond99 += std::abs(a.rgb[i] - b.rgb[i]) / (std::sqrt(2.0) * var.rgb[i]) > 2.5758;
      ++tested;
    }
  }
  // 20 trials at a 1% family-wise level: 3 or more false alarms has probability ~0.001.
  EXPECT_LE(disagreements, 2);
  // Sanity of the generator: 1% of pixel z-scores beyond the two-sided 99% quantile.
  EXPECT_NEAR(double(beyond99) / tested, 0.01, 0.002);
}

// `se` holds standard errors (what compareImages takes): sdFactor times the noise.
Image noisier(const Image& se, double sdFactor) { return scaled(se, sdFactor); }

// minDetectable is the difference the image-mean test finds with 80 % probability: the formula
// by hand, and the detection rate when one channel's mean really differs by that much.
TEST(CompareImagesSynthetic, MinDetectableDifferenceHasTheStatedPower) {
  Image mu, var;
  groundTruth(mu, var);
  var = noisier(var, 20.0);   // ~250 % per-pixel noise: the image means known to a few %
  const ComparisonResult first = compareImages(draw(mu, var, 1), var, draw(mu, var, 2), var);
  int channel = 0;
  for (int c = 0; c < 3; ++c) {
    double sumB = 0.0, sumVar = 0.0;
    for (size_t p = 0; p < mu.pixelCount(); ++p) sumVar += 2.0 * double(var.rgb[3 * p + c]) * var.rgb[3 * p + c];
    const Image b = draw(mu, var, 2);
    for (size_t p = 0; p < mu.pixelCount(); ++p) sumB += b.rgb[3 * p + c];
    const double z80 = normalUpperQuantile(0.2);
    EXPECT_NEAR(first.minDetectable[c], (first.meanZThreshold + z80) * std::sqrt(sumVar) / std::abs(sumB),
                1e-6 * first.minDetectable[c]);
    if (first.minDetectable[c] > first.minDetectable[channel]) channel = c;
  }
  EXPECT_DOUBLE_EQ(first.minDetectableDifference, first.minDetectable[channel]);
  const double delta = first.minDetectable[channel];
  Image shifted = mu;
  for (size_t p = 0; p < mu.pixelCount(); ++p) shifted.rgb[3 * p + channel] *= float(1.0 + delta);
  int detected = 0;
  const int trials = 400;
  for (int t = 0; t < trials; ++t)
    detected += !compareImages(draw(shifted, var, 1000 + 2 * t), var, draw(mu, var, 1001 + 2 * t), var).meanTestPassed;
  // Binomial(400, 0.8): sd 0.02; +-0.07 is 3.5 sd.
  EXPECT_NEAR(double(detected) / trials, kDetectionPower, 0.07) << "delta " << delta;
}

// Same means, per-pixel noise so large that a 10 % difference of the image means would usually
// be missed: not "agree" but "inconclusive" (and the CLI's exit status 3); at the usual noise the
// same images are conclusive; a large difference is "differ" whatever the power.
TEST(CompareImagesSynthetic, LowPowerIsInconclusiveAndDifferIsNot) {
  Image mu, var;
  groundTruth(mu, var);
  const ComparisonResult usual = compareImages(draw(mu, var, 11), var, draw(mu, var, 12), var);
  EXPECT_STREQ(usual.verdict(), "agree") << usual.summary();
  EXPECT_LT(usual.minDetectableDifference, 0.02);

  const Image noisy = noisier(var, 20.0);
  const Image a = draw(mu, noisy, 13), b = draw(mu, noisy, 14);
  const ComparisonResult weak = compareImages(a, noisy, b, noisy);
  EXPECT_TRUE(weak.agree) << weak.summary();
  EXPECT_TRUE(weak.inconclusive) << weak.summary();
  EXPECT_STREQ(weak.verdict(), "inconclusive");
  EXPECT_GT(weak.minDetectableDifference, kInconclusiveDifference);
  EXPECT_EQ(weak.summary().rfind("inconclusive: ", 0), 0u) << weak.summary();

  const ComparisonResult large = compareImages(draw(scaled(mu, 3.0), noisy, 15), noisy, b, noisy);
  EXPECT_FALSE(large.agree) << large.summary();
  EXPECT_FALSE(large.inconclusive);
  EXPECT_STREQ(large.verdict(), "differ");

  const fs::path dir = scratchDir("compare-inconclusive");
  writeExr((dir / "a.exr").string(), a, ExrMetadata{}, &noisy);
  writeExr((dir / "b.exr").string(), b, ExrMetadata{}, &noisy);
  const fs::path json = dir / "r.json";
  const CliResult cli = runCompare((dir / "a.exr").string() + " " + (dir / "b.exr").string() + " --json " + json.string());
  EXPECT_EQ(cli.exitCode, 3) << cli.out << cli.err;
  EXPECT_EQ(cli.out, weak.summary() + "\n");
  nlohmann::json j;
  std::ifstream(json) >> j;
  EXPECT_EQ(j["verdict"].get<std::string>(), "inconclusive");
  EXPECT_TRUE(j["inconclusive"].get<bool>());
  EXPECT_DOUBLE_EQ(j["min_detectable_difference"].get<double>(), weak.minDetectableDifference);
}

TEST(CompareImagesSynthetic, ShiftedMeanDiffers) {
  Image mu, var;
  groundTruth(mu, var);
  // 3%: about ten standard deviations of the image-mean difference at these variances.
  const Image a = draw(mu, var, 101), b = draw(scaled(mu, 1.03), var, 102);
  const ComparisonResult r = compareImages(a, var, b, var);
  EXPECT_FALSE(r.agree) << r.summary();
  EXPECT_FALSE(r.meanTestPassed);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(r.meanRatio[c], 1.0 / 1.03, 0.01);
    EXPECT_LT(r.meanRatioZ[c], -r.meanZThreshold);
  }
}

TEST(CompareImagesSynthetic, LocalPatchDiffersPerPixel) {
  Image mu, var;
  groundTruth(mu, var);
  Image a = draw(mu, var, 201);
  const Image b = draw(mu, var, 202);
  // A 3x3 patch, 12 standard deviations brighter: 27 pixel-channels, far above the allowance of 9.
  for (int y = 20; y < 23; ++y)
    for (int x = 30; x < 33; ++x)
      for (int c = 0; c < 3; ++c) a.pixel(x, y)[c] += 12.0f * var.pixel(x, y)[c];
  const ComparisonResult r = compareImages(a, var, b, var);
  EXPECT_EQ(r.allowedFailures, 9u);
  EXPECT_GE(r.failed, 27u);
  EXPECT_FALSE(r.pixelTestPassed);
  EXPECT_FALSE(r.agree) << r.summary();
  // A looser allowance tolerates it (if the mean test does too).
  EXPECT_TRUE(compareImages(a, var, b, var, 0.01, 0.01).pixelTestPassed);
}

// A directly seen emitter after thousands of samples: the variance estimate is round-off itself,
// and float accumulation on the GPU moves the mean by ~2e-5 relative. Such differences agree;
// a 1e-3 relative difference on the same pixels still fails.
TEST(CompareImagesSynthetic, RoundOffOnNearlyConstantPixelsAgrees) {
  Image a(40, 30), tiny(40, 30);
  for (size_t i = 0; i < a.rgb.size(); ++i) {
    a.rgb[i] = 312.5f;
    tiny.rgb[i] = 1e-8f;
  }
  Image b = a;
  for (size_t i = 0; i < b.rgb.size(); ++i) b.rgb[i] = 312.5f * (1.0f + 2e-5f);
  ComparisonResult r = compareImages(a, tiny, b, tiny);
  EXPECT_EQ(r.failed, 0u) << r.summary();
  for (int i = 0; i < 10; ++i) b.rgb[i * 7] = 312.5f * 1.001f;
  r = compareImages(a, tiny, b, tiny);
  EXPECT_EQ(r.failed, 10u) << r.summary();
}

TEST(CompareImagesSynthetic, ZeroVarianceMustMatchExactly) {
  Image a(40, 30), zero(40, 30);
  for (size_t i = 0; i < a.rgb.size(); ++i) a.rgb[i] = 0.5f + 0.001f * float(i % 97);
  Image b = a;
  EXPECT_TRUE(compareImages(a, zero, b, zero).agree);
  for (size_t i = 0; i < b.rgb.size(); ++i) b.rgb[i] *= 1.000001f;  // round-off level: fine
  ComparisonResult r = compareImages(a, zero, b, zero);
  EXPECT_TRUE(r.agree) << r.summary();
  EXPECT_EQ(r.failed, 0u);
  for (int i = 0; i < 10; ++i) b.rgb[i * 7] *= 1.001f;  // ten real differences
  r = compareImages(a, zero, b, zero);
  EXPECT_EQ(r.failed, 10u);
  EXPECT_FALSE(r.agree) << r.summary();
}

TEST(CompareImagesSynthetic, NonFiniteValuesDiffer) {
  Image mu, var;
  groundTruth(mu, var);
  Image a = draw(mu, var, 5);
  const Image b = draw(mu, var, 6);
  a.rgb[100] = std::nanf("");
  const ComparisonResult r = compareImages(a, var, b, var);
  EXPECT_EQ(r.nonFinite, 1u);
  EXPECT_FALSE(r.agree);
  EXPECT_TRUE(std::isfinite(r.meanRatioZ[100 % 3])) << "NaN kept out of the image mean";
}

TEST(CompareImagesSynthetic, RelMseMatchesHandComputedValueWithTrimming) {
  // 1000 pixels: floor(0.1% * 1000) = 1 pixel, the largest error, is dropped.
  Image ref(40, 25), img(40, 25);
  for (float& v : ref.rgb) v = 1.0f;
  img = ref;
  img.pixel(0, 0)[0] = img.pixel(0, 0)[1] = img.pixel(0, 0)[2] = 1.1f;  // e = 0.01 / 1.0001
  img.pixel(1, 0)[0] = 1.2f;                                          // e = 0.04 / 1.0001 / 3
  img.pixel(2, 0)[0] = img.pixel(2, 0)[1] = img.pixel(2, 0)[2] = 3.0f;  // e = 4 / 1.0001: dropped
  ref.pixel(3, 0)[2] = 0.0f;
  img.pixel(3, 0)[2] = 0.01f;                                         // e = (1e-4 / 1e-4) / 3
  const double d1 = double(1.1f) - 1.0, d2 = double(1.2f) - 1.0, d4 = double(0.01f);
  const double expected = (d1 * d1 / 1.0001 + d2 * d2 / 1.0001 / 3.0 + d4 * d4 / 1e-4 / 3.0) / 999.0;
  EXPECT_NEAR(relativeMse(img, ref), expected, 1e-12);

  Image zero(40, 25);
  const ComparisonResult r = compareImages(img, zero, ref, zero);
  EXPECT_DOUBLE_EQ(r.relMse, relativeMse(img, ref));

  // One pixel fewer (999): nothing is trimmed, the outlier counts.
  Image smallRef(37, 27), smallImg(37, 27);
  for (float& v : smallRef.rgb) v = 1.0f;
  smallImg = smallRef;
  smallImg.pixel(5, 5)[0] = smallImg.pixel(5, 5)[1] = smallImg.pixel(5, 5)[2] = 3.0f;
  EXPECT_NEAR(relativeMse(smallImg, smallRef), 4.0 / 1.0001 / 999.0, 1e-12);
}

TEST(CompareImagesSynthetic, ThresholdsAreTheCorrectedNormalQuantiles) {
  EXPECT_NEAR(normalUpperQuantile(0.5), 0.0, 1e-12);
  EXPECT_NEAR(normalUpperQuantile(0.025), 1.959963984540054, 1e-9);
  EXPECT_NEAR(normalUpperQuantile(1e-7), 5.199337582192817, 1e-8);
  EXPECT_NEAR(normalUpperQuantile(0.975), -1.959963984540054, 1e-9);
  EXPECT_NEAR(sidakTwoSidedThreshold(0.01, 1), 2.5758293035489, 1e-9);
  // Šidák for 3 tests at 1%: per test 1 - 0.99^(1/3) = 0.0033445...
  EXPECT_NEAR(sidakTwoSidedThreshold(0.01, 3), normalUpperQuantile(0.5 * (1.0 - std::pow(0.99, 1.0 / 3.0))), 1e-9);
  // More tests, higher threshold.
  EXPECT_GT(sidakTwoSidedThreshold(0.01, 1000000), sidakTwoSidedThreshold(0.01, 1000));
  Image mu, var;
  groundTruth(mu, var);
  const ComparisonResult r = compareImages(mu, var, mu, var, 0.05);
  EXPECT_DOUBLE_EQ(r.zThreshold, sidakTwoSidedThreshold(0.05, 3 * kW * kH));
  EXPECT_TRUE(r.agree);
  EXPECT_EQ(r.relMse, 0.0);
}

std::string errorOf(const Image& a, const Image& va, const Image& b, const Image& vb) {
  try {
    compareImages(a, va, b, vb);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(CompareImagesSynthetic, SizeMismatchAndMissingVarianceThrow) {
  const Image small(4, 3), large(5, 3), none;
  std::string message = errorOf(small, small, large, large);
  EXPECT_NE(message.find("4x3"), std::string::npos) << message;
  EXPECT_NE(message.find("5x3"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  message = errorOf(small, none, small, small);
  EXPECT_NE(message.find("--variance"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  message = errorOf(small, small, small, none);
  EXPECT_NE(message.find("--variance"), std::string::npos) << message;
  message = errorOf(small, large, small, small);
  EXPECT_NE(message.find("variance"), std::string::npos) << message;
  EXPECT_THROW(compareImages(small, small, small, small, 0.0), Error);
  EXPECT_THROW(compareImages(small, small, small, small, 1.0), Error);
}

}  // namespace
