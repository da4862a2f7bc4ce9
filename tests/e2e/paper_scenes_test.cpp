// The paper's scenes, converted from the reference implementation's SeeSharp files
// (scenes/paper/convert_seesharp.py), load and render on Vulkan: the plain path tracer and cms give
// finite, non-black images, and uniform and power-proportional light selection, both unbiased,
// agree within noise (`mixtrace compare`'s rule: per-pixel z-test plus image-mean test, with
// enough power to see a 10 % difference of the image means). A converted scene whose emitters
// face the wrong way, whose camera looks into a wall, or that the loader refuses fails here.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "compare/image_compare.h"
#include "output/exr_io.h"
#include "support/run_binary.h"
#include "support/test_level.h"

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

namespace {

// scenes/paper/<Scene>/<Scene>.gltf, sorted.
std::vector<std::string> paperScenes() {
  std::vector<std::string> scenes;
  for (auto& e : fs::directory_iterator(fs::path(MIXTRACE_SOURCE_DIR) / "scenes" / "paper")) {
    const fs::path gltf = e.path() / (e.path().filename().string() + ".gltf");
    if (e.is_directory() && fs::exists(gltf)) scenes.push_back(gltf.string());
  }
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

Image render(const std::string& scene, const std::string& method, int seed, const std::string& size,
             const fs::path& out, Image* standardError) {
  RunResult r = runMixtrace("render " + scene + " " + size + " --method " + method + " --seed " +
                                std::to_string(seed) + " --variance -q --no-png --out " + out.string(),
                            "", 3000);
  EXPECT_EQ(r.exitCode, 0) << r.stderrText;
  // The converter writes files the loader takes without complaint (no dropped triangles, no
  // clamped factors): a warning means the conversion and the loader disagree about something.
  EXPECT_EQ(r.stderrText, "") << method;
  return readExr(out.string(), nullptr, standardError);
}

}  // namespace

class PaperScenes : public ::testing::TestWithParam<std::string> {};

TEST_P(PaperScenes, PlainAndCmsRendersAreFiniteAndLit) {
  fs::path dir = scratchDir("paper-" + fs::path(GetParam()).stem().string());
  for (const char* method : {"pt-uniform", "cms"}) {
    Image se;
    Image image = render(GetParam(), method, 1, "--width 32 --height 24 --spp 32", dir / (std::string(method) + ".exr"), &se);
    ASSERT_FALSE(image.rgb.empty()) << method;
    size_t lit = 0, nonFinite = 0;
    for (float v : image.rgb) {
      if (!std::isfinite(v)) ++nonFinite;
      else if (v > 0.0f) ++lit;
    }
    EXPECT_EQ(nonFinite, 0u) << method;
    // Every scene is an interior lit from inside: nearly every pixel sees some light.
    EXPECT_GT(double(lit) / image.rgb.size(), 0.9) << method << ": " << lit << " of " << image.rgb.size();
  }
}

TEST_P(PaperScenes, UniformAndPowerSelectionAgree) {
  fs::path dir = scratchDir("paper-agree-" + fs::path(GetParam()).stem().string());
  const std::string size = byTestLevel<std::string>("--width 32 --height 24 --spp 256", "--width 96 --height 72 --spp 1024");
  Image se[2];
  Image a = render(GetParam(), "pt-uniform", 1, size, dir / "uniform.exr", &se[0]);
  Image b = render(GetParam(), "pt-power", 2, size, dir / "power.exr", &se[1]);
  ComparisonResult r = compareImages(a, se[0], b, se[1]);
  EXPECT_TRUE(r.agree) << r.summary();
  EXPECT_FALSE(r.inconclusive) << "too few samples to see a 10 % difference: " << r.summary();
}

INSTANTIATE_TEST_SUITE_P(Converted, PaperScenes, ::testing::ValuesIn(paperScenes()),
                         [](const auto& info) { return fs::path(info.param).stem().string(); });
