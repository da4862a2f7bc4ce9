// Hostile inputs (issue 11, points 2 and 8-10): each hand-made file in tests/data/hostile/
// (written by its make_hostile.py), and the FIFOs, devices and oversized files made here, must
// end `mixtrace` with one clear error line and a non-zero exit: no crash, no hang, no file read
// from outside the scene's folder, no allocation the file cannot back. The binary runs as a
// subprocess under `timeout` and `ulimit -v`, so a regression fails the test instead of hanging
// or exhausting the machine.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>
#include <vector>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "gltf/gltf_limits.h"
#include "support/run_binary.h"

namespace fs = std::filesystem;
using namespace mixtrace::testing;

namespace {

const fs::path kHostile = fs::path(MIXTRACE_SOURCE_DIR) / "tests/data/hostile";

// 2 GiB of address space: far more than refusing needs, far less than the failures took (the
// /dev/zero read and the 16384^2 PNG each went past 3 GB).
const std::string kLimits = "ulimit -v 2097152;";
constexpr int kTimeoutSeconds = 20;

// Render options that keep an accidental success cheap.
const std::string kTiny = " --backend cpu --width 8 --height 8 --spp 1 -q --no-png";

std::string quoted(const fs::path& p) { return "'" + p.string() + "'"; }

RunResult renderScene(const fs::path& scene, const std::string& prefix = "", const std::string& extra = "") {
  const fs::path out = scratchDir("hostile-out") / "out.exr";
  return runMixtrace("render " + quoted(scene) + kTiny + " --out " + quoted(out) + extra, prefix + kLimits,
                     kTimeoutSeconds);
}

// One line, "mixtrace: error: ...", containing `mustContain`; an exit code that is neither 0,
// nor timeout's 124, nor a signal's 128+.
void expectRefused(const RunResult& r, const std::string& mustContain) {
  EXPECT_NE(r.exitCode, 0) << r.stderrText;
  EXPECT_NE(r.exitCode, 124) << "timed out (hang)";
  EXPECT_LT(r.exitCode, 128) << "killed by a signal (crash)";
  const std::vector<std::string> lines = r.stderrLines();
  ASSERT_EQ(lines.size(), 1u) << r.stderrText;
  EXPECT_EQ(lines[0].rfind("mixtrace: error: ", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find(mustContain), std::string::npos) << lines[0];
}

void writeTriangleBin(const fs::path& p) {
  const float positions[9] = {-1, -1, 0, 1, -1, 0, 0, 1, 0};
  std::ofstream f(p, std::ios::binary);
  f.write(reinterpret_cast<const char*>(positions), sizeof(positions));
}

// A fresh folder holding a copy of hostile file `name`, for cases that add files beside it.
fs::path copyToScratch(const std::string& name, const std::string& folder) {
  const fs::path dir = scratchDir("hostile-" + folder);
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(kHostile / name, dir / name);
  return dir;
}

}  // namespace

// --- 8. Nesting ----------------------------------------------------------------------------------

TEST(HostileInput, DeepNestingInJsonIsRefusedBeforeParsing) {
  expectRefused(renderScene(kHostile / "deep_nesting.gltf"), "nests deeper than 128 levels");
}

TEST(HostileInput, DeepNestingInGlbJsonChunkIsRefusedBeforeParsing) {
  expectRefused(renderScene(kHostile / "deep_nesting.glb"), "nests deeper than 128 levels");
}

// --- 9. URIs -------------------------------------------------------------------------------------

TEST(HostileInput, ParentDirectoryUriIsRefusedWithoutReadingOrSizingIt) {
  const RunResult r = renderScene(kHostile / "uri_parent_escape.gltf");
  expectRefused(r, "points outside the scene's folder");
  EXPECT_EQ(r.stderrText.find("requestedBytes"), std::string::npos) << "reveals the size of a file outside";
}

TEST(HostileInput, ImageUriOutsideTheFolderIsRefused) {
  expectRefused(renderScene(kHostile / "uri_image_escape.gltf"), "points outside the scene's folder");
}

// From the root directory tinygltf's current-directory fallback made "/etc/passwd" resolve.
TEST(HostileInput, AbsoluteUriIsRefusedEvenWhenRenderingFromTheRoot) {
  expectRefused(renderScene(kHostile / "uri_absolute.gltf", "cd / &&"), "is an absolute path");
}

TEST(HostileInput, MissingBufferIsNotLookedUpInTheCurrentDirectory) {
  const fs::path sceneDir = copyToScratch("uri_cwd_fallback.gltf", "cwd-scene");
  const fs::path workDir = scratchDir("hostile-cwd-work");
  writeTriangleBin(workDir / "only_in_working_directory.bin");
  expectRefused(renderScene(sceneDir / "uri_cwd_fallback.gltf", "cd " + quoted(workDir) + " &&"),
                "File not found : only_in_working_directory.bin");
}

// Inside the folder the message names the URI, not the absolute path tinygltf built from it.
TEST(HostileInput, SizeMismatchNamesTheUriNotTheResolvedPath) {
  const fs::path dir = copyToScratch("uri_fifo.gltf", "mismatch");
  { std::ofstream(dir / "fifo.bin") << "four"; }
  const RunResult r = renderScene(dir / "uri_fifo.gltf");
  expectRefused(r, "fifo.bin");
  EXPECT_EQ(r.stderrText.find((fs::canonical(dir) / "fifo.bin").string()), std::string::npos) << r.stderrText;
}

TEST(HostileInput, AssetRootAdmitsFilesInASiblingFolder) {
  const fs::path root = scratchDir("hostile-root");
  fs::remove_all(root);
  fs::create_directories(root / "scene");
  fs::create_directories(root / "shared");
  writeTriangleBin(root / "shared/triangle.bin");
  std::string text = readText(kHostile / "uri_cwd_fallback.gltf");
  text.replace(text.find("only_in_working_directory.bin"), 29, "../shared/triangle.bin");
  writeFile(root / "scene/scene.gltf", text);
  expectRefused(renderScene(root / "scene/scene.gltf"), "URI '../shared/triangle.bin' points outside");
  const RunResult allowed = renderScene(root / "scene/scene.gltf", "", " --asset-root " + quoted(root));
  EXPECT_EQ(allowed.exitCode, 0) << allowed.stderrText;
}

// The check is on the resolved path: a link inside the folder does not lead out of it.
TEST(HostileInput, SymbolicLinkOutOfTheFolderIsRefused) {
  const fs::path outside = scratchDir("hostile-link-outside");
  writeTriangleBin(outside / "triangle.bin");
  const fs::path dir = copyToScratch("uri_fifo.gltf", "link");
  fs::create_symlink(outside / "triangle.bin", dir / "fifo.bin");
  expectRefused(renderScene(dir / "uri_fifo.gltf"), "URI 'fifo.bin' points outside the scene's folder");
}

TEST(HostileInput, FifoBufferIsRefusedWithoutBlocking) {
  const fs::path dir = copyToScratch("uri_fifo.gltf", "fifo-uri");
  ASSERT_EQ(::mkfifo((dir / "fifo.bin").c_str(), 0600), 0);
  expectRefused(renderScene(dir / "uri_fifo.gltf"), "URI 'fifo.bin' is a FIFO, not a regular file");
}

// --- 10. Sizes and file kinds --------------------------------------------------------------------

TEST(HostileInput, FifoSceneIsRefusedWithoutBlocking) {
  const fs::path dir = scratchDir("hostile-fifo-scene");
  fs::remove(dir / "scene.gltf");
  ASSERT_EQ(::mkfifo((dir / "scene.gltf").c_str(), 0600), 0);
  expectRefused(renderScene(dir / "scene.gltf"), "is a FIFO, not a regular file");
}

TEST(HostileInput, DeviceSceneIsRefusedUnread) {
  expectRefused(renderScene("/dev/zero"), "/dev/zero: is a character device, not a regular file");
}

TEST(HostileInput, SceneOverTheSizeLimitIsRefusedUnread) {
  const fs::path big = scratchDir("hostile-big") / "big.gltf";
  { std::ofstream(big) << "{"; }
  fs::resize_file(big, mixtrace::gltf::kMaxFileBytes + 1);  // sparse: costs no disk
  expectRefused(renderScene(big), "bytes, more than the 1024 MiB limit");
  fs::remove(big);
}

TEST(HostileInput, PngClaimingHugeDimensionsIsRefusedBeforeDecoding) {
  expectRefused(renderScene(kHostile / "huge_claim_png.gltf"), "(huge_claim.png) is 16384x16384, more than the");
}

TEST(HostileInput, ExrClaimingHugeDimensionsIsRefusedBeforeAllocating) {
  const std::string exr = quoted(kHostile / "huge_claim.exr");
  expectRefused(runMixtrace("compare " + exr + " " + exr, kLimits, kTimeoutSeconds),
                "claims 20000x20000 pixels, more than 16384 on a side");
}

TEST(HostileInput, ExrClaimingMoreThanItsBytesCanHoldIsRefused) {
  const std::string exr = quoted(kHostile / "huge_claim_16k.exr");
  expectRefused(runMixtrace("compare " + exr + " " + exr, kLimits, kTimeoutSeconds),
                "claims 16384x16384 pixels, more than its");
}

TEST(HostileInput, FifoExrIsRefusedWithoutBlocking) {
  const fs::path fifo = scratchDir("hostile-fifo-exr") / "a.exr";
  fs::remove(fifo);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expectRefused(runMixtrace("compare " + quoted(fifo) + " " + quoted(fifo), kLimits, kTimeoutSeconds),
                "not a regular file");
}

TEST(HostileInput, AccessorWithoutDataClaimingMillionsOfVerticesIsRefused) {
  expectRefused(renderScene(kHostile / "dataless_accessor.gltf"), "has no bufferView but claims 30000000 elements");
}

// --- 2. Finite doubles beyond float --------------------------------------------------------------

TEST(HostileInput, EmissiveStrengthBeyondFloatIsRefused) {
  expectRefused(renderScene(kHostile / "emissive_strength_1e39.gltf"),
                "materials[0].emissiveStrength 1e+39 does not fit in a float");
}

TEST(HostileInput, LightIntensityBeyondFloatIsRefused) {
  expectRefused(renderScene(kHostile / "light_intensity_1e39.gltf"),
                "lights[0].intensity 1e+39 does not fit in a float");
}

TEST(HostileInput, CameraTranslationBeyondFloatIsRefused) {
  expectRefused(renderScene(kHostile / "camera_translation_1e300.gltf"),
                "nodes[1].translation[2] 1e+300 does not fit in a float");
}

TEST(HostileInput, VerticesCarriedBeyondFloatByNestedTransformsAreRefused) {
  expectRefused(renderScene(kHostile / "nested_scale_1e60.gltf"), "after its node's transform 1e+60 does not fit");
}
