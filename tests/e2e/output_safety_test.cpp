// Output that cannot destroy work (issue 11, point 6): the format follows --out's extension;
// unknown formats, outputs that name the same file (or the scene, or a file it reads) and
// unwritable directories are refused before rendering; every file is written under a temporary
// name and renamed, so the old file is never truncated in place. Also the EXR header's estimator
// and the "1 light" line (point 16). CPU backend, tiny images: seconds.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include "output/atomic_file.h"
#include "output/exr_io.h"
#include "output/png_preview.h"
#include "support/run_binary.h"
#include "util/error.h"

namespace fs = std::filesystem;
using namespace mixtrace;
using namespace mixtrace::testing;

namespace {

const std::string kQuick = "render --backend cpu --width 16 --height 12 --spp 1 ";

std::string bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

bool startsWith(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }
const std::string kExrMagic("\x76\x2f\x31\x01", 4);
const std::string kPngMagic("\x89PNG", 4);
const std::string kJpegMagic("\xff\xd8\xff", 3);

// Refused before rendering: exit 1, one error line mentioning `needle`, and no "scene ...:" line
// (printed once set-up is done, just before the sample passes) because nothing was loaded.
void expectRefusedBeforeRendering(const std::string& args, const std::string& needle) {
  const RunResult r = runMixtrace(args);   // not -q: an info line would show that it rendered
  EXPECT_EQ(r.exitCode, 1) << args << "\n" << r.stderrText;
  const auto lines = r.stderrLines();
  ASSERT_EQ(lines.size(), 1u) << args << "\n" << r.stderrText;
  EXPECT_TRUE(startsWith(lines[0], "mixtrace: error: ")) << lines[0];
  EXPECT_NE(lines[0].find(needle), std::string::npos) << lines[0];
}

ino_t inodeOf(const fs::path& p) {
  struct stat s {};
  return ::stat(p.c_str(), &s) == 0 ? s.st_ino : 0;
}

}  // namespace

TEST(OutputFormat, FollowsTheExtension) {
  const fs::path dir = scratchDir("format");
  // .exr: float data, the PNG preview beside it.
  ASSERT_EQ(runMixtrace(kQuick + "-q --out " + (dir / "a.exr").string()).exitCode, 0);
  EXPECT_TRUE(startsWith(bytesOf(dir / "a.exr"), kExrMagic));
  EXPECT_TRUE(startsWith(bytesOf(dir / "a.png"), kPngMagic));
  // .png and .jpg (any case): the tonemapped image only, no EXR bytes anywhere.
  ASSERT_EQ(runMixtrace(kQuick + "-q --out " + (dir / "b.png").string()).exitCode, 0);
  EXPECT_TRUE(startsWith(bytesOf(dir / "b.png"), kPngMagic));
  EXPECT_FALSE(fs::exists(dir / "b.exr"));
  for (const char* name : {"c.jpg", "d.JPEG"}) {
    const RunResult r = runMixtrace(kQuick + "-q --out " + (dir / name).string());
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    EXPECT_TRUE(startsWith(bytesOf(dir / name), kJpegMagic)) << name << " does not hold JPEG data";
  }
  EXPECT_FALSE(fs::exists(dir / "c.png")) << "a JPEG output has no preview beside it";
  // Anything else: refused before rendering, nothing written.
  for (const char* name : {"e.tiff", "noextension", "f.exr.bak"}) {
    expectRefusedBeforeRendering(kQuick + "--out " + (dir / name).string(), "extension");
    EXPECT_FALSE(fs::exists(dir / name)) << name;
  }
  expectRefusedBeforeRendering(kQuick + "--variance --out " + (dir / "g.png").string(), "--variance");
}

TEST(OutputFormat, HeaderNamesTheEstimatorThatRan) {
  // cms on the Cornell box (one light cluster) runs pt-bvh's estimator (its own default
  // selection): the header says both.
  const fs::path dir = scratchDir("estimator");
  const RunResult r = runMixtrace(kQuick + "--no-png --out " + (dir / "e.exr").string());
  ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  ExrMetadata meta;
  readExr((dir / "e.exr").string(), &meta);
  EXPECT_EQ(meta.strings["method"], "cms");
  EXPECT_EQ(meta.strings["estimator"], "pt-bvh");
  EXPECT_NE(r.stderrText.find(" 1 light;"), std::string::npos) << r.stderrText;
  EXPECT_EQ(r.stderrText.find("1 lights"), std::string::npos) << r.stderrText;
}

