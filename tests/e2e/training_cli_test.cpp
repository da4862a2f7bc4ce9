// --training: the learning methods' schedule, end to end on both backends, read from the stats
// JSON's count of sample passes that gathered statistics. Doubling (the default) solves after
// samples 1, 3, 7, 15 of a 32-spp render, so samples 1..14 gather (the first only makes the pixel
// estimate); the paper's schedule solves once, after its training samples: 1..15 gather.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/run_binary.h"

namespace fs = std::filesystem;
using namespace mixtrace::testing;

namespace {

int gatheringSpp(const std::string& backend, const std::string& training) {
  const fs::path dir = scratchDir("training-" + backend);
  const fs::path stats = dir / "stats.json";
  const RunResult r = runMixtrace("render " + std::string(MIXTRACE_SOURCE_DIR) +
                                  "/scenes/veach_mis.gltf --method cms --width 24 --height 16 --spp 32 --no-png "
                                  "--backend " + backend + " " + training + " --out " + (dir / "x.exr").string() +
                                  " --stats " + stats.string());
  EXPECT_EQ(r.exitCode, 0) << r.stderrText;
  std::ifstream f(stats);
  const nlohmann::json j = nlohmann::json::parse(f);
  EXPECT_EQ(j["estimator"], "cms");
  return j["cms_gathering_spp"].get<int>();
}

class Training : public ::testing::TestWithParam<std::string> {};

TEST_P(Training, DoublingByDefaultAndThePapersOneSolveWhenAsked) {
  EXPECT_EQ(gatheringSpp(GetParam(), ""), 14);
  EXPECT_EQ(gatheringSpp(GetParam(), "--training doubling"), 14);
  EXPECT_EQ(gatheringSpp(GetParam(), "--training paper"), 15);
  EXPECT_EQ(gatheringSpp(GetParam(), "--training paper --train-spp 8"), 7);
}

INSTANTIATE_TEST_SUITE_P(Backends, Training, ::testing::Values("vulkan", "cpu"));

}  // namespace
