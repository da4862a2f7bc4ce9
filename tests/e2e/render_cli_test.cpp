// End-to-end tests of `mixtrace render` on lavapipe: every shipped scene renders with no
// non-finite sample and zero validation errors; specialised and general pipelines agree; bad
// input fails with one clear line and a non-zero exit.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "output/exr_io.h"
#include "support/run_binary.h"
#include "support/shipped_scenes.h"
#include "support/image_difference.h"

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

namespace {

nlohmann::json readJson(const fs::path& p) {
  std::ifstream f(p);
  return nlohmann::json::parse(f);
}

void expectOneErrorLine(const RunResult& r, const std::string& mustContain) {
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.exitCode, 124) << "timed out (hang)";
  auto lines = r.stderrLines();
  ASSERT_EQ(lines.size(), 1u) << r.stderrText;
  EXPECT_EQ(lines[0].rfind("mixtrace: error: ", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find(mustContain), std::string::npos) << lines[0];
}

}  // namespace

class ShippedScene : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedScene, RendersFiniteWithoutValidationErrors) {
  fs::path dir = scratchDir("scene");
  std::string stem = fs::path(GetParam()).stem().string();
  fs::path exr = dir / (stem + ".exr"), stats = dir / (stem + ".json");
  RunResult r = runMixtrace("render " + GetParam() + " --width 64 --height 48 --spp 4 --max-depth 5 --validation -q --out " +
                            exr.string() + " --stats " + stats.string(), "", 300);
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  nlohmann::json j = readJson(stats);
  EXPECT_EQ(j["non_finite_samples"].get<int>(), 0);
  EXPECT_EQ(j["validation_errors"].get<int>(), 0);
  EXPECT_EQ(j["spp"].get<int>(), 4);
  EXPECT_GT(j["extension_rays"].get<double>(), 0.0);
  ExrMetadata meta;
  Image img = readExr(exr.string(), &meta);
  ASSERT_EQ(img.width, 64);
  ASSERT_EQ(img.height, 48);
  EXPECT_EQ(meta.ints["spp"], 4);
  EXPECT_EQ(meta.strings["method"], "cms");   // the default: its CMS pipelines get validated too
  double sum = 0.0;
  for (float v : img.rgb) {
    ASSERT_TRUE(std::isfinite(v));   // (a control variate may make single pixels negative)
    sum += v;
  }
  EXPECT_GT(sum, 0.0) << "a shipped scene rendered black";
  EXPECT_TRUE(fs::exists(dir / (stem + ".png")));
}

INSTANTIATE_TEST_SUITE_P(Scenes, ShippedScene, ::testing::ValuesIn(shippedScenes()),
                         [](const auto& info) { return fs::path(info.param).stem().string(); });

// The feature set only removes code a scene cannot reach, so for the same seed the specialised
// and the fully general pipelines must produce the same image (up to float re-association).
TEST(Specialization, MatchesGeneralPipelines) {
  fs::path dir = scratchDir("spec");
  for (const std::string& scene : shippedScenes()) {
    std::string common = "render " + scene + " --width 48 --height 36 --spp 2 --seed 7 -q --no-png";
    ASSERT_EQ(runMixtrace(common + " --out " + (dir / "a.exr").string()).exitCode, 0) << scene;
    ASSERT_EQ(runMixtrace(common + " --general-pipelines --out " + (dir / "b.exr").string()).exitCode, 0) << scene;
    Image a = readExr((dir / "a.exr").string()), b = readExr((dir / "b.exr").string());
    ASSERT_EQ(a.rgb.size(), b.rgb.size());
    EXPECT_EQ(differingChannels(a, b, 1e-4f), 0u) << scene;
  }
}

TEST(BadInput, MissingFile) {
  expectOneErrorLine(runMixtrace("render /nonexistent/scene.gltf -q"), "/nonexistent/scene.gltf");
}

TEST(BadInput, MalformedJson) {
  fs::path p = scratchDir("bad") / "malformed.gltf";
  writeFile(p, "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [ {\"primitives\": [");
  expectOneErrorLine(runMixtrace("render " + p.string() + " -q"), "malformed.gltf");
}

TEST(BadInput, TruncatedGlb) {
  fs::path p = scratchDir("bad") / "truncated.glb";
  std::ifstream in(fs::path(MIXTRACE_SOURCE_DIR) / "scenes/textured.glb", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 200u);
  writeFile(p, bytes.substr(0, bytes.size() / 2));
  expectOneErrorLine(runMixtrace("render " + p.string() + " -q"), "truncated.glb");
}

TEST(BadInput, SceneWithoutTriangles) {
  fs::path p = scratchDir("bad") / "empty.gltf";
  writeFile(p, R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"name":"empty"}]})");
  expectOneErrorLine(runMixtrace("render " + p.string() + " -q"), "no triangles");
}

