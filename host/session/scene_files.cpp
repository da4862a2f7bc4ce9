#include "session/scene_files.h"

#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "gltf/gltf_limits.h"
#include "gltf/json_nesting.h"

namespace mixtrace {
namespace {

namespace fs = std::filesystem;

// Larger JSON is not worth parsing twice just for this check.
constexpr uintmax_t kMaxJsonBytes = 64u << 20;

uint32_t littleEndian32(const unsigned char* bytes) {
  return uint32_t(bytes[0]) | uint32_t(bytes[1]) << 8 | uint32_t(bytes[2]) << 16 | uint32_t(bytes[3]) << 24;
}

// The JSON text of a .gltf, or of a .glb's first chunk; "" when there is none or it is too big.
std::string sceneJson(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return "";
  const uintmax_t size = fs::file_size(path, ec);
  if (ec) return "";
  std::ifstream in(path, std::ios::binary);
  unsigned char header[20] = {};
  in.read(reinterpret_cast<char*>(header), sizeof(header));
  uintmax_t offset = 0, length = size;
  if (in.gcount() == sizeof(header) && std::memcmp(header, "glTF", 4) == 0) {
    if (std::memcmp(header + 16, "JSON", 4) != 0) return "";
    offset = sizeof(header);
    length = littleEndian32(header + 12);
  }
  if (length > kMaxJsonBytes || offset + length > size) return "";
  std::string text(size_t(length), '\0');
  in.clear();
  in.seekg(std::streamoff(offset));
  in.read(text.data(), std::streamsize(length));
  return in.gcount() == std::streamsize(length) ? text : "";
}

// glTF URIs are percent-encoded ("my%20texture.png").
std::string percentDecoded(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

}  // namespace

std::vector<std::string> filesReferencedByScene(const std::string& scenePath) {
  std::vector<std::string> files;
  const std::string text = sceneJson(scenePath);
  // Deeply nested JSON (a hostile file) is left to the loader's own refusal: this parse must not
  // be where it fails.
  if (text.empty()) return files;
  if (jsonNestingExceededAt(text.data(), text.size(), gltf::kMaxJsonNesting) != kJsonNestingOk) return files;
  const nlohmann::json json = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!json.is_object()) return files;
  const fs::path directory = fs::path(scenePath).parent_path();
  for (const char* list : {"buffers", "images"}) {
    const auto entries = json.find(list);
    if (entries == json.end() || !entries->is_array()) continue;
    for (const nlohmann::json& entry : *entries) {
      if (!entry.is_object() || !entry.contains("uri") || !entry["uri"].is_string()) continue;
      const std::string uri = entry["uri"].get<std::string>();
      if (uri.empty() || uri.rfind("data:", 0) == 0) continue;
      files.push_back((directory / percentDecoded(uri)).string());
    }
  }
  return files;
}

}  // namespace mixtrace
