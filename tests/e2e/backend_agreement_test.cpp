// The Vulkan wavefront renderer against the CPU reference on every shipped scene and method.
// With the same seed both draw the same random numbers in the same order, so the same paths
// are traced: the images must match path by path, up to float rounding that occasionally sends
// a ray the other way at an edge. This catches any logic difference between the wavefront
// orchestration (queues, indirect dispatch, traversal on the GPU) and the straightforward loop.
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>

#include "compare/image_compare.h"
#include "output/exr_io.h"
#include "support/run_binary.h"
#include "support/shipped_scenes.h"
#include "support/test_level.h"
#include "support/image_difference.h"

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

namespace {

struct Case {
  std::string scene;
  std::string method;
};
void PrintTo(const Case& c, std::ostream* os) { *os << sceneStem(c.scene) << " " << c.method; }

std::vector<Case> allCases() {
  std::vector<Case> cases;
  for (const std::string& s : shippedScenes())
    for (const char* m : {"pt-uniform", "pt-power", "pt-bvh"}) cases.push_back({s, m});
  return cases;
}

Image renderWith(const Case& c, const std::string& backend, const std::string& extra, const fs::path& out,
                 Image* variance = nullptr) {
  RunResult r = runMixtrace("render " + c.scene + " --method " + c.method + " --backend " + backend +
                            " -q --no-png " + extra + " --out " + out.string(), "", 3000);
  EXPECT_EQ(r.exitCode, 0) << r.stderrText;
  return readExr(out.string(), nullptr, variance);
}

}  // namespace

class BackendAgreement : public ::testing::TestWithParam<Case> {};

TEST_P(BackendAgreement, SameSeedTracesTheSamePaths) {
  fs::path dir = scratchDir("backends");
  const std::string extra = "--width 64 --height 48 --spp 2 --seed 3";
  Image gpu = renderWith(GetParam(), "vulkan", extra, dir / "gpu.exr");
  Image cpu = renderWith(GetParam(), "cpu", extra, dir / "cpu.exr");
  ASSERT_EQ(gpu.rgb.size(), cpu.rgb.size());
  const size_t differing = differingChannels(gpu, cpu, 1e-3f, 1e-2f);
  // A few paths diverge where a ray grazes an edge and float rounding differs between the two.
  EXPECT_LE(differing, gpu.rgb.size() / 200) << differing << " of " << gpu.rgb.size() << " channels differ";
}

TEST_P(BackendAgreement, IndependentImagesAgreeStatistically) {
  fs::path dir = scratchDir("backends-stat");
  const std::string size = byTestLevel<std::string>("--width 48 --height 36 --spp 128", "--width 128 --height 96 --spp 512");
  Image gpuVar, cpuVar;
  Image gpu = renderWith(GetParam(), "vulkan", size + " --variance --seed 11", dir / "gpu.exr", &gpuVar);
  Image cpu = renderWith(GetParam(), "cpu", size + " --variance --seed 12", dir / "cpu.exr", &cpuVar);
  ComparisonResult r = compareImages(gpu, gpuVar, cpu, cpuVar);
  EXPECT_TRUE(r.agree) << r.summary();
}

INSTANTIATE_TEST_SUITE_P(ScenesAndMethods, BackendAgreement, ::testing::ValuesIn(allCases()), [](const auto& info) {
  std::string name = sceneStem(info.param.scene) + "_" + info.param.method;
  for (char& ch : name)
    if (ch == '-') ch = '_';
  return name;
});
