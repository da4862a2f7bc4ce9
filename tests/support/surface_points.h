#pragma once
// Shading points on a prepared scene's surfaces, as the shade pass meets them: the centroids of
// random non-emitting triangles, just off the front face, with the geometric normal. For the tests
// of light selection at a point (the light BVH, the BVH defaults of controlled mixture sampling).
#include <cstdint>
#include <random>
#include <vector>

#include <glm/glm.hpp>

#include "scene/prepared_scene.h"

namespace mixtrace::testing {

struct ShadingPoint {
  glm::vec3 p;
  glm::vec3 n;
};

inline std::vector<ShadingPoint> surfacePoints(const PreparedScene& scene, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<ShadingPoint> points;
  const auto& tris = scene.bvh.triangles;
  const float size = glm::length(scene.scene.bounds.extent());
  for (int tries = 0; tries < 100 * count && int(points.size()) < count; ++tries) {
    const uint32_t t = uint32_t(rng() % tris.size());
    if (scene.shading[t].emitter >= 0) continue;
    const glm::vec3 c = glm::cross(tris[t].e1, tris[t].e2);
    const float len = glm::length(c);
    if (!(len > 0.0f)) continue;
    const glm::vec3 n = c / len;
    points.push_back({tris[t].v0 + (tris[t].e1 + tris[t].e2) / 3.0f + n * (1e-4f * size), n});
  }
  return points;
}

}  // namespace mixtrace::testing
