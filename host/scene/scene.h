#pragma once
// The renderer's scene: what the glTF loader produces and everything downstream (lights, BVH,
// upload, CPU code) reads. Geometry is flattened to world-space triangles.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "shared/layouts.h"
#include "util/bounds.h"

namespace mixtrace {

using shared::MaterialGpu;

// One flattened world-space triangle.
struct Triangle {
  glm::vec3 p[3];
  glm::vec3 n[3];      // shading normals (unit); the geometric normal where the file has none
  glm::vec2 uv[3];     // the material's TEXCOORD set, transformed; (0,0) where the file has none
  glm::vec2 uv2[3] = {glm::vec2(0.0f), glm::vec2(0.0f), glm::vec2(0.0f)};  // its second mapping, where its
                                                                        // textures read two (kMaterialSecondUv*)
  glm::vec4 color[3] = {glm::vec4(1.0f), glm::vec4(1.0f), glm::vec4(1.0f)};  // COLOR_0 (linear RGBA)
  glm::vec4 tangent[3] = {glm::vec4(0.0f), glm::vec4(0.0f), glm::vec4(0.0f)};  // xyz unit, w = +-1; 0: none
  uint32_t material;
  uint32_t primitive;  // index of the glTF mesh primitive instance it came from: one area light
};

// An 8-bit RGBA image as the file stores it (colour textures are sRGB-decoded at lookup).
struct Texture {
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t wrapS = shared::kWrapRepeat;
  uint32_t wrapT = shared::kWrapRepeat;
  bool nearest = false;          // the sampler's magFilter is NEAREST (else bilinear)
  std::vector<uint32_t> texels;  // RGBA8 packed little-endian (R in the low byte), top row first
  glm::vec3 averageLinear{0.0f}; // mean of the sRGB-decoded texels (used for light power)
};

// KHR_lights_punctual, in world space.
struct PunctualLight {
  uint32_t kind = shared::kLightPoint;  // kLightPoint, kLightSpot or kLightDirectional
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // the direction the light travels (node's -Z)
  glm::vec3 intensity{1.0f};               // colour * intensity
  float innerConeAngle = 0.0f;
  float outerConeAngle = 0.7853981634f;
};

struct Camera {
  glm::vec3 position{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float yfov = 0.8f;        // vertical field of view, radians
  float aspectRatio = 0.0f; // the file camera's width / height; 0: not given (the film decides)
  bool fromFile = false;    // false: framed from the scene bounds (defaultFraming); true: set by the
                            // file or on the command line (--look-from, ...: session/scene_camera.h)
};

// An environment light: an equirectangular map of linear radiance around the scene (--env,
// --env-color; session/scene_environment.h). Direction conventions in shaders/shared/environment.h.
struct Environment {
  uint32_t width = 0;               // 0: no environment (escaping rays carry nothing)
  uint32_t height = 0;
  std::vector<glm::vec3> radiance;  // width x height, top row (+Y) first, --env-scale applied
  float rotation = 0.0f;            // radians about +Y (--env-rotate)
  std::string source;               // the file, or "uniform colour", for messages and the stats
  bool present() const { return width > 0 && height > 0; }
};

struct Scene {
  std::string name;                 // file name without directory
  std::vector<Triangle> triangles;
  std::vector<MaterialGpu> materials;
  std::vector<Texture> textures;
  std::vector<PunctualLight> punctualLights;
  Camera camera;
  Bounds bounds;
  Environment environment;
};

}  // namespace mixtrace
