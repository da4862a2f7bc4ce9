// On a device without VK_EXT_shader_atomic_float every method must run: the pipelines are chosen
// by the device's capability, not by the method. MIXTRACE_DISABLE_FLOAT_ATOMICS=1 makes the
// context leave the extension disabled (vulkan/context.h), and the validation layer reports any
// pipeline that still declares the float-atomic-add capability (VUID-RuntimeSpirv-None-06280),
// which is how pt-uniform, pt-power and cms-reduced-to-pt-power failed before.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

#include "session/options.h"
#include "support/run_binary.h"
#include "vulkan/context.h"

namespace mixtrace {
namespace {

class WithoutFloatAtomics : public ::testing::TestWithParam<std::string> {};

TEST_P(WithoutFloatAtomics, RendersWithZeroValidationErrors) {
  const std::string method = GetParam();
  const auto dir = testing::scratchDir("no-float-atomics-" + method);
  const std::string stats = (dir / "stats.json").string();
  // many_lights: several clusters, so cms gathers statistics (on the Cornell box it runs as pt-power).
  for (const char* scene : {"cornell_box.gltf", "many_lights.gltf"}) {
    const testing::RunResult r = testing::runMixtrace(
        "render " + std::string(MIXTRACE_SOURCE_DIR) + "/scenes/" + scene + " --method " + method +
            " --validation --spp 2 --width 16 --height 12 --no-png -q --out " + (dir / "out.exr").string() +
            " --stats " + stats,
        "MIXTRACE_DISABLE_FLOAT_ATOMICS=1");
    EXPECT_EQ(r.exitCode, 0) << method << " on " << scene << ": " << r.stderrText;
    EXPECT_EQ(r.stderrText.find("validation error"), std::string::npos) << r.stderrText;
    std::ifstream in(stats);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j.value("validation_errors", -1), 0);
    // Where statistics are gathered, they went through the compare-and-swap loops.
    // (The pt-* methods, plain MIS, gather none.)
    const bool gathers = method.compare(0, 3, "pt-") != 0 && std::string(scene) == "many_lights.gltf";
    if (gathers) EXPECT_TRUE(j.contains("cms_statistics_atomics")) << method << " gathered no statistics";
    if (j.contains("cms_statistics_atomics")) EXPECT_EQ(j["cms_statistics_atomics"], "cas") << scene;
  }
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, WithoutFloatAtomics, ::testing::ValuesIn(knownMethods()),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

TEST(WithoutFloatAtomics, TheContextOptionLeavesTheExtensionDisabled) {
  ContextOptions options;
  options.floatAtomics = false;
  VulkanContext ctx(options);
  EXPECT_FALSE(ctx.floatAtomics());
}

}  // namespace
}  // namespace mixtrace
