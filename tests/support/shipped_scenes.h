#pragma once
// The scenes the project ships (scenes/*.gltf, *.glb), sorted, for tests that run on each.
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace mixtrace::testing {

inline std::vector<std::string> shippedScenes() {
  std::vector<std::string> scenes;
  for (auto& e : std::filesystem::directory_iterator(std::filesystem::path(MIXTRACE_SOURCE_DIR) / "scenes")) {
    auto ext = e.path().extension();
    if (ext == ".gltf" || ext == ".glb") scenes.push_back(e.path().string());
  }
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

// Test-name-safe stem of a scene path, for INSTANTIATE_TEST_SUITE_P.
inline std::string sceneStem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

}  // namespace mixtrace::testing
