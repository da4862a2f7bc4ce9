// pt-bvh (lights chosen by the light BVH at each shading point) is unbiased, so its image must
// agree within noise with pt-uniform's, on both backends, on the scenes where the selections differ
// most: veach_mis (lights of very different sizes and powers) and many_lights; and punctual, whose
// directional light the BVH leaves out and picks with a fixed probability. A selection pmf
// that differs from the pmf the BSDF sample's MIS weight evaluates (a wrong point or normal kept
// in the path state, a bit-trail walked wrongly) or a light that the BVH's bounds wrongly cut off
// shows up as a difference (mixtrace compare's per-pixel z-test and image means).
#include <filesystem>

#include <gtest/gtest.h>

#include "compare/image_compare.h"
#include "output/exr_io.h"
#include "support/run_binary.h"
#include "support/shipped_scenes.h"
#include "support/test_level.h"

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

namespace {

struct Case {
  std::string scene;
  std::string backend;
};
void PrintTo(const Case& c, std::ostream* os) { *os << c.scene << " " << c.backend; }

std::vector<Case> cases() {
  std::vector<Case> all;
  for (const char* scene : {"veach_mis", "many_lights", "punctual"})
    for (const char* backend : {"vulkan", "cpu"}) all.push_back({scene, backend});
  return all;
}

}  // namespace

class LightBvhAgreement : public ::testing::TestWithParam<Case> {};

TEST_P(LightBvhAgreement, BvhSelectionAgreesWithUniform) {
  const Case& c = GetParam();
  fs::path dir = scratchDir("bvh-agree-" + c.scene + "-" + c.backend);
  const std::string scene = (fs::path(MIXTRACE_SOURCE_DIR) / "scenes" / (c.scene + ".gltf")).string();
  const std::string size = byTestLevel<std::string>("--width 48 --height 36 --spp 256", "--width 128 --height 96 --spp 1024");
  auto render = [&](const std::string& method, int seed, Image& variance) {
    fs::path out = dir / (method + ".exr");
    RunResult r = runMixtrace("render " + scene + " " + size + " --method " + method + " --backend " + c.backend +
                              " --seed " + std::to_string(seed) + " --variance -q --no-png --out " + out.string(), "", 3000);
    EXPECT_EQ(r.exitCode, 0) << r.stderrText;
    return readExr(out.string(), nullptr, &variance);
  };
  Image uniformVariance, bvhVariance;
  Image uniform = render("pt-uniform", 1, uniformVariance);
  Image bvh = render("pt-bvh", 2, bvhVariance);
  ComparisonResult r = compareImages(bvh, bvhVariance, uniform, uniformVariance);
  EXPECT_TRUE(r.agree) << r.summary();
}

INSTANTIATE_TEST_SUITE_P(Scenes, LightBvhAgreement, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.scene + "_" + info.param.backend; });
