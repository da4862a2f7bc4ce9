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

// DiningRoom2's sky, scenes/paper/DiningRoom2/Skydome.exr (the source's environment map in
// mixtrace's convention, written by convert_seesharp.py; the tests above render the scene without
// it): the file is there and loads without a word; looking out of the window (in the +X wall,
// x = 5.1, y 2 to 6.8) the sky is there between the blinds with it and black without it; and from
// the paper's camera it adds light to the room (measured with the CPU backend, same paths: +7.6 %,
// +8.1 %, +7.6 % of the image mean for seeds 1, 2, 3; the window view 0.42 against 0.0005).
TEST(PaperSceneEnvironment, DiningRoom2SkyLightsTheRoom) {
  const fs::path folder = fs::path(MIXTRACE_SOURCE_DIR) / "scenes" / "paper" / "DiningRoom2";
  const std::string scene = (folder / "DiningRoom2.gltf").string();
  const std::string sky = (folder / "Skydome.exr").string();
  ASSERT_TRUE(fs::exists(sky)) << sky;
  const fs::path dir = scratchDir("paper-sky");
  auto mean = [](const Image& image) {
    double sum = 0.0;
    for (float v : image.rgb) sum += v;
    return sum / double(image.rgb.size());
  };
  auto finite = [](const Image& image) {
    return std::all_of(image.rgb.begin(), image.rgb.end(), [](float v) { return std::isfinite(v); });
  };
  const std::string window = " --look-from 3,4.3,-0.6 --look-at 10,4.3,-0.6 --up 0,1,0 --fov 30";
  Image se;
  Image out = render(scene + window + " --env " + sky, "pt-power", 1, "--width 32 --height 24 --spp 16",
                     dir / "window-sky.exr", &se);
  Image dark = render(scene + window + " --env none", "pt-power", 1, "--width 32 --height 24 --spp 16",
                      dir / "window-none.exr", &se);
  ASSERT_FALSE(out.rgb.empty());
  ASSERT_FALSE(dark.rgb.empty());
  EXPECT_TRUE(finite(out));
  size_t skyPixels = 0;
  for (size_t i = 0; i < out.pixelCount(); ++i)
    if (out.rgb[3 * i] + out.rgb[3 * i + 1] + out.rgb[3 * i + 2] > 0.15f) ++skyPixels;
  EXPECT_GT(double(skyPixels) / double(out.pixelCount()), 0.3) << skyPixels << " of " << out.pixelCount();
  EXPECT_GT(mean(out), 0.2);
  EXPECT_LT(mean(dark), 0.01);

  Image lit = render(scene + " --env " + sky, "pt-power", 1, "--width 32 --height 24 --spp 64", dir / "room-sky.exr", &se);
  Image lamps = render(scene + " --env none", "pt-power", 1, "--width 32 --height 24 --spp 64", dir / "room-none.exr", &se);
  ASSERT_FALSE(lit.rgb.empty());
  ASSERT_FALSE(lamps.rgb.empty());
  EXPECT_TRUE(finite(lit));
  EXPECT_GT(mean(lit), 1.03 * mean(lamps)) << mean(lit) << " against " << mean(lamps) << " with the lamps alone";
}