TEST(BadInput, NoVulkanDriver) {
  // Point the loader at a driver manifest that does not exist: no device can be found.
  expectOneErrorLine(runMixtrace("render -q --out /tmp/none.exr", "VK_ICD_FILENAMES=/nonexistent.json VK_DRIVER_FILES=/nonexistent.json"),
                     "Vulkan");
}

TEST(BadInput, ImageTooLargeForMemory) {
  expectOneErrorLine(runMixtrace("render --width 16384 --height 16384 -q --out /tmp/none.exr"), "16384");
}

TEST(BadInput, UnknownOption) { expectOneErrorLine(runMixtrace("render --bogus 3"), "--bogus"); }

TEST(NoLights, RendersBlackWithWarning) {
  // One non-emissive triangle in front of the default camera framing, with --env none (without
  // it a scene without lights gets a white environment: environment_render_test).
  fs::path dir = scratchDir("nolights");
  std::string positions = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";  // (0,0,0) (1,0,0) (0,1,0)
  writeFile(dir / "dark.gltf", R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],
    "bufferViews":[{"buffer":0,"byteLength":36}],
    "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)" + positions + R"("}]})");
  RunResult r = runMixtrace("render " + (dir / "dark.gltf").string() + " --env none --width 16 --height 16 --spp 1 --no-png --out " +
                            (dir / "dark.exr").string());
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_NE(r.stderrText.find("no lights"), std::string::npos) << r.stderrText;
  Image img = readExr((dir / "dark.exr").string());
  for (float v : img.rgb) EXPECT_EQ(v, 0.0f);
}

// cms on a scene whose lights form one cluster runs plain MIS (cms/cms_setup.h), says so, and
// reports it; with several clusters it runs cms; the research method cv runs as asked.
TEST(DefaultMethod, ReducesToPlainMisOnlyWithOneCluster) {
  fs::path dir = scratchDir("reduce");
  auto render = [&](const std::string& scene, const std::string& method, RunResult* out = nullptr) {
    fs::path stats = dir / (scene + method + ".json");
    RunResult r = runMixtrace("render " + std::string(MIXTRACE_SOURCE_DIR) + "/scenes/" + scene +
                              " --width 32 --height 24 --spp 2 --no-png --method " + method + " --out " +
                              (dir / "x.exr").string() + " --stats " + stats.string());
    EXPECT_EQ(r.exitCode, 0) << r.stderrText;
    if (out) *out = r;
    return readJson(stats);
  };
  RunResult cornell;
  nlohmann::json j = render("cornell_box.gltf", "cms", &cornell);
  EXPECT_EQ(j["method"], "cms");
  EXPECT_EQ(j["estimator"], "pt-bvh");
  EXPECT_FALSE(j.contains("cms_clusters"));
  EXPECT_NE(cornell.stderrText.find("one cluster"), std::string::npos) << cornell.stderrText;
  EXPECT_NE(cornell.stderrText.find("pt-bvh's estimator"), std::string::npos) << cornell.stderrText;
  j = render("veach_mis.gltf", "cms");
  EXPECT_EQ(j["estimator"], "cms");
  EXPECT_EQ(j["cms_clusters"].get<int>(), 4);
  j = render("cornell_box.gltf", "cv");
  EXPECT_EQ(j["estimator"], "cv");
  EXPECT_EQ(j["cms_clusters"].get<int>(), 1);
}

// What the reduced cms names is what it renders: several lights in one cluster (--max-clusters 1),
// where pt-bvh and pt-power differ, give pt-bvh's image for the same seed, sample for sample.
TEST(DefaultMethod, ReducedCmsRendersTheEstimatorItNames) {
  fs::path dir = scratchDir("reduce-image");
  auto render = [&](const std::string& method) {
    const fs::path exr = dir / (method + ".exr"), stats = dir / (method + ".json");
    RunResult r = runMixtrace("render " + std::string(MIXTRACE_SOURCE_DIR) +
                              "/scenes/veach_mis.gltf --width 32 --height 24 --spp 4 --seed 7 --max-clusters 1 "
                              "--no-png --method " + method + " --out " + exr.string() + " --stats " + stats.string());
    EXPECT_EQ(r.exitCode, 0) << r.stderrText;
    return std::make_pair(readExr(exr.string()), readJson(stats));
  };
  const auto [cms, cmsStats] = render("cms");
  const auto [bvh, bvhStats] = render("pt-bvh");
  const auto [power, powerStats] = render("pt-power");
  EXPECT_EQ(cmsStats["estimator"], "pt-bvh");
  ASSERT_EQ(cms.rgb.size(), bvh.rgb.size());
  EXPECT_EQ(cms.rgb, bvh.rgb) << "the same estimator and seed trace the same paths";
  EXPECT_NE(cms.rgb, power.rgb) << "the scene tells pt-bvh from pt-power";
}

