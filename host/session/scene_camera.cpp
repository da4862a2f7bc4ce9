#include "session/scene_camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/glm.hpp>

#include "gltf/gltf_loader.h"
#include "scene/prepared_scene.h"
#include "session/scene_environment.h"
#include "util/error.h"
#include "util/log.h"

namespace mixtrace {
namespace {

// Below this sine of the angle between up and the view direction the camera's right vector is
// mostly rounding error (0.006 degrees).
constexpr double kMinUpSine = 1e-4;

using Vec = glm::dvec3;

Vec toVec(const std::array<double, 3>& v) { return Vec(v[0], v[1], v[2]); }

std::string formatPoint(const Vec& v) {
  char text[96];
  std::snprintf(text, sizeof(text), "%g,%g,%g", v.x, v.y, v.z);
  return text;
}

// "" when from, at and up make a camera frame, else why not.
std::string frameProblem(const Vec& from, const Vec& at, const Vec& up) {
  const Vec view = at - from;
  if (!(glm::length(view) > 0.0)) return "look-from and look-at are the same point (" + formatPoint(from) + ")";
  if (!(glm::length(up) > 0.0)) return "the up direction is zero";
  const double sine = glm::length(glm::cross(glm::normalize(view), glm::normalize(up)));
  if (!(sine >= kMinUpSine))
    return "the up direction (" + formatPoint(up) + ") is parallel to the view direction (" + formatPoint(view) + ")";
  return "";
}

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

std::string describe(const Camera& camera, const Vec& target) {
  char fov[32];
  std::snprintf(fov, sizeof(fov), "%.4g", camera.yfov * kDegrees);
  return "position " + formatPoint(Vec(camera.position)) + ", target " + formatPoint(target) + ", up " +
         formatPoint(Vec(camera.up)) + ", vertical fov " + fov + " degrees";
}

// The point a camera looks at: a camera has only a direction, so the point straight ahead at the
// distance of the bounds' centre stands in for it (for the default framing: that centre).
Vec targetOf(const Camera& camera, const Scene& scene) {
  const Vec position(camera.position), centre(scene.bounds.center());
  const double distance = glm::length(centre - position);
  return position + glm::normalize(Vec(camera.forward)) * (distance > 0.0 ? distance : 1.0);
}

}  // namespace

void checkCameraOptions(const CameraOptions& c) {
  if (c.up && !(glm::length(toVec(*c.up)) > 0.0)) throw Error("--up 0,0,0 is not a direction");
  if (c.lookFrom && c.lookAt && toVec(*c.lookFrom) == toVec(*c.lookAt))
    throw Error("--look-from and --look-at are the same point (" + formatPoint(toVec(*c.lookFrom)) +
                "): the camera needs a direction to look in");
  if (c.lookFrom && c.lookAt && c.up) {
    const std::string problem = frameProblem(toVec(*c.lookFrom), toVec(*c.lookAt), toVec(*c.up));
    if (!problem.empty()) throw Error("--up: " + problem);
  }
}

glm::dvec3 applyCameraOptions(Scene& scene, const CameraOptions& c) {
  if (!c.any()) return targetOf(scene.camera.fromFile ? scene.camera : defaultFraming(scene), scene);
  const Camera base = scene.camera.fromFile ? scene.camera : defaultFraming(scene);
  const Vec from = c.lookFrom ? toVec(*c.lookFrom) : Vec(base.position);
  const Vec at = c.lookAt ? toVec(*c.lookAt) : targetOf(base, scene);
  const Vec up = c.up ? toVec(*c.up) : Vec(base.up);
  const std::string problem = frameProblem(from, at, up);
  if (!problem.empty()) {
    const std::string source = scene.camera.fromFile ? "the file's camera" : "the default camera";
    throw Error("camera: " + problem + " (what --look-from, --look-at and --up do not set comes from " + source +
                ")");
  }
  Camera& out = scene.camera;
  out.position = glm::vec3(from);
  out.forward = glm::vec3(glm::normalize(at - from));
  out.up = glm::vec3(glm::normalize(up));
  if (c.fovDegrees) out.yfov = float(*c.fovDegrees / kDegrees);
  out.fromFile = true;
  return at;
}

Scene loadSceneForRendering(const std::string& scenePath, const RenderOptions& o) {
  const CameraOptions& camera = o.camera;
  Scene scene = loadGltf(scenePath, GltfLoadOptions{o.assetRoot});
  const bool fileHasCamera = scene.camera.fromFile;
  const Vec target = applyCameraOptions(scene, camera);
  if (camera.any())
    info("camera from the command line: " + describe(scene.camera, target));
  else if (!fileHasCamera)
    info(scene.name + " has no camera; the default camera frames its bounds from outside (" +
         describe(defaultFraming(scene), target) + "); set one with --look-from, --look-at, --up, --fov");
  applyEnvironmentOptions(scene, o);
  return scene;
}

void applyFileAspectRatio(RenderOptions& o, const Scene& scene) {
  const double aspect = scene.camera.aspectRatio;
  if (!(aspect > 0.0) || (o.widthGiven && o.heightGiven)) return;
  auto side = [&](double v) { return int(std::clamp(std::lround(v), 1l, long(kMaxImageSide))); };
  const int width = o.width, height = o.height;
  if (o.heightGiven) o.width = side(o.height * aspect);
  else o.height = side(o.width / aspect);
  if (o.width != width || o.height != height)
    info(scene.name + "'s camera has aspect ratio " + std::to_string(aspect) + ": rendering " + std::to_string(o.width) +
         "x" + std::to_string(o.height) + " (give both --width and --height to choose another)");
}

}  // namespace mixtrace
