// The Vulkan renderer's two schedules (--schedule wavefront|fused, issue 15): the fused kernel
// traces each path whole with the CPU backend's loops (shared/path_tracer.h, and for the methods
// with controlled mixture sampling shared/cms_path_tracer.h), the wavefront passes split the same
// estimator over dispatches; for the same seed both draw the same random numbers in the same order,
// so every shipped scene gives the same paths (the same ray counts), the same CMS statistics and
// the same image up to float rounding. Fused refuses, in one line, AOVs (the wavefront's aov pass).
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "compare/image_compare.h"
#include "support/render_with_stats.h"
#include "support/run_binary.h"
#include "support/shipped_scenes.h"

namespace {

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

RenderWithStats renderWith(const std::string& scene, const std::string& method, const std::string& schedule,
                           const fs::path& out, const std::string& extra = "--spp 2") {
  return renderWithStats(scene + " --width 32 --height 24 --seed 5 --variance --method " + method +
                             " --schedule " + schedule + " " + extra,
                         out, 600);
}

// The fraction of pixels whose value differs between a and b beyond float rounding.
double fractionOfPixelsThatDiffer(const Image& a, const Image& b) {
  size_t differ = 0;
  for (size_t p = 0; p < a.pixelCount(); ++p) {
    for (size_t c = 0; c < 3; ++c) {
      const float x = a.rgb[3 * p + c];
      const float y = b.rgb[3 * p + c];
      if (!(std::abs(x - y) <= 1e-5f * std::max(std::abs(x), std::abs(y)) + 1e-9f)) {
        ++differ;
        break;
      }
    }
  }
  return double(differ) / double(a.pixelCount());
}

// The stats JSON's integer `key` of both renders, equal within `tolerance` (relative).
void expectCountsClose(const RenderWithStats& w, const RenderWithStats& f, const char* key, double tolerance,
                       const std::string& where) {
  ASSERT_TRUE(w.stats.contains(key)) << where << ": " << key;
  ASSERT_TRUE(f.stats.contains(key)) << where << ": " << key;
  const double a = w.stats[key].get<double>();
  const double b = f.stats[key].get<double>();
  EXPECT_LE(std::abs(a - b), tolerance * std::max(a, b)) << where << ": " << key << " " << a << " / " << b;
}

class Schedule : public ::testing::TestWithParam<std::string> {};

TEST_P(Schedule, FusedAndWavefrontTraceTheSamePaths) {
  const fs::path dir = scratchDir("schedule");
  const std::string stem = sceneStem(GetParam());
  for (const char* method : {"pt-uniform", "pt-power", "pt-bvh"}) {
    const RenderWithStats w = renderWith(GetParam(), method, "wavefront", dir / (stem + "-w.exr"));
    const RenderWithStats f = renderWith(GetParam(), method, "fused", dir / (stem + "-f.exr"));
    ASSERT_EQ(w.exitCode, 0) << w.stderrText;
    ASSERT_EQ(f.exitCode, 0) << f.stderrText;
    EXPECT_EQ(w.stats["schedule"], "wavefront");
    EXPECT_EQ(f.stats["schedule"], "fused");
    EXPECT_EQ(w.stats["extension_rays"], f.stats["extension_rays"]) << method;
    EXPECT_EQ(w.stats["shadow_rays"], f.stats["shadow_rays"]) << method;
    const ComparisonResult c = compareImages(f.mean, f.variance, w.mean, w.variance);
    EXPECT_LT(c.relMse, 1e-9) << method << ": " << c.summary();
  }
}

// The learning methods at 8 spp, so the training solves three times (doubling: after passes 1, 3
// and 7) and later passes sample from learned cells. The statistics are float sums added with
// atomics in whatever order the worker threads reach them, as in two wavefront renders of one
// seed, so a solve may differ in its last bits, and a random number that falls right at a
// selection CDF's boundary can then pick another light in one render than in the other: the paths
// are compared with room for a few such flips (0.5 % of the rays, 3 % of the pixels), where an
// estimator that differed would change nearly every pixel.
TEST_P(Schedule, FusedAndWavefrontLearnTheSameCells) {
  const fs::path dir = scratchDir("schedule-cms");
  const std::string stem = sceneStem(GetParam());
  for (const std::string method : {"cms", "learned"}) {
    const std::string where = stem + " " + method;
    const RenderWithStats w = renderWith(GetParam(), method, "wavefront", dir / (stem + "-w.exr"), "--spp 8");
    const RenderWithStats f = renderWith(GetParam(), method, "fused", dir / (stem + "-f.exr"), "--spp 8");
    ASSERT_EQ(w.exitCode, 0) << w.stderrText;
    ASSERT_EQ(f.exitCode, 0) << f.stderrText;
    EXPECT_EQ(f.stats["schedule"], "fused");
    EXPECT_EQ(w.stats["estimator"], f.stats["estimator"]) << where;
    expectCountsClose(w, f, "extension_rays", 0.005, where);
    expectCountsClose(w, f, "shadow_rays", 0.005, where);
    if (w.stats["estimator"] == method) {   // (cms on a one-light scene reduces to pt-power: no cells)
      expectCountsClose(w, f, "cms_cells_used", 0.01, where);
      expectCountsClose(w, f, "cms_vertices_without_cell", 0.01, where);
      EXPECT_EQ(w.stats["cms_gathering_spp"], f.stats["cms_gathering_spp"]) << where;
      if (w.stats.contains("cms_pair_samples")) {   // the per-triangle control variate (cms)
        expectCountsClose(w, f, "cms_pairs_used", 0.01, where);
        expectCountsClose(w, f, "cms_pair_samples", 0.01, where);
        expectCountsClose(w, f, "cms_pair_remainder_samples", 0.01, where);
      }
    }
    EXPECT_LT(fractionOfPixelsThatDiffer(w.mean, f.mean), 0.03) << where;
  }
}

// The fused kernel's two modules for the statistics, as the shade and shadow passes have them: float
// atomics, and compare-and-swap loops (--float-atomics off, the module for devices without
// VK_EXT_shader_atomic_float); and cv, the per-cluster control variate.
TEST(ScheduleChoice, FusedLearnsWithEitherStatisticsModuleAndTheClusterControlVariate) {
  const fs::path dir = scratchDir("schedule-cms-modules");
  const std::string veach = std::string(MIXTRACE_SOURCE_DIR) + "/scenes/veach_mis.gltf";
  for (const std::string variant : {"cms --float-atomics off", "cv --float-atomics on"}) {
    const RenderWithStats w = renderWith(veach, variant, "wavefront", dir / "w.exr", "--spp 8");
    const RenderWithStats f = renderWith(veach, variant, "fused", dir / "f.exr", "--spp 8 --validation");
    ASSERT_EQ(w.exitCode, 0) << w.stderrText;
    ASSERT_EQ(f.exitCode, 0) << f.stderrText;
    EXPECT_EQ(f.stats["schedule"], "fused");
    EXPECT_EQ(w.stats["cms_statistics_atomics"], f.stats["cms_statistics_atomics"]) << variant;
    EXPECT_EQ(f.stats["cms_statistics_atomics"], variant.find("off") != std::string::npos ? "cas" : "float")
        << variant;
    expectCountsClose(w, f, "extension_rays", 0.005, variant);
    expectCountsClose(w, f, "shadow_rays", 0.005, variant);
    expectCountsClose(w, f, "cms_cells_used", 0.01, variant);
    EXPECT_LT(fractionOfPixelsThatDiffer(w.mean, f.mean), 0.03) << variant;
    EXPECT_EQ(f.stats["non_finite_samples"], 0) << variant;
    EXPECT_EQ(f.stats["validation_errors"], 0) << variant;
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, Schedule, ::testing::ValuesIn(shippedScenes()),
                         [](const auto& info) { return sceneStem(info.param); });

// Auto is the wavefront on lavapipe (measured faster there: wavefront_renderer.cpp).
TEST(ScheduleChoice, AutoIsTheWavefrontOnLavapipe) {
  const fs::path dir = scratchDir("schedule-auto");
  const std::string box = std::string(MIXTRACE_SOURCE_DIR) + "/scenes/cornell_box.gltf";
  const std::string veach = std::string(MIXTRACE_SOURCE_DIR) + "/scenes/veach_mis.gltf";
  const RenderWithStats plain = renderWith(box, "pt-power", "auto", dir / "plain.exr");
  // (cms on a one-light scene reduces to pt-bvh, which fuses: the learning scene has four lights.)
  const RenderWithStats learning = renderWith(veach, "cms", "auto", dir / "cms.exr");
  ASSERT_EQ(plain.exitCode, 0) << plain.stderrText;
  ASSERT_EQ(learning.exitCode, 0) << learning.stderrText;
  EXPECT_EQ(plain.stats["schedule"], "wavefront") << plain.stats["device"];
  EXPECT_EQ(learning.stats["schedule"], "wavefront");
}

TEST(ScheduleChoice, FusedRefusesWhatItCannotRunInOneLine) {
  const fs::path dir = scratchDir("schedule-refused");
  const std::string box = std::string(MIXTRACE_SOURCE_DIR) + "/scenes/veach_mis.gltf";   // four lights: cms learns
  for (const std::string extra : {"--method pt-power --aov albedo", "--method cms --aov depth"}) {
    const fs::path out = dir / "refused.exr";
    const RunResult r = runMixtrace("render " + box + " --width 8 --height 8 --spp 1 --schedule fused " + extra +
                                    " -q --no-png --out " + out.string());
    EXPECT_NE(r.exitCode, 0) << extra;
    const auto lines = r.stderrLines();
    ASSERT_EQ(lines.size(), 1u) << extra << ": " << r.stderrText;
    EXPECT_NE(lines[0].find("--schedule"), std::string::npos) << lines[0];
    EXPECT_FALSE(fs::exists(out)) << extra;
  }
  const RunResult bad = runMixtrace("render " + box + " --schedule megakernel -q --no-png --out " + (dir / "x.exr").string());
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.stderrText.find("--schedule"), std::string::npos) << bad.stderrText;
}

}  // namespace
