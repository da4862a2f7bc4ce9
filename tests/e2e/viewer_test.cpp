// The viewer end to end, without a GPU: under Xvfb on lavapipe, `mixtrace view` replays a script
// (keys, mouse drags, a resize, screenshots, a save) with the validation layer on. The shots must
// show the scene (not black), change when the method, the debug view or the camera change, show
// two methods side by side in the split view, and follow the resize; the save key writes the EXR
// and PNG; the viewer exits cleanly with zero validation errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "support/stb_image_reader.h"

#include "output/exr_io.h"
#include "support/run_binary.h"

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

namespace {

struct Shot {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  double mean() const {
    double s = 0.0;
    for (unsigned char c : rgb) s += c;
    return rgb.empty() ? 0.0 : s / double(rgb.size());
  }
  // Mean absolute difference per channel, 0..255, over columns [x0, x1).
  double difference(const Shot& o, int x0 = 0, int x1 = -1) const {
    if (x1 < 0) x1 = width;
    double s = 0.0;
    size_t n = 0;
    for (int y = 0; y < height; ++y)
      for (int x = x0; x < x1; ++x)
        for (int c = 0; c < 3; ++c, ++n) {
          const size_t i = (size_t(y) * width + x) * 3 + c;
          s += std::abs(int(rgb[i]) - int(o.rgb[i]));
        }
    return n ? s / double(n) : 0.0;
  }
  size_t distinctColours() const {
    std::set<unsigned> colours;
    for (size_t i = 0; i + 2 < rgb.size(); i += 3) colours.insert(rgb[i] | (rgb[i + 1] << 8) | (rgb[i + 2] << 16));
    return colours.size();
  }
};

Shot load(const fs::path& p) {
  Shot s;
  int channels = 0;
  unsigned char* data = stbi_load(p.string().c_str(), &s.width, &s.height, &channels, 3);
  if (!data) return s;
  s.rgb.assign(data, data + size_t(s.width) * s.height * 3);
  stbi_image_free(data);
  return s;
}

}  // namespace

TEST(Viewer, ScriptedSessionUnderXvfb) {
  ASSERT_EQ(std::system("command -v xvfb-run > /dev/null"), 0) << "xvfb-run is missing (scripts/setup.sh installs xvfb)";
  const fs::path dir = scratchDir("viewer");
  const auto shot = [&](const std::string& name) { return (dir / (name + ".png")).string(); };
  writeFile(dir / "script.txt",
            "frames 6\nscreenshot " + shot("cms") +            // the default method, cms
            "\nkey 1\nframes 6\nscreenshot " + shot("uniform") +   // pt-uniform
            "\nkey 5\nkey f3\nframes 1\nscreenshot " + shot("cells") +   // cms, the cells of the first hits
            "\nkey f1\ndrag left 60 0\nframes 4\nscreenshot " + shot("orbited") +
            "\nkey r\nkey shift+2\nframes 6\nscreenshot " + shot("split") +   // cms | pt-power
            "\nkey v\nresize 400 300\nframes 2\nscreenshot " + shot("resized") +
            "\nkey p\nquit\n");
  const std::string scene = std::string(MIXTRACE_SOURCE_DIR) + "/scenes/veach_mis.gltf";
  // --cells 16: at 64x48 auto would choose a coarser grid than the cell view's check was set for.
  RunResult r = runMixtrace("view " + scene + " --width 64 --height 48 --cells 16 --validation --out " + (dir / "saved.exr").string() +
                                " --script " + (dir / "script.txt").string(),
                            "xvfb-run -a -s '-screen 0 1024x768x24'", 300);
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_NE(r.stderrText.find("view: 0 validation errors"), std::string::npos) << r.stderrText;

  const Shot cms = load(shot("cms")), uniform = load(shot("uniform")), cells = load(shot("cells")),
             orbited = load(shot("orbited")), split = load(shot("split")), resized = load(shot("resized"));
  ASSERT_EQ(cms.width, 640) << "the window is the film scaled by 10";
  ASSERT_EQ(cms.height, 480);
  EXPECT_GT(cms.mean(), 8.0) << "the image is black";
  EXPECT_GT(cms.difference(uniform), 0.5) << "switching the method changed nothing on screen";
  EXPECT_LT(cms.difference(uniform), 40.0) << "the two methods should show the same scene";
  EXPECT_GT(cells.distinctColours(), 20u) << "the cell view shows few cells";
  EXPECT_GT(cells.difference(cms), 10.0);
  EXPECT_GT(orbited.difference(cms), 5.0) << "orbiting did not move the camera";
  // The split view: a white divider at the middle, cms on the left, pt-power on the right.
  ASSERT_EQ(split.width, 640);
  const size_t divider = (size_t(240) * 640 + 320) * 3;
  EXPECT_EQ(split.rgb[divider], 255);
  EXPECT_EQ(split.rgb[divider + 1], 255);
  EXPECT_LT(split.difference(cms, 0, 320), split.difference(uniform, 0, 320) + 40.0);
  EXPECT_GT(split.mean(), 8.0);
  EXPECT_EQ(resized.width, 400) << "the resize did not reach the swapchain";
  EXPECT_EQ(resized.height, 300);
  EXPECT_GT(resized.mean(), 8.0);
  // P saved the film as render does: an EXR (with its header) and the PNG beside it.
  ASSERT_TRUE(fs::exists(dir / "saved.exr")) << r.stderrText;
  EXPECT_TRUE(fs::exists(dir / "saved.png"));
  ExrMetadata meta;
  const Image saved = readExr((dir / "saved.exr").string(), &meta);
  EXPECT_EQ(saved.width, 64);
  EXPECT_EQ(meta.strings["method"], "cms");
  EXPECT_GT(meta.ints["spp"], 0);
}

