#include "session/scene_environment.h"

#include <algorithm>
#include <cmath>

#include <stb/stb_image.h>  // declarations only: stb_image is compiled into libstb

#include "output/exr_io.h"
#include "output/pfm_io.h"
#include "util/error.h"
#include "util/log.h"

namespace mixtrace {
namespace {

constexpr double kDegrees = 3.14159265358979323846 / 180.0;
// A map larger than this is refused rather than decoded (16k x 8k RGB float is 1.5 GiB).
constexpr size_t kMaxDecodedTexels = size_t(16384) * 8192;

std::string lowerExtension(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

Image readHdr(const std::string& path) {
  int w = 0, h = 0, n = 0;
  if (!stbi_info(path.c_str(), &w, &h, &n)) throw Error(path + ": not a readable Radiance .hdr file (" + stbi_failure_reason() + ")");
  if (w < 1 || h < 1 || size_t(w) * size_t(h) > kMaxDecodedTexels)
    throw Error(path + ": " + std::to_string(w) + "x" + std::to_string(h) + " is not a size this renderer reads");
  float* data = stbi_loadf(path.c_str(), &w, &h, &n, 3);
  if (!data) throw Error(path + ": not a readable Radiance .hdr file (" + stbi_failure_reason() + ")");
  Image image(w, h);
  std::copy(data, data + image.rgb.size(), image.rgb.begin());
  stbi_image_free(data);
  return image;
}

// Halves a map (2x2 box; an odd last row or column is averaged with what it has).
Environment halve(const Environment& e) {
  Environment out = e;
  out.width = std::max(1u, e.width / 2);
  out.height = std::max(1u, e.height / 2);
  out.radiance.assign(size_t(out.width) * out.height, glm::vec3(0.0f));
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x) {
      glm::dvec3 sum(0.0);
      int n = 0;
      for (uint32_t dy = 0; dy < 2; ++dy)
        for (uint32_t dx = 0; dx < 2; ++dx) {
          const uint32_t sx = 2 * x + dx, sy = 2 * y + dy;
          if (sx >= e.width || sy >= e.height) continue;
          sum += glm::dvec3(e.radiance[size_t(sy) * e.width + sx]);
          ++n;
        }
      out.radiance[size_t(y) * out.width + x] = glm::vec3(sum / double(n));
    }
  return out;
}

// A uniform environment: a small map of one colour (the distribution is then uniform in each
// row's solid angle, shared/environment.h).
Environment uniformEnvironment(const glm::vec3& colour) {
  Environment e;
  e.width = 32;
  e.height = 16;
  e.radiance.assign(size_t(e.width) * e.height, colour);
  e.source = "uniform colour";
  return e;
}

}  // namespace

Environment readEnvironmentImage(const std::string& path) {
  const std::string ext = lowerExtension(path);
  Image image;
  if (ext == ".exr") image = readExr(path);
  else if (ext == ".hdr") image = readHdr(path);
  else if (ext == ".pfm") image = readPfm(path, kMaxDecodedTexels);
  else throw Error("--env " + path + ": an environment map must be .exr, .hdr or .pfm");
  Environment env;
  env.width = uint32_t(image.width);
  env.height = uint32_t(image.height);
  env.source = path;
  env.radiance.resize(image.pixelCount());
  size_t negative = 0;
  for (size_t i = 0; i < env.radiance.size(); ++i) {
    glm::vec3 c(image.rgb[3 * i], image.rgb[3 * i + 1], image.rgb[3 * i + 2]);
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(c[k])) throw Error(path + ": the environment map has a texel that is not a finite number");
      if (c[k] < 0.0f) {
        c[k] = 0.0f;
        ++negative;
      }
    }
    env.radiance[i] = c;
  }
  if (negative > 0) warn(path + ": " + std::to_string(negative) + " negative radiance value(s) read as 0");
  while (size_t(env.width) * env.height > kMaxEnvironmentTexels) {
    env = halve(env);
    info(path + ": environment map halved to " + std::to_string(env.width) + "x" + std::to_string(env.height) +
         " to fit one storage buffer");
  }
  return env;
}

bool sceneHasLights(const Scene& scene) {
  if (!scene.punctualLights.empty()) return true;
  for (const Triangle& t : scene.triangles) {
    const MaterialGpu& m = scene.materials[t.material];
    if (m.emission.x > 0.0f || m.emission.y > 0.0f || m.emission.z > 0.0f) return true;
  }
  return false;
}

void applyEnvironmentOptions(Scene& scene, const RenderOptions& o) {
  const bool none = o.env == "none";
  if (!o.env.empty() && o.envColor) throw Error("give --env or --env-color, not both");
  if (!std::isfinite(o.envScale) || o.envScale < 0.0) throw Error("--env-scale must be a finite number >= 0");
  Environment env;
  if (none) {
    scene.environment = Environment{};
    return;
  }
  if (!o.env.empty()) {
    env = readEnvironmentImage(o.env);
  } else if (o.envColor) {
    const std::array<double, 3>& c = *o.envColor;
    if (!(c[0] >= 0.0 && c[1] >= 0.0 && c[2] >= 0.0)) throw Error("--env-color: each of R, G, B must be >= 0");
    env = uniformEnvironment(glm::vec3(float(c[0]), float(c[1]), float(c[2])));
  } else if (!sceneHasLights(scene)) {
    env = uniformEnvironment(glm::vec3(1.0f));
    info(scene.name + " has no lights: lit by a uniform white environment of radiance 1 (--env none keeps it "
         "black; --env FILE or --env-color R,G,B choose another)");
  } else {
    return;
  }
  for (glm::vec3& c : env.radiance) c *= float(o.envScale);
  env.rotation = float(o.envRotateDegrees * kDegrees);
  scene.environment = std::move(env);
}

}  // namespace mixtrace