// The stats say which grid the cells were keyed to: --cells N as given, auto as chosen from the
// footprint (cms/grid_resolution.h), the same on both backends.
TEST(CellGrid, StatsReportTheResolutionUsed) {
  fs::path dir = scratchDir("grid");
  auto render = [&](const std::string& extra) {
    fs::path stats = dir / "stats.json";
    RunResult r = runMixtrace("render " + std::string(MIXTRACE_SOURCE_DIR) +
                              "/scenes/veach_mis.gltf --method cms --width 64 --height 48 --spp 2 --no-png --out " +
                              (dir / "x.exr").string() + " --stats " + stats.string() + " " + extra);
    EXPECT_EQ(r.exitCode, 0) << r.stderrText;
    return readJson(stats);
  };
  nlohmann::json j = render("--cells 21");
  EXPECT_EQ(j["cms_grid_cells"].get<int>(), 21);
  EXPECT_FALSE(j["cms_grid_cells_auto"].get<bool>());
  const nlohmann::json vulkan = render("");
  EXPECT_TRUE(vulkan["cms_grid_cells_auto"].get<bool>());
  const int chosen = vulkan["cms_grid_cells"].get<int>();
  EXPECT_GE(chosen, 4);
  EXPECT_LE(chosen, 256);
  EXPECT_EQ(render("--backend cpu")["cms_grid_cells"].get<int>(), chosen);
  // Twice the image in each direction, about twice the cells.
  j = render("--width 128 --height 96");
  EXPECT_NEAR(j["cms_grid_cells"].get<double>() / chosen, 2.0, 0.25);
}

TEST(TimeBudget, StopsNearTheRequestedTime) {
  fs::path dir = scratchDir("time");
  auto start = std::chrono::steady_clock::now();
  RunResult r = runMixtrace("render --width 64 --height 48 --time 1.0 -q --no-png --out " + (dir / "t.exr").string() +
                            " --stats " + (dir / "t.json").string());
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  nlohmann::json j = readJson(dir / "t.json");
  EXPECT_GE(j["spp"].get<int>(), 1);
  EXPECT_GE(j["render_seconds"].get<double>(), 0.9);
  EXPECT_LT(j["render_seconds"].get<double>(), 3.0);
  EXPECT_LT(wall, 60.0);
}

TEST(DeviceSelection, ByIndexByNameAndUnknown) {
  fs::path dir = scratchDir("device");
  std::string common = "render --width 16 --height 12 --spp 1 -q --no-png --out " + (dir / "d.exr").string();
  EXPECT_EQ(runMixtrace(common + " --device 0").exitCode, 0);
  EXPECT_EQ(runMixtrace(common + " --device llvmpipe").exitCode, 0);
  expectOneErrorLine(runMixtrace(common + " --device no-such-gpu"), "no-such-gpu");
}

TEST(VarianceOutput, WritesVarianceOfTheMean) {
  fs::path dir = scratchDir("variance");
  ASSERT_EQ(runMixtrace("render --width 32 --height 24 --spp 8 -q --no-png --variance --out " + (dir / "v.exr").string()).exitCode, 0);
  Image variance;
  Image mean = readExr((dir / "v.exr").string(), nullptr, &variance);
  ASSERT_EQ(variance.width, 32);
  double positive = 0;
  for (size_t i = 0; i < variance.rgb.size(); ++i) {
    ASSERT_TRUE(std::isfinite(variance.rgb[i]) && variance.rgb[i] >= 0.0f);
    positive += variance.rgb[i] > 0.0f;
  }
  EXPECT_GT(positive, 0.1 * variance.rgb.size()) << "a noisy render has non-zero variance in many pixels";
}

// stderr that is not a terminal (this test's file, a CI log) gets a plain progress line every
// Progress::kLogIntervalSeconds (5 s) instead of nothing; no carriage returns.
TEST(ProgressInLogs, APlainLineEveryFewSeconds) {
  fs::path dir = scratchDir("progress");
  RunResult r = runMixtrace("render --backend cpu --width 16 --height 12 --time 5.6 --no-png --out " +
                            (dir / "p.exr").string());
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  EXPECT_NE(r.stderrText.find("% "), std::string::npos) << "no progress line in:\n" << r.stderrText;
  EXPECT_NE(r.stderrText.find(" spp, "), std::string::npos) << r.stderrText;
  EXPECT_EQ(r.stderrText.find('\r'), std::string::npos) << r.stderrText;
}