// Under --schedule fused the learning methods fuse too (shared/cms_path_tracer.h): a key switches
// to cms, which learns cells, and the cell view shows the cells of the first hits the fused kernel
// recorded (it was the wavefront's shade pass alone that wrote them).
TEST(Viewer, FusedScheduleRunsLearningMethodsWithTheirCellViews) {
  ASSERT_EQ(std::system("command -v xvfb-run > /dev/null"), 0) << "xvfb-run is missing (scripts/setup.sh installs xvfb)";
  const fs::path dir = scratchDir("viewer-fused");
  writeFile(dir / "script.txt", "frames 2\nkey 5\nframes 2\nscreenshot " + (dir / "cms.png").string() +
                                    "\nkey f3\nframes 1\nscreenshot " + (dir / "cells.png").string() + "\nquit\n");
  const std::string scene = std::string(MIXTRACE_SOURCE_DIR) + "/scenes/veach_mis.gltf";
  RunResult r = runMixtrace("view " + scene + " --method pt-power --schedule fused --width 64 --height 48 --cells 16 "
                                "--validation --script " + (dir / "script.txt").string(),
                            "xvfb-run -a -s '-screen 0 1024x768x24'", 300);
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_NE(r.stderrText.find("view: 0 validation errors"), std::string::npos) << r.stderrText;
  EXPECT_EQ(r.stderrText.find("wavefront"), std::string::npos) << r.stderrText;
  const Shot cms = load((dir / "cms.png").string()), cells = load((dir / "cells.png").string());
  EXPECT_GT(cms.mean(), 8.0) << "the image is black";
  EXPECT_GT(cells.distinctColours(), 20u) << "the cell view shows few cells";
  EXPECT_GT(cells.difference(cms), 10.0);
}

TEST(Viewer, WithoutADisplayItFailsWithOneLine) {
  RunResult r = runMixtrace("view --width 32 --height 24", "env -u DISPLAY -u WAYLAND_DISPLAY", 60);
  EXPECT_EQ(r.exitCode, 1);
  auto lines = r.stderrLines();
  ASSERT_EQ(lines.size(), 1u) << r.stderrText;
  EXPECT_NE(lines[0].find("no display"), std::string::npos) << lines[0];
}

TEST(Viewer, RejectsOptionsItCannotHonour) {
  for (const std::string& args : {"view --backend cpu", "view --time 2", "view --script"}) {
    RunResult r = runMixtrace(args, "", 60);
    EXPECT_EQ(r.exitCode, 1) << args;
    EXPECT_EQ(r.stderrLines().size(), 1u) << args << ": " << r.stderrText;
  }
}