TEST(OutputSafety, OutputsNamingTheSameFileAreRefused) {
  const fs::path dir = scratchDir("samefile");
  const std::string exr = (dir / "x.exr").string();
  expectRefusedBeforeRendering(kQuick + "--out " + exr + " --stats " + exr, "same file");
  expectRefusedBeforeRendering(kQuick + "--out " + exr + " --stats " + (dir / "x.png").string(), "PNG preview");
  // Spelt differently: "./", "..", a symbolic link, a hard link.
  fs::create_directories(dir / "sub");
  expectRefusedBeforeRendering(kQuick + "--out " + exr + " --stats " + (dir / "sub/../x.exr").string(), "same file");
  writeFile(dir / "x.png", "an earlier preview");
  fs::create_symlink(dir / "x.png", dir / "link.json");
  fs::create_hard_link(dir / "x.png", dir / "hard.json");
  for (const char* other : {"link.json", "hard.json"})
    expectRefusedBeforeRendering(kQuick + "--out " + exr + " --stats " + (dir / other).string(), "same file");
  EXPECT_FALSE(fs::exists(exr));
  EXPECT_EQ(bytesOf(dir / "x.png"), "an earlier preview");
  // With --no-png the preview's name is free.
  EXPECT_EQ(runMixtrace(kQuick + "-q --no-png --out " + exr + " --stats " + (dir / "x.png").string()).exitCode, 0);
}

TEST(OutputSafety, TheSceneAndItsFilesAreNeverOverwritten) {
  const fs::path dir = scratchDir("inputs");
  // The Cornell box with its buffer moved out into a file beside it.
  nlohmann::json scene = nlohmann::json::parse(bytesOf(fs::path(MIXTRACE_SOURCE_DIR) / "scenes/cornell_box.gltf"));
  const std::string uri = scene["buffers"][0]["uri"];
  const std::string base64 = uri.substr(uri.find(',') + 1);
  const std::string decoder = "base64 -d > '" + (dir / "geometry data.bin").string() + "'";
  FILE* pipe = ::popen(decoder.c_str(), "w");
  ASSERT_NE(pipe, nullptr);
  std::fwrite(base64.data(), 1, base64.size(), pipe);
  ASSERT_EQ(::pclose(pipe), 0);
  scene["buffers"][0]["uri"] = "geometry%20data.bin";
  writeFile(dir / "room.gltf", scene.dump());
  const std::string room = (dir / "room.gltf").string();
  ASSERT_EQ(runMixtrace(kQuick + "-q --no-png " + room + " --out " + (dir / "ok.exr").string()).exitCode, 0)
      << "the scene with an external buffer renders";

  const std::string sceneBefore = bytesOf(room), bufferBefore = bytesOf(dir / "geometry data.bin");
  expectRefusedBeforeRendering(kQuick + room + " --stats " + room, "the scene");
  expectRefusedBeforeRendering(kQuick + room + " --stats '" + (dir / "geometry data.bin").string() + "'",
                               "the scene's file");
  // A scene whose name has an image's extension (glTF is told by its content).
  fs::copy_file(room, dir / "scene.png");
  expectRefusedBeforeRendering(kQuick + (dir / "scene.png").string() + " --out " + (dir / "scene.png").string(),
                               "would overwrite the scene");
  EXPECT_EQ(bytesOf(room), sceneBefore);
  EXPECT_EQ(bytesOf(dir / "geometry data.bin"), bufferBefore);
}

TEST(OutputSafety, EveryOutputDirectoryIsCheckedBeforeRendering) {
  const fs::path dir = scratchDir("dirs");
  writeFile(dir / "file", "x");
  fs::create_directories(dir / "adir.exr");
  expectRefusedBeforeRendering(kQuick + "--out " + (dir / "missing/x.exr").string(), "does not exist");
  expectRefusedBeforeRendering(kQuick + "--out " + (dir / "file/x.exr").string(), "not a directory");
  expectRefusedBeforeRendering(kQuick + "--out " + (dir / "adir.exr").string(), "is a directory");
  expectRefusedBeforeRendering(kQuick + "--out " + (dir / "x.exr").string() + " --stats " + (dir / "missing/s.json").string(),
                               "--stats");
  // Permission bits do not stop root; a directory that takes no new files does.
  expectRefusedBeforeRendering(kQuick + "--out /proc/x.exr", "cannot create files");
  expectRefusedBeforeRendering(kQuick + "--out /dev/null --stats " + (dir / "s.json").string(), "extension");
  expectRefusedBeforeRendering(kQuick + "--stats /dev/null", "not a regular file");
}

