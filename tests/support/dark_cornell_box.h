#pragma once
// The shipped Cornell box with its light's emission removed: a scene without lights, written as
// dark.gltf into `dir` (for the tests of what a scene without lights gets).
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "support/run_binary.h"

namespace mixtrace::testing {

inline std::filesystem::path writeDarkCornellBox(const std::filesystem::path& dir) {
  std::ifstream in(std::filesystem::path(MIXTRACE_SOURCE_DIR) / "scenes/cornell_box.gltf");
  nlohmann::json j = nlohmann::json::parse(in);
  for (auto& material : j["materials"]) {
    material.erase("emissiveFactor");
    if (material.contains("extensions")) material["extensions"].erase("KHR_materials_emissive_strength");
  }
  writeFile(dir / "dark.gltf", j.dump());
  return dir / "dark.gltf";
}

}  // namespace mixtrace::testing
