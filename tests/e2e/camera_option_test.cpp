// The camera on the command line and the default camera (issue 11, point 5), and the warning for
// an entirely black image (point 2): a file without a camera says which default it got; a closed
// room seen from that default (outside) renders black with a warning instead of in silence;
// --look-from/--look-at/--up/--fov reproduce a file's camera (per-pixel statistical test) and set
// where the viewer starts.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "support/stb_image_reader.h"

#include "output/exr_io.h"
#include "session/options.h"
#include "support/dark_cornell_box.h"
#include "support/run_binary.h"

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

namespace {

// A shipped scene with its camera removed, written into `dir`.
std::string withoutCamera(const std::string& scene, const fs::path& dir) {
  std::ifstream in(fs::path(MIXTRACE_SOURCE_DIR) / "scenes" / scene);
  nlohmann::json j = nlohmann::json::parse(in);
  j.erase("cameras");
  for (auto& node : j["nodes"]) node.erase("camera");
  const fs::path out = dir / ("nocamera_" + scene);
  writeFile(out, j.dump());
  return out.string();
}

double meanOf(const std::string& exr) {
  const Image image = readExr(exr);
  double sum = 0.0;
  for (float v : image.rgb) sum += v;
  return sum / double(image.rgb.size());
}

const std::string kQuick = "render --backend cpu --width 24 --height 18 ";
// many_lights' own camera, as a look-at: inside the room, facing its back wall.
const std::string kInsideManyLights = " --look-from 1.5,1.6,3.85 --look-at 1.5,1.2,0";

}  // namespace

TEST(DefaultCamera, IsNamedAndABlackClosedRoomIsWarnedAbout) {
  const fs::path dir = scratchDir("defaultcamera");
  const std::string room = withoutCamera("many_lights.gltf", dir);
  const RunResult r = runMixtrace(kQuick + "--spp 2 --no-png " + room + " --out " + (dir / "out.exr").string());
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  for (const char* needle : {"has no camera", "default camera", "position 0,1.5,", "target 0,1.5,0", "fov", "--look-from"})
    EXPECT_NE(r.stderrText.find(needle), std::string::npos) << needle << " missing in:\n" << r.stderrText;
  EXPECT_EQ(meanOf((dir / "out.exr").string()), 0.0) << "the default camera was expected to see the room's outside";
  EXPECT_NE(r.stderrText.find("warning: the image is entirely black although the scene has 34 lights"), std::string::npos)
      << r.stderrText;

  // From inside, the room is lit, and nothing is said about blackness.
  const RunResult inside = runMixtrace(kQuick + "--spp 2 --no-png " + room + kInsideManyLights + " --out " +
                                       (dir / "inside.exr").string());
  ASSERT_EQ(inside.exitCode, 0) << inside.stderrText;
  EXPECT_GT(meanOf((dir / "inside.exr").string()), 0.01);
  EXPECT_EQ(inside.stderrText.find("black"), std::string::npos) << inside.stderrText;
  EXPECT_NE(inside.stderrText.find("camera from the command line: position 1.5,1.6,3.85, target 1.5,1.2,0"),
            std::string::npos)
      << inside.stderrText;
}

TEST(DefaultCamera, NoLightsIsSaidAfterTheRender) {
  const fs::path dir = scratchDir("dark");
  writeDarkCornellBox(dir);
  // --env none: without it a scene without lights gets a white environment (environment_render_test).
  const RunResult r = runMixtrace(kQuick + "--spp 1 --no-png --env none " + (dir / "dark.gltf").string() + " --out " +
                                  (dir / "dark.exr").string());
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_NE(r.stderrText.find("warning: the image is entirely black: the scene has no lights"), std::string::npos)
      << r.stderrText;
}

// The Cornell box's camera is at (0, 0.5, 1.85), looking down -Z, yfov 0.7 rad: the same camera
// given on the command line to the box without one renders the same image (z-test per pixel);
// the default camera does not (the test can tell cameras apart).
TEST(CommandLineCamera, ReproducesTheFilesCamera) {
  const fs::path dir = scratchDir("lookat");
  const std::string box = withoutCamera("cornell_box.gltf", dir);
  // 48x36 at 32 spp: the image means are known to a few per cent (compare would say
  // "inconclusive" at the quick tests' size).
  const std::string common = "render --backend cpu --width 48 --height 36 --spp 32 --variance --no-png -q --method pt-power ";
  const std::string original = (dir / "original.exr").string(), given = (dir / "given.exr").string(),
                    framed = (dir / "default.exr").string();
  ASSERT_EQ(runMixtrace(common + std::string(MIXTRACE_SOURCE_DIR) + "/scenes/cornell_box.gltf --out " + original).exitCode, 0);
  const RunResult r = runMixtrace(common + box + " --seed 3 --look-from 0,0.5,1.85 --look-at 0,0.5,-1 --up 0,1,0 --fov " +
                                  std::to_string(0.7 * 180.0 / 3.14159265358979323846) + " --out " + given);
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  ASSERT_EQ(runMixtrace(common + box + " --out " + framed).exitCode, 0);
  const RunResult same = runMixtrace("compare " + given + " " + original);
  EXPECT_EQ(same.exitCode, 0) << same.stdoutText << same.stderrText;
  const RunResult different = runMixtrace("compare " + framed + " " + original);
  EXPECT_EQ(different.exitCode, 1) << different.stdoutText << different.stderrText;
}

