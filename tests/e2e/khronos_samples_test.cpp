// Khronos glTF sample models (tests/data/khronos/, each with its licence), rendered by the real
// binary: each test checks what its model exists to show.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "output/exr_io.h"
#include "support/pfm_writer.h"
#include "support/run_binary.h"

namespace {

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

fs::path sample(const std::string& name) {
  return fs::path(MIXTRACE_SOURCE_DIR) / "tests/data/khronos" / name / (name + ".gltf");
}

float luminanceAt(const Image& img, int x, int y) {
  const size_t p = 3 * (size_t(y) * img.width + x);
  return 0.2126f * img.rgb[p] + 0.7152f * img.rgb[p + 1] + 0.0722f * img.rgb[p + 2];
}

// SimpleSparseAccessor: a strip 6 wide and 1 high whose sparse accessor lifts three top vertices to
// y = 2, 3 and 4. Seen face on (camera at (3, 2, 10) towards -Z, 40 degrees: a 7.28-unit square at
// z = 0 on 48x48 pixels), lit from behind the camera (an environment bright only towards +Z, so
// the background is black): the spike at x = 5 reaches y = 3.5, where without the substitution
// there is nothing. The file has no lights and no camera.
class SimpleSparseAccessor : public ::testing::TestWithParam<const char*> {};

TEST_P(SimpleSparseAccessor, TheSubstitutedVerticesShapeTheStrip) {
  const fs::path dir = scratchDir("khronos-sparse");
  std::vector<glm::vec3> map(8 * 4, glm::vec3(0.0f));
  for (int y = 0; y < 4; ++y)
    for (int x = 2; x < 6; ++x) map[size_t(y) * 8 + x] = glm::vec3(1.0f);   // u in [1/4, 3/4): +Z
  writePfm(dir / "behind.pfm", 8, 4, map);
  const fs::path out = dir / "sparse.exr";
  const RunResult r = runMixtrace("render " + sample("SimpleSparseAccessor").string() + " --env " +
                                  (dir / "behind.pfm").string() +
                                  " --look-from 3,2,10 --look-at 3,2,0 --fov 40 --width 48 --height 48 --spp 16 "
                                  "--max-depth 2 --no-png -q --backend " + GetParam() + " --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  const Image img = readExr(out.string());
  auto pixelOf = [](double x, double y) {
    const double half = 10.0 * std::tan(20.0 * 3.14159265358979323846 / 180.0);
    return std::pair<int, int>{int((x - 3.0 + half) / (2.0 * half) * 48.0), int((2.0 + half - y) / (2.0 * half) * 48.0)};
  };
  const auto [spikeX, spikeY] = pixelOf(5.0, 3.4);   // inside the tallest spike only with the substitution
  const auto [gapX, gapY] = pixelOf(2.0, 3.4);       // between spikes: background
  const auto [baseX, baseY] = pixelOf(2.5, 0.5);     // the strip's body
  EXPECT_GT(luminanceAt(img, spikeX, spikeY), 0.05f) << "the spike at x = 5 is missing";
  EXPECT_GT(luminanceAt(img, baseX, baseY), 0.05f);
  EXPECT_EQ(luminanceAt(img, gapX, gapY), 0.0f);
  const auto [aboveX, aboveY] = pixelOf(5.0, 4.6);   // above the spike's top
  EXPECT_EQ(luminanceAt(img, aboveX, aboveY), 0.0f);
}

INSTANTIATE_TEST_SUITE_P(Backends, SimpleSparseAccessor, ::testing::Values("vulkan", "cpu"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
