#pragma once
// A loaded scene made ready for rendering: BVH built (triangles in BVH order), lights, feature set,
// and every flat array the shaders read. Both backends render from this. It does not depend on
// the method: built once, it serves every method, whose light selection and clusters are tables
// beside it (cms/method_lights.h), so switching methods builds no BVH.
#include <cstdint>
#include <vector>

#include "bvh/bvh.h"
#include "scene/features.h"
#include "scene/light_set.h"
#include "scene/scene.h"
#include "shared/layouts.h"

namespace mixtrace {

struct PreparedScene {
  Scene scene;
  Bvh bvh;
  LightSet lights;
  FeatureSet features;
  std::vector<shared::TriangleShading> shading;  // BVH order
  std::vector<shared::TextureGpu> textures;
  std::vector<uint32_t> texels;
  std::vector<float> environment;  // the ENVIRONMENT buffer (scene/environment_distribution.h)
  std::vector<shared::TriangleUvs> secondUvs;   // per triangle (BVH order) where features.secondUvs; else one
};

PreparedScene prepareScene(Scene scene);

// How many scenes this process has prepared (each one a BVH build): lets the tests check that
// setting up a method, or switching to one, prepares none.
uint64_t preparedSceneCount();

// The camera used when the file has none and the command line sets none: the bounding sphere
// framed from +Z, looking down -Z (its target is the bounds' centre).
Camera defaultFraming(const Scene& scene);

// The pinhole camera for an image of width x height: the file's camera, or a framing of the
// scene bounds looking down -Z when the file has none.
shared::CameraGpu makeCamera(const Scene& scene, uint32_t width, uint32_t height);

}  // namespace mixtrace
