// loadGltf: walks the node hierarchy of the chosen scene and flattens meshes, the camera and
// punctual lights into world space. Parsing, accessors, geometry and materials live in the other
// gltf_*.cpp files.
#include "gltf/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "gltf/gltf_internal.h"
#include "util/error.h"

namespace mixtrace {
namespace {

using gltf::LoadContext;

constexpr double kHalfPi = 1.5707963267948966;

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool allFinite(const std::vector<double>& values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

// The node's local transform: its matrix, or translation * rotation * scale.
glm::dmat4 localTransform(const LoadContext& ctx, const tinygltf::Node& node, int nodeIndex) {
  const std::string where = "node " + std::to_string(nodeIndex);
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16 || !allFinite(node.matrix)) ctx.fail(where + " has a malformed matrix");
    gltf::checkFitsInFloat(ctx, node.matrix, "nodes[" + std::to_string(nodeIndex) + "].matrix");
    glm::dmat4 m(1.0);
    for (int column = 0; column < 4; ++column) {
      for (int row = 0; row < 4; ++row) m[column][row] = node.matrix[size_t(column * 4 + row)];  // column-major
    }
    return m;
  }
  glm::dmat4 m(1.0);
  if (!node.translation.empty()) {
    if (node.translation.size() != 3 || !allFinite(node.translation)) ctx.fail(where + " has a malformed translation");
    gltf::checkFitsInFloat(ctx, node.translation, "nodes[" + std::to_string(nodeIndex) + "].translation");
    m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
  }
  if (!node.rotation.empty()) {
    if (node.rotation.size() != 4 || !allFinite(node.rotation)) ctx.fail(where + " has a malformed rotation");
    // glTF stores the unit quaternion as (x, y, z, w); glm's constructor takes w first.
    glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    const double length = glm::length(q);
    if (!(length > 0.0)) ctx.fail(where + " has a zero rotation quaternion");
    m = m * glm::mat4_cast(q / length);
  }
  if (!node.scale.empty()) {
    if (node.scale.size() != 3 || !allFinite(node.scale)) ctx.fail(where + " has a malformed scale");
    gltf::checkFitsInFloat(ctx, node.scale, "nodes[" + std::to_string(nodeIndex) + "].scale");
    m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
  }
  return m;
}

glm::dvec3 transformPoint(const glm::dmat4& m, const glm::dvec3& p) { return glm::dvec3(m * glm::dvec4(p, 1.0)); }

// The world-space position of a camera or light, which the renderer holds in float: a chain of
// transforms can carry it beyond float's range even when every node's own values fit.
void checkWorldPosition(const LoadContext& ctx, const glm::dvec3& p, const std::string& what) {
  for (int c = 0; c < 3; ++c) gltf::checkedFloat(ctx, p[c], what + " world position[" + std::to_string(c) + "]");
}

glm::dvec3 transformDirection(const glm::dmat4& m, const glm::dvec3& d) { return glm::dmat3(m) * d; }

// Unit vector, or false when the direction collapsed (zero scale) or is not finite.
bool normalizeChecked(glm::dvec3& v) {
  const double length = glm::length(v);
  if (!(length > 0.0) || !std::isfinite(length)) return false;
  v /= length;
  return true;
}

class SceneBuilder {
 public:
  SceneBuilder(const LoadContext& ctx, Scene& scene)
      : ctx_(ctx), model_(ctx.model), scene_(scene), materials_(ctx, scene) {}

