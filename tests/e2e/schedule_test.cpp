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

// Auto on a CPU device (lavapipe here): the first submission runs the wavefront and counts the
// extension rays per path and depth; where paths run deep (many_lights.gltf is closed) the rest of
// the render fuses, where many end early (veach_mis, textured) it stays the wavefront, and with
// AOVs, which only the wavefront renders, nothing is measured (wavefront_renderer.cpp
// decideSchedule). A render that switched traces the same paths as one that did not.
TEST(ScheduleChoice, AutoOnACpuDeviceFusesWherePathsRunDeep) {
  const fs::path dir = scratchDir("schedule-auto");
  const auto scene = [](const char* name) { return std::string(MIXTRACE_SOURCE_DIR) + "/scenes/" + name; };
  struct Case {
    std::string scene, method;
    bool fuses;
  };
  for (const Case& k : {Case{scene("many_lights.gltf"), "pt-power", true}, Case{scene("many_lights.gltf"), "cms", true},
                        Case{scene("veach_mis.gltf"), "cms", false}, Case{scene("textured.glb"), "pt-power", false}}) {
    const std::string where = sceneStem(k.scene) + " " + k.method;
    const RenderWithStats a = renderWith(k.scene, k.method, "auto", dir / "auto.exr", "--spp 4");
    ASSERT_EQ(a.exitCode, 0) << a.stderrText;
    ASSERT_NE(a.stats["device"].get<std::string>().find("llvmpipe"), std::string::npos) << a.stats["device"];
    ASSERT_TRUE(a.stats.contains("schedule_ray_occupancy")) << where;
    const double occupancy = a.stats["schedule_ray_occupancy"].get<double>();
    EXPECT_GT(occupancy, 0.0) << where;
    EXPECT_LE(occupancy, 1.0) << where;
    EXPECT_EQ(occupancy >= 0.75, k.fuses) << where << ": " << occupancy;
    EXPECT_EQ(a.stats["schedule"], k.fuses ? "fused" : "wavefront") << where;
    if (k.method != "pt-power") continue;
    const RenderWithStats w = renderWith(k.scene, k.method, "wavefront", dir / "w.exr", "--spp 4");
    ASSERT_EQ(w.exitCode, 0) << w.stderrText;
    EXPECT_FALSE(w.stats.contains("schedule_ray_occupancy")) << "only auto measures";
    EXPECT_EQ(w.stats["extension_rays"], a.stats["extension_rays"]) << where;
    EXPECT_EQ(w.stats["shadow_rays"], a.stats["shadow_rays"]) << where;
    const ComparisonResult c = compareImages(a.mean, a.variance, w.mean, w.variance);
    EXPECT_LT(c.relMse, 1e-9) << where << ": " << c.summary();
  }
  const RenderWithStats aov =
      renderWith(scene("many_lights.gltf"), "pt-power", "auto", dir / "aov.exr", "--spp 2 --aov albedo");
  ASSERT_EQ(aov.exitCode, 0) << aov.stderrText;
  EXPECT_EQ(aov.stats["schedule"], "wavefront");
  EXPECT_FALSE(aov.stats.contains("schedule_ray_occupancy"));
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
