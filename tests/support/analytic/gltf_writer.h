#pragma once
// Writes a small glTF 2.0 scene (JSON with an embedded base64 buffer) from triangle soups,
// metallic-roughness materials and one perspective camera. No NORMAL attribute is written, so the
// renderer shades with the flat geometric normals the spec prescribes.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "support/analytic/meshes.h"

namespace mixtrace::testing::analytic {

inline std::string base64Encode(const std::vector<uint8_t>& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t chunk = uint32_t(bytes[i]) << 16;
    if (n > 1) chunk |= uint32_t(bytes[i + 1]) << 8;
    if (n > 2) chunk |= uint32_t(bytes[i + 2]);
    for (size_t k = 0; k < 4; ++k) out += k <= n ? kAlphabet[(chunk >> (18 - 6 * k)) & 63u] : '=';
  }
  return out;
}

struct MaterialSpec {
  glm::vec3 baseColor{1.0f};
  float metallic = 0.0f;
  float roughness = 1.0f;
  glm::vec3 emission{0.0f};  // radiance Le; written as emissiveFactor times emissiveStrength
  bool doubleSided = false;
  const char* alphaMode = "OPAQUE";  // glTF alphaMode; alpha is baseColorFactor's fourth component
  float alpha = 1.0f;
  float alphaCutoff = 0.5f;
  float transmission = 0.0f;  // KHR_materials_transmission's factor (written when > 0)
  float ior = 1.5f;           // KHR_materials_ior (written when not 1.5)
  bool volumetric = false;    // KHR_materials_volume with thicknessFactor 1 (thin-walled without)
};

