// The Vulkan renderer's two schedules (--schedule wavefront|fused, issue 15): the fused kernel
// traces each path whole with the CPU backend's loop (shared/path_tracer.h), the wavefront passes
// split the same estimator over dispatches; for the same seed both draw the same random numbers in
// the same order, so every shipped scene gives the same paths (the same ray counts) and the same
// image up to float rounding. Fused refuses, in one line, the learning methods and AOVs, whose
// state lives in the wavefront passes.
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
                           const fs::path& out) {
  return renderWithStats(scene + " --width 32 --height 24 --spp 2 --seed 5 --variance --method " + method +
                             " --schedule " + schedule,
                         out, 600);
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
  for (const std::string extra : {"--method cms", "--method learned", "--method pt-power --aov albedo"}) {
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