// Each output replaces its file by a rename: the old inode is never written to, so a reader of
// the old file (or an interrupted write) never sees a truncated image.
TEST(OutputSafety, FilesAreReplacedByRenameNotRewrittenInPlace) {
  const fs::path dir = scratchDir("atomic");
  const std::string common = kQuick + "-q --out " + (dir / "r.exr").string() + " --stats " + (dir / "r.json").string();
  ASSERT_EQ(runMixtrace(common).exitCode, 0);
  ASSERT_EQ(runMixtrace(kQuick + "-q --out " + (dir / "r.jpg").string()).exitCode, 0);
  const fs::path files[] = {dir / "r.exr", dir / "r.png", dir / "r.json", dir / "r.jpg"};
  ino_t before[4];
  for (int i = 0; i < 4; ++i) before[i] = inodeOf(files[i]);
  ASSERT_EQ(runMixtrace(common).exitCode, 0);
  ASSERT_EQ(runMixtrace(kQuick + "-q --out " + (dir / "r.jpg").string()).exitCode, 0);
  for (int i = 0; i < 4; ++i) EXPECT_NE(inodeOf(files[i]), before[i]) << files[i] << " was rewritten in place";
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().string().find(".partial"), std::string::npos) << "left behind: " << entry.path();
  // New files get the usual permissions (mkstemp's 0600 would hide renders from other users).
  EXPECT_EQ(fs::status(dir / "r.exr").permissions() & fs::perms::others_read, fs::perms::others_read);
}

TEST(AtomicFile, AFailedWriteLeavesTheOldFileAndNoTemporary) {
  const fs::path dir = scratchDir("atomic-unit");
  const fs::path target = dir / "keep.txt";
  writeFile(target, "old content");
  EXPECT_THROW(writeFileAtomically(target.string(),
                                   [](const std::string& temporary) {
                                     writeFile(temporary, "half of the new");
                                     throw Error("disk full");
                                   }),
               Error);
  EXPECT_EQ(bytesOf(target), "old content");
  size_t entries = 0;
  for (const auto& entry : fs::directory_iterator(dir)) entries += entry.is_regular_file();
  EXPECT_EQ(entries, 1u) << "the temporary file was not removed";

  // Through a symbolic link: the link stays, the file it names gets the content.
  fs::create_symlink(target, dir / "link.txt");
  writeFileAtomically((dir / "link.txt").string(), std::string("new content"));
  EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
  EXPECT_EQ(bytesOf(target), "new content");
  EXPECT_THROW(writeFileAtomically((dir / "missing/x.txt").string(), std::string("x")), Error);
}

// compare's outputs (--json, --error-map) never overwrite the images compared, and a bad
// directory is refused before the images are read; the error map is replaced by rename.
TEST(OutputSafety, CompareOutputsAreCheckedToo) {
  const fs::path dir = scratchDir("compare-out");
  const std::string a = (dir / "a.exr").string(), b = (dir / "b.exr").string();
  ASSERT_EQ(runMixtrace(kQuick + "-q --no-png --variance --out " + a).exitCode, 0);
  ASSERT_EQ(runMixtrace(kQuick + "-q --no-png --variance --seed 1 --out " + b).exitCode, 0);
  const std::string before = bytesOf(a);
  for (const std::string& args : {"compare " + a + " " + b + " --json " + a,
                                  "compare " + a + " " + b + " --error-only --error-map " + b,
                                  "compare " + a + " " + b + " --json " + (dir / "missing/r.json").string()}) {
    const RunResult r = runMixtrace(args);
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.stderrText;
    ASSERT_EQ(r.stderrLines().size(), 1u) << args << "\n" << r.stderrText;
  }
  EXPECT_EQ(bytesOf(a), before);
  EXPECT_TRUE(startsWith(bytesOf(b), kExrMagic));
  const std::string map = (dir / "e.pfm").string();
  ASSERT_EQ(runMixtrace("compare " + a + " " + b + " --error-only --error-map " + map).exitCode, 0);
  const ino_t first = inodeOf(map);
  ASSERT_EQ(runMixtrace("compare " + a + " " + b + " --error-only --error-map " + map).exitCode, 0);
  EXPECT_NE(inodeOf(map), first);
  EXPECT_TRUE(startsWith(bytesOf(map), "Pf\n"));
}
