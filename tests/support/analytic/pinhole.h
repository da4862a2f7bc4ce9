#pragma once
// The camera model and a brute-force ray caster over the test scene's triangles, written
// independently of the renderer (shaders/shared/camera.h) for computing per-pixel expectations:
// a pinhole with vertical field of view yfov, aspect = width / height, pixel (0, 0) top left,
// and a box filter (uniform position inside the pixel).
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "support/analytic/gltf_writer.h"
#include "support/analytic/meshes.h"

namespace mixtrace::testing::analytic {

struct Ray {
  glm::dvec3 origin;
  glm::dvec3 direction;  // unit
};

// The ray through image position (px, py) in pixel units (pixel x covers [x, x + 1)).
inline Ray cameraRay(const CameraSpec& c, int width, int height, double px, double py) {
  const double t = std::tan(0.5 * c.yfov);
  const double sx = (2.0 * px / width - 1.0) * t * double(width) / height;
  const double sy = (1.0 - 2.0 * py / height) * t;
  return {c.position, glm::normalize(c.forward() + sx * c.right() + sy * c.trueUp())};
}

struct Hit {
  int triangle = -1;  // -1: the ray leaves the scene
  double t = 0.0;
  glm::dvec3 point{0.0};
};

// Closest hit over all triangles (Moeller-Trumbore in double); fine for a few thousand triangles.
inline Hit closestHit(const std::vector<Tri>& tris, const Ray& r) {
  Hit best;
  best.t = 1e300;
  for (size_t i = 0; i < tris.size(); ++i) {
    const glm::dvec3 a(tris[i].p[0]), e1 = glm::dvec3(tris[i].p[1]) - a, e2 = glm::dvec3(tris[i].p[2]) - a;
    const glm::dvec3 pv = glm::cross(r.direction, e2);
    const double det = glm::dot(e1, pv);
    if (std::abs(det) < 1e-300) continue;
    const glm::dvec3 tv = r.origin - a;
    const double u = glm::dot(tv, pv) / det;
    if (u < 0.0 || u > 1.0) continue;
    const glm::dvec3 qv = glm::cross(tv, e1);
    const double v = glm::dot(r.direction, qv) / det;
    if (v < 0.0 || u + v > 1.0) continue;
    const double t = glm::dot(e2, qv) / det;
    if (t > 1e-9 && t < best.t) {
      best.t = t;
      best.triangle = int(i);
    }
  }
  if (best.triangle < 0) return Hit{};
  best.point = r.origin + best.t * r.direction;
  return best;
}

}  // namespace mixtrace::testing::analytic