// Pinhole camera: looks from `position` at `target`, `up` roughly up, vertical field of view.
struct CameraSpec {
  glm::dvec3 position{0.0};
  glm::dvec3 target{0.0, 0.0, -1.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double yfov = 0.8;
  // The orthonormal frame the renderer derives from the camera node (forward = node's -Z).
  glm::dvec3 forward() const { return glm::normalize(target - position); }
  glm::dvec3 right() const { return glm::normalize(glm::cross(forward(), up)); }
  glm::dvec3 trueUp() const { return glm::cross(right(), forward()); }
};

class GltfWriter {
 public:
  int addMaterial(const MaterialSpec& m) {
    nlohmann::json pbr = {{"baseColorFactor", {m.baseColor.x, m.baseColor.y, m.baseColor.z, m.alpha}},
                          {"metallicFactor", m.metallic},
                          {"roughnessFactor", m.roughness}};
    nlohmann::json mat = {{"pbrMetallicRoughness", pbr}, {"doubleSided", m.doubleSided}, {"alphaMode", m.alphaMode}};
    if (std::string(m.alphaMode) == "MASK") mat["alphaCutoff"] = m.alphaCutoff;
    // emissiveFactor is limited to [0, 1]; larger radiance goes through the strength extension.
    const float peak = std::max({m.emission.x, m.emission.y, m.emission.z});
    if (peak > 1.0f) {
      const glm::vec3 c = m.emission / peak;
      mat["emissiveFactor"] = {c.x, c.y, c.z};
      mat["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", peak}}}};
      extensionsUsed_.insert("KHR_materials_emissive_strength");
    } else if (peak > 0.0f) {
      mat["emissiveFactor"] = {m.emission.x, m.emission.y, m.emission.z};
    }
    auto extension = [&](const char* name, nlohmann::json value) {
      mat["extensions"][name] = std::move(value);
      extensionsUsed_.insert(name);
    };
    if (m.transmission > 0.0f) extension("KHR_materials_transmission", {{"transmissionFactor", m.transmission}});
    if (m.ior != 1.5f) extension("KHR_materials_ior", {{"ior", m.ior}});
    if (m.volumetric) extension("KHR_materials_volume", {{"thicknessFactor", 1.0}});
    materials_.push_back(mat);
    return int(materials_.size()) - 1;
  }

  // Each call is its own mesh, node and primitive: an emissive one is one light of the renderer.
  // `colors`, when given, is COLOR_0 (linear RGBA, FLOAT VEC4): one per corner, 3 per triangle.
  void addMesh(const std::vector<Tri>& tris, int material, const std::vector<glm::vec4>& colors = {}) {
    const size_t offset = bytes_.size();
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Tri& t : tris)
      for (const glm::vec3& p : t.p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
        append(&p.x, 3);
      }
    bufferViews_.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes_.size() - offset}});
    accessors_.push_back({{"bufferView", bufferViews_.size() - 1},
                          {"componentType", 5126},
                          {"count", tris.size() * 3},
                          {"type", "VEC3"},
                          {"min", {lo.x, lo.y, lo.z}},
                          {"max", {hi.x, hi.y, hi.z}}});
    nlohmann::json attributes = {{"POSITION", accessors_.size() - 1}};
    if (!colors.empty()) {
      const size_t colorOffset = bytes_.size();
      for (const glm::vec4& c : colors) append(&c.x, 4);
      bufferViews_.push_back({{"buffer", 0}, {"byteOffset", colorOffset}, {"byteLength", bytes_.size() - colorOffset}});
      accessors_.push_back(
          {{"bufferView", bufferViews_.size() - 1}, {"componentType", 5126}, {"count", colors.size()}, {"type", "VEC4"}});
      attributes["COLOR_0"] = accessors_.size() - 1;
    }
    meshes_.push_back({{"primitives", {{{"attributes", attributes}, {"material", material}, {"mode", 4}}}}});
  }

  void setCamera(const CameraSpec& c) { camera_ = c; }

  std::string json() const {
    nlohmann::json nodes = nlohmann::json::array();
    nlohmann::json sceneNodes = nlohmann::json::array();
    for (size_t i = 0; i < meshes_.size(); ++i) {
      nodes.push_back({{"mesh", i}});
      sceneNodes.push_back(i);
    }
    // Column-major node matrix whose columns are right, up, back (= -forward) and the position.
    const glm::dvec3 r = camera_.right(), u = camera_.trueUp(), b = -camera_.forward(), p = camera_.position;
    nodes.push_back({{"camera", 0},
                     {"matrix", {r.x, r.y, r.z, 0.0, u.x, u.y, u.z, 0.0, b.x, b.y, b.z, 0.0, p.x, p.y, p.z, 1.0}}});
    sceneNodes.push_back(meshes_.size());
    nlohmann::json doc = {
        {"asset", {{"version", "2.0"}, {"generator", "mixtrace analytic_render_test"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", sceneNodes}}}},
        {"nodes", nodes},
        {"meshes", meshes_},
        {"materials", materials_},
        {"accessors", accessors_},
        {"bufferViews", bufferViews_},
        {"buffers",
         {{{"byteLength", bytes_.size()}, {"uri", "data:application/octet-stream;base64," + base64Encode(bytes_)}}}},
        {"cameras", {{{"type", "perspective"}, {"perspective", {{"yfov", camera_.yfov}, {"znear", 0.001}}}}}}};
    if (!extensionsUsed_.empty()) doc["extensionsUsed"] = extensionsUsed_;
    return doc.dump(1);
  }

 private:
  void append(const float* values, size_t n) {
    const size_t at = bytes_.size();
    bytes_.resize(at + sizeof(float) * n);
    std::memcpy(&bytes_[at], values, sizeof(float) * n);
  }

  std::vector<uint8_t> bytes_;
  nlohmann::json materials_ = nlohmann::json::array();
  nlohmann::json meshes_ = nlohmann::json::array();
  nlohmann::json accessors_ = nlohmann::json::array();
  nlohmann::json bufferViews_ = nlohmann::json::array();
  CameraSpec camera_;
  std::set<std::string> extensionsUsed_;
};

}  // namespace mixtrace::testing::analytic