  void build() {
    visited_.assign(model_.nodes.size(), false);
    // Depth-first, pre-order, with an explicit stack so deep hierarchies cannot overflow ours.
    std::vector<std::pair<int, glm::dmat4>> stack;
    const std::vector<int> roots = rootNodes();
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::dmat4(1.0));
    while (!stack.empty()) {
      const auto [nodeIndex, parentWorld] = stack.back();
      stack.pop_back();
      const tinygltf::Node& node = model_.nodes[size_t(nodeIndex)];
      const glm::dmat4 world = parentWorld * localTransform(ctx_, node, nodeIndex);
      if (node.mesh >= 0) addMesh(node, nodeIndex, world);
      if (node.camera >= 0) addCamera(node, nodeIndex, world);
      addLight(node, nodeIndex, world);
      if (node.skin >= 0) skinned_ = true;
      for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) {
        checkNode(*it, "node " + std::to_string(nodeIndex) + " has child");
        stack.emplace_back(*it, world);
      }
    }
    reportOnce();
  }

 private:
  void checkNode(int nodeIndex, const std::string& referrer) {
    if (nodeIndex < 0 || size_t(nodeIndex) >= model_.nodes.size()) {
      ctx_.fail(referrer + " node " + std::to_string(nodeIndex) + ", which does not exist");
    }
    // glTF nodes form disjoint trees; a second visit means a cycle or a shared child, either of
    // which would loop forever or duplicate geometry.
    if (visited_[size_t(nodeIndex)]) {
      ctx_.fail("node " + std::to_string(nodeIndex) + " appears more than once in the node hierarchy");
    }
    visited_[size_t(nodeIndex)] = true;
  }

  std::vector<int> rootNodes() {
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
      const int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (size_t(sceneIndex) >= model_.scenes.size()) {
        ctx_.fail("default scene " + std::to_string(sceneIndex) + " does not exist");
      }
      roots = model_.scenes[size_t(sceneIndex)].nodes;
    } else if (!model_.nodes.empty()) {
      // No scenes: the spec leaves this to the application; render every root node.
      ctx_.warning("has no scenes; rendering every root node");
      std::vector<bool> isChild(model_.nodes.size(), false);
      for (const tinygltf::Node& node : model_.nodes) {
        for (int child : node.children) {
          if (child >= 0 && size_t(child) < isChild.size()) isChild[size_t(child)] = true;
        }
      }
      for (size_t i = 0; i < model_.nodes.size(); ++i) {
        if (!isChild[i]) roots.push_back(int(i));
      }
    }
    for (int root : roots) checkNode(root, "the scene refers to");
    return roots;
  }

  void addMesh(const tinygltf::Node& node, int nodeIndex, const glm::dmat4& world) {
    if (size_t(node.mesh) >= model_.meshes.size()) {
      ctx_.fail("node " + std::to_string(nodeIndex) + " refers to mesh " + std::to_string(node.mesh) +
                ", which does not exist");
    }
    const tinygltf::Mesh& mesh = model_.meshes[size_t(node.mesh)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& primitive = mesh.primitives[p];
      if (!primitive.targets.empty()) morphed_ = true;
      if (!gltf::isSurfaceMode(primitive.mode)) {
        if (skippedModes_.insert({node.mesh, int(p)}).second) {
          ctx_.warning("mesh " + std::to_string(node.mesh) + " primitive " + std::to_string(p) + " has mode " +
                       std::to_string(primitive.mode) +
                       " (points or lines: no surface to render); only TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN "
                       "(4, 5, 6) are rendered, skipping it");
        }
        continue;
      }
      const uint32_t material = materials_.materialFor(primitive.material);
      // One id per (node instance, primitive): each emissive instance becomes its own light.
      const size_t added = gltf::appendPrimitive(ctx_, node.mesh, int(p), world, material,
                                                 materials_.uvMappingFor(primitive.material),
                                                 materials_.hasNormalMap(primitive.material), nextPrimitiveId_,
                                                 scene_.triangles, stats_);
      if (added > 0) ++nextPrimitiveId_;
    }
  }

  void addCamera(const tinygltf::Node& node, int nodeIndex, const glm::dmat4& world) {
    if (size_t(node.camera) >= model_.cameras.size()) {
      ctx_.fail("node " + std::to_string(nodeIndex) + " refers to camera " + std::to_string(node.camera) +
                ", which does not exist");
    }
    if (scene_.camera.fromFile) return;  // the first perspective camera wins
    const tinygltf::Camera& camera = model_.cameras[size_t(node.camera)];
    if (camera.type != "perspective") {
      ctx_.warning("camera " + std::to_string(node.camera) + " is " + (camera.type.empty() ? "untyped" : camera.type) +
                   "; only perspective cameras are supported, ignoring it");
      return;
    }
    glm::dvec3 forward = transformDirection(world, {0.0, 0.0, -1.0});
    glm::dvec3 up = transformDirection(world, {0.0, 1.0, 0.0});
    const glm::dvec3 position = transformPoint(world, glm::dvec3(0.0));
    checkWorldPosition(ctx_, position, "the camera of nodes[" + std::to_string(nodeIndex) + "]");
    bool usable = isFinite(position) && normalizeChecked(forward);
    if (usable) {
      up -= glm::dot(up, forward) * forward;  // re-orthogonalise under shear / non-uniform scale
      usable = normalizeChecked(up);
    }
    if (!usable) {
      ctx_.warning("camera node " + std::to_string(nodeIndex) + " has a degenerate transform; ignoring it");
      return;
    }
    Camera& out = scene_.camera;
    out.position = glm::vec3(position);
    out.forward = glm::vec3(forward);
    out.up = glm::vec3(up);
    const double yfov = camera.perspective.yfov;
    if (std::isfinite(yfov) && yfov > 0.0 && yfov < 3.14159) {
      out.yfov = float(yfov);
    } else {
      ctx_.warning("camera " + std::to_string(node.camera) + " has an invalid yfov; using " + std::to_string(out.yfov));
    }
    const double aspect = camera.perspective.aspectRatio;   // optional in glTF: 0 when absent
    if (std::isfinite(aspect) && aspect > 0.0 && aspect <= 1e4 && aspect >= 1e-4) {
      out.aspectRatio = float(aspect);
    } else if (aspect != 0.0) {
      ctx_.warning("camera " + std::to_string(node.camera) + " has an invalid aspectRatio; the image size decides");
    }
    out.fromFile = true;
  }

  void addLight(const tinygltf::Node& node, int nodeIndex, const glm::dmat4& world) {
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) return;
    const std::string where = "node " + std::to_string(nodeIndex);
    if (!ext->second.IsObject() || !ext->second.Get("light").IsNumber()) {
      ctx_.fail(where + " has a KHR_lights_punctual extension without a light index");
    }
    const int lightIndex = ext->second.Get("light").GetNumberAsInt();
    if (lightIndex < 0 || size_t(lightIndex) >= model_.lights.size()) {
      ctx_.fail(where + " refers to light " + std::to_string(lightIndex) + ", which does not exist");
    }
    const tinygltf::Light& light = model_.lights[size_t(lightIndex)];
    const std::string name = "light " + std::to_string(lightIndex);

    PunctualLight out;
    if (light.type == "point") {
      out.kind = shared::kLightPoint;
    } else if (light.type == "spot") {
      out.kind = shared::kLightSpot;
    } else if (light.type == "directional") {
      out.kind = shared::kLightDirectional;
    } else {
      ctx_.warning(name + " has unknown type \"" + light.type + "\"; ignoring it");
      return;
    }
    const std::string property = "KHR_lights_punctual lights[" + std::to_string(lightIndex) + "]";
    gltf::checkedFloat(ctx_, light.intensity, property + ".intensity");
    gltf::checkFitsInFloat(ctx_, light.color, property + ".color");
    glm::dvec3 color(1.0);
    if (light.color.size() == 3) color = glm::dvec3(light.color[0], light.color[1], light.color[2]);
    const glm::dvec3 intensity = color * light.intensity;
    for (int c = 0; c < 3; ++c) {
      gltf::checkedFloat(ctx_, intensity[c], property + ".color[" + std::to_string(c) + "] * intensity");
    }
    if (!isFinite(intensity) || intensity.x < 0.0 || intensity.y < 0.0 || intensity.z < 0.0) {
      ctx_.warning(name + " has a negative or non-finite colour/intensity; ignoring it");
      return;
    }
    out.intensity = glm::vec3(intensity);
    // `range` is deliberately ignored: the renderer uses the physical inverse-square falloff.
    const glm::dvec3 position = transformPoint(world, glm::dvec3(0.0));
    checkWorldPosition(ctx_, position, "the light of nodes[" + std::to_string(nodeIndex) + "]");
    glm::dvec3 direction = transformDirection(world, {0.0, 0.0, -1.0});
    const bool hasDirection = normalizeChecked(direction);
    if (!isFinite(position) || (out.kind != shared::kLightPoint && !hasDirection)) {
      ctx_.warning(where + " places " + name + " with a degenerate transform; ignoring it");
      return;
    }
    out.position = glm::vec3(position);
    if (hasDirection) out.direction = glm::vec3(direction);
    if (out.kind == shared::kLightSpot) {
      double inner = light.spot.innerConeAngle;
      double outer = light.spot.outerConeAngle;
      const bool valid =
          std::isfinite(inner) && std::isfinite(outer) && inner >= 0.0 && inner < outer && outer <= kHalfPi;
      if (!valid) {
        outer = std::isfinite(outer) ? std::min(std::max(outer, 1e-4), kHalfPi) : kHalfPi / 2.0;
        inner = std::isfinite(inner) ? std::min(std::max(inner, 0.0), outer) : 0.0;
        ctx_.warning(name + " needs 0 <= innerConeAngle < outerConeAngle <= pi/2; clamped");
      }
      out.innerConeAngle = float(inner);
      out.outerConeAngle = float(outer);
    }
    scene_.punctualLights.push_back(out);
  }

  void reportOnce() {
    if (stats_.degenerate > 0) {
      ctx_.warning("dropped " + std::to_string(stats_.degenerate) +
                   " degenerate triangles (zero area or non-finite positions)");
    }
    if (stats_.invalidNormals > 0) {
      ctx_.warning("replaced " + std::to_string(stats_.invalidNormals) +
                   " zero or non-finite vertex normals with face normals");
    }
    if (stats_.leftoverIndices > 0) {
      ctx_.warning("ignored " + std::to_string(stats_.leftoverIndices) +
                   " trailing vertices/indices that do not form a whole triangle");
    }
    if (skinned_ || morphed_) ctx_.warning("skinning and morph targets are not supported; meshes keep their rest pose");
    if (!model_.animations.empty()) ctx_.ignoring("animations", "a still image renders the scene as its nodes place it");
  }

  const LoadContext& ctx_;
  const tinygltf::Model& model_;
  Scene& scene_;
  gltf::MaterialTable materials_;
  gltf::GeometryStats stats_;
  std::vector<bool> visited_;
  std::set<std::pair<int, int>> skippedModes_;
  uint32_t nextPrimitiveId_ = 0;
  bool skinned_ = false;
  bool morphed_ = false;
};

}  // namespace

Scene loadGltf(const std::string& path, const GltfLoadOptions& options) {
  LoadContext ctx;
  ctx.path = path;
  ctx.assetRoot = options.assetRoot;
  gltf::parseGltfFile(ctx);

  Scene scene;
  scene.name = std::filesystem::path(path).filename().string();
  SceneBuilder(ctx, scene).build();
  if (scene.triangles.empty()) throw Error(path + " contains no triangles");
  for (const Triangle& tri : scene.triangles) {
    for (const glm::vec3& p : tri.p) scene.bounds.grow(p);
  }
  return scene;
}

}  // namespace mixtrace
