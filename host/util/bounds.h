#pragma once
// An axis-aligned box in world space: the scene's bounds, the BVH's node boxes, the CMS grid's
// extent. Empty (invalid) until grown by a point.
#include <glm/glm.hpp>

namespace mixtrace {

struct Bounds {
  glm::vec3 min{1e30f};
  glm::vec3 max{-1e30f};
  void grow(const glm::vec3& p) { min = glm::min(min, p); max = glm::max(max, p); }
  void grow(const Bounds& b) { min = glm::min(min, b.min); max = glm::max(max, b.max); }
  bool valid() const { return min.x <= max.x && min.y <= max.y && min.z <= max.z; }
  glm::vec3 center() const { return 0.5f * (min + max); }
  glm::vec3 extent() const { return max - min; }
};

}  // namespace mixtrace
