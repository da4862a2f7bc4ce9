#pragma once
// Writes a colour PFM (the format's rows run bottom to top, little-endian floats) from an image
// given top row first: environment maps for the tests' --env.
#include <filesystem>
#include <fstream>
#include <vector>

#include <glm/glm.hpp>

namespace mixtrace::testing {

inline void writePfm(const std::filesystem::path& path, int w, int h, const std::vector<glm::vec3>& topFirst) {
  std::ofstream out(path, std::ios::binary);
  out << "PF\n" << w << " " << h << "\n-1.0\n";
  for (int y = h - 1; y >= 0; --y)
    out.write(reinterpret_cast<const char*>(&topFirst[size_t(y) * w]), std::streamsize(sizeof(float) * 3 * w));
}

}  // namespace mixtrace::testing
