#include "session/default_scene.h"

#include <filesystem>

#include "util/error.h"

namespace mixtrace {

std::string defaultScenePath() {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  for (fs::path candidate : {fs::path(MIXTRACE_SOURCE_DIR) / "scenes/cornell_box.gltf",
                             exe.parent_path() / "../scenes/cornell_box.gltf",
                             exe.parent_path() / "../share/mixtrace/scenes/cornell_box.gltf"})
    if (fs::exists(candidate, ec)) return candidate.string();
  throw Error("no scene given and the default scene scenes/cornell_box.gltf was not found");
}

}  // namespace mixtrace