TEST(CommandLineCamera, CombinationsThatAreNoCameraAreRefused) {
  const fs::path dir = scratchDir("badcamera");
  const std::string box = withoutCamera("cornell_box.gltf", dir);
  // The default camera's up (0,1,0) and a view straight down.
  const RunResult r = runMixtrace(kQuick + "--spp 1 " + box + " --look-from 0,5,0 --look-at 0,0,0");
  EXPECT_EQ(r.exitCode, 1);
  ASSERT_EQ(r.stderrLines().size(), 1u) << r.stderrText;
  EXPECT_NE(r.stderrText.find("parallel"), std::string::npos) << r.stderrText;
  // The default camera's target is the bounds' centre: a look-from there alone looks nowhere.
  const RunResult centre = runMixtrace(kQuick + "--spp 1 " + box + " --look-from 0,0.5,0");
  EXPECT_EQ(centre.exitCode, 1);
  EXPECT_NE(centre.stderrText.find("same point"), std::string::npos) << centre.stderrText;
}

// The viewer takes render's camera options: it starts inside the room (not black), where its
// default camera would see only the outside.
TEST(CommandLineCamera, TheViewerStartsFromIt) {
  ASSERT_EQ(std::system("command -v xvfb-run > /dev/null"), 0) << "xvfb-run is missing (scripts/setup.sh installs xvfb)";
  const fs::path dir = scratchDir("viewcamera");
  const std::string room = withoutCamera("many_lights.gltf", dir);
  const std::string shot = (dir / "inside.png").string();
  writeFile(dir / "script.txt", "frames 4\nscreenshot " + shot + "\nquit\n");
  const RunResult r = runMixtrace("view " + room + " --width 32 --height 24 --method pt-power" + kInsideManyLights +
                                      " --script " + (dir / "script.txt").string(),
                                  "xvfb-run -a -s '-screen 0 1024x768x24'", 300);
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  int width = 0, height = 0, channels = 0;
  unsigned char* pixels = stbi_load(shot.c_str(), &width, &height, &channels, 3);
  ASSERT_NE(pixels, nullptr) << r.stderrText;
  double sum = 0.0;
  for (size_t i = 0; i < size_t(width) * height * 3; ++i) sum += pixels[i];
  stbi_image_free(pixels);
  EXPECT_GT(sum / (double(width) * height * 3), 8.0) << "the viewer did not start from the command line's camera";
}

// A file camera's aspectRatio (glTF: width / height) decides the film side the command line leaves
// open (issue 14, point 6): --width alone, --height alone, neither (the default width), both (as
// given, nothing said).
TEST(FileCamera, AspectRatioDecidesTheSideTheCommandLineLeavesOpen) {
  const fs::path dir = scratchDir("aspectratio");
  std::ifstream in(fs::path(MIXTRACE_SOURCE_DIR) / "scenes" / "cornell_box.gltf");
  nlohmann::json j = nlohmann::json::parse(in);
  j["cameras"][0]["perspective"]["aspectRatio"] = 2.0;
  const fs::path scene = dir / "wide.gltf";
  writeFile(scene, j.dump());
  struct Case {
    std::string size;
    int width, height;
  };
  const RenderOptions defaults;
  for (const Case& c : {Case{"--width 40", 40, 20}, Case{"--height 15", 30, 15},
                        Case{"", defaults.width, defaults.width / 2}, Case{"--width 24 --height 18", 24, 18}}) {
    const fs::path out = dir / ("out" + std::to_string(c.width) + ".exr");
    const RunResult r = runMixtrace("render --backend cpu --spp 1 --max-depth 1 --no-png " + c.size + " " +
                                    scene.string() + " --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << c.size << ": " << r.stderrText;
    const Image image = readExr(out.string());
    EXPECT_EQ(image.width, c.width) << c.size;
    EXPECT_EQ(image.height, c.height) << c.size;
    const bool changed = c.size != "--width 24 --height 18";
    EXPECT_EQ(r.stderrText.find("aspect ratio 2") != std::string::npos, changed) << c.size << ": " << r.stderrText;
  }
}
