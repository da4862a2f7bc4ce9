#pragma once
// Triangle soups for the analytic scenes: an icosphere and an oriented rectangle. Positions are
// float, exactly as written to the glTF file, so the expectations integrate over the very
// geometry the renderer loads.
#include <cmath>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace mixtrace::testing::analytic {

// Corners in glTF front-face order: counter-clockwise seen from the side the normal points to.
struct Tri {
  glm::vec3 p[3];
  glm::dvec3 normal() const {
    glm::dvec3 n = glm::cross(glm::dvec3(p[1]) - glm::dvec3(p[0]), glm::dvec3(p[2]) - glm::dvec3(p[0]));
    return n / glm::length(n);
  }
  double area() const {
    return 0.5 * glm::length(glm::cross(glm::dvec3(p[1]) - glm::dvec3(p[0]), glm::dvec3(p[2]) - glm::dvec3(p[0])));
  }
  glm::dvec3 centroid() const { return (glm::dvec3(p[0]) + glm::dvec3(p[1]) + glm::dvec3(p[2])) / 3.0; }
};

// Icosahedron around `centre`, each face split into 4^subdivisions, vertices on the sphere of
// `radius`. Front faces point outwards, or inwards with `inward` (a room seen from inside).
// Edge midpoints are computed from the same two endpoints in every face that shares the edge,
// so neighbouring faces share bit-identical vertices: the mesh is closed.
inline std::vector<Tri> icosphere(glm::dvec3 centre, double radius, int subdivisions, bool inward) {
  const double g = 0.5 * (1.0 + std::sqrt(5.0));
  std::vector<glm::dvec3> v;
  for (double a : {-1.0, 1.0})
    for (double b : {-g, g}) {
      v.push_back({0.0, a, b});
      v.push_back({a, b, 0.0});
      v.push_back({b, 0.0, a});
    }
  // The faces are the vertex triples at mutual distance 2 (the edge length): no table to get wrong.
  std::vector<std::vector<glm::dvec3>> faces;
  auto isEdge = [&](int i, int j) { return std::abs(glm::length(v[i] - v[j]) - 2.0) < 1e-9; };
  for (int i = 0; i < 12; ++i)
    for (int j = i + 1; j < 12; ++j)
      for (int k = j + 1; k < 12; ++k)
        if (isEdge(i, j) && isEdge(j, k) && isEdge(i, k)) faces.push_back({v[i], v[j], v[k]});
  for (auto& f : faces)
    for (auto& p : f) p = glm::normalize(p);
  for (int s = 0; s < subdivisions; ++s) {
    std::vector<std::vector<glm::dvec3>> finer;
    auto mid = [](glm::dvec3 a, glm::dvec3 b) { return glm::normalize(a + b); };  // a + b == b + a exactly
    for (const auto& f : faces) {
      glm::dvec3 ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({ab, f[1], bc});
      finer.push_back({ca, bc, f[2]});
      finer.push_back({ab, bc, ca});
    }
    faces.swap(finer);
  }
  std::vector<Tri> out;
  for (auto f : faces) {
    const bool outward = glm::dot(glm::cross(f[1] - f[0], f[2] - f[0]), f[0] + f[1] + f[2]) > 0.0;
    if (outward == inward) std::swap(f[1], f[2]);
    Tri t;
    for (int k = 0; k < 3; ++k) t.p[k] = glm::vec3(centre + radius * f[k]);
    out.push_back(t);
  }
  return out;
}

// The rectangle {origin + s u + t w : s, t in [0, 1]} as two triangles whose front face points
// along `facing` (which must not be perpendicular to u x w).
inline std::vector<Tri> rectangle(glm::dvec3 origin, glm::dvec3 u, glm::dvec3 w, glm::dvec3 facing) {
  if (glm::dot(glm::cross(u, w), facing) < 0.0) std::swap(u, w);
  const glm::vec3 a(origin), b(origin + u), c(origin + u + w), d(origin + w);
  return {Tri{{a, b, c}}, Tri{{a, c, d}}};
}

}  // namespace mixtrace::testing::analytic
