#pragma once
// What a BVH is built over: each triangle's three corners in world space, and nothing else of
// the scene. The scene model (scene/scene.h) lies above the BVH; prepareScene hands the corners
// of its triangles down (cornersOf).
#include <vector>

#include <glm/glm.hpp>

namespace mixtrace {

struct TriangleCorners {
  glm::vec3 p[3];
};

// The corners of `triangles`, in their order (any type with a `p[3]` member: the scene's
// Triangle, a test's own).
template <typename TriangleWithCorners>
std::vector<TriangleCorners> cornersOf(const std::vector<TriangleWithCorners>& triangles) {
  std::vector<TriangleCorners> corners(triangles.size());
  for (size_t i = 0; i < triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) corners[i].p[k] = triangles[i].p[k];
  return corners;
}

}  // namespace mixtrace
