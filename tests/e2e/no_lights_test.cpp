// A render with cms of a scene without lights (--env none: no default environment) says so, and
// not that its lights form one cluster
// (the note itself: tests/unit/cms/cms_setup_test.cpp).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

#include "support/dark_cornell_box.h"
#include "support/run_binary.h"

namespace mixtrace {
namespace {

// The Cornell box with its light switched off, rendered with cms.
TEST(CmsSetup, RenderOfASceneWithoutLightsSaysSo) {
  const auto dir = testing::scratchDir("cms-no-lights");
  testing::writeDarkCornellBox(dir);
  const testing::RunResult r = testing::runMixtrace("render " + (dir / "dark.gltf").string() +
                                                    " --method cms --env none --spp 1 --width 8 --height 8 --no-png --out " +
                                                    (dir / "dark.exr").string());
  EXPECT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_NE(r.stderrText.find("cms: the scene has no lights"), std::string::npos) << r.stderrText;
  EXPECT_EQ(r.stderrText.find("one cluster"), std::string::npos) << r.stderrText;
}

}  // namespace
}  // namespace mixtrace
