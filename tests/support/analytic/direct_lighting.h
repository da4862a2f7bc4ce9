#pragma once
// Direct illumination by emitting triangles, by quadrature over the emitters' area with the glTF
// BRDF as implemented (shared::bsdfEval):
//   L(x, wo) = sum over emitters of integral f(wo, wi) Le cos_x cos_l / d^2 dA,
// counting only the emitters' front faces (emission is one-sided) and assuming nothing occludes
// them (the caller's scenes are built so: a plane under a quad, or under a convex light whose
// front faces tile its silhouette exactly once).
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "shared/bsdf.h"
#include "support/analytic/meshes.h"
#include "support/analytic/quadrature.h"

namespace mixtrace::testing::analytic {

struct EmitterPoint {
  glm::dvec3 position;
  glm::dvec3 normal;   // front-face normal of its triangle
  glm::dvec3 weightedLe;  // Le times the area weight of the quadrature node
};

// Quadrature nodes over the emitting triangles, each triangle split into 4^levels pieces.
inline std::vector<EmitterPoint> emitterNodes(const std::vector<Tri>& tris, glm::dvec3 le, int levels, int order) {
  std::vector<EmitterPoint> out;
  for (const Tri& t : tris) {
    std::vector<TriangleNode> nodes;
    appendTriangleRule(glm::dvec3(t.p[0]), glm::dvec3(t.p[1]), glm::dvec3(t.p[2]), levels, order, nodes);
    for (const TriangleNode& n : nodes) out.push_back({n.point, t.normal(), le * n.weight});
  }
  return out;
}

// Radiance leaving x (surface normal n, any orientation: the BRDF is two-sided, so the side the
// viewer is on counts) towards the unit direction `toViewer`.
// The BRDF at x (normal n, seen from toViewer) as a function of the world direction wi: any
// tangent frame does, the BRDF is isotropic.
struct LocalBsdf {
  const shared::BsdfParams& m;
  glm::dvec3 n, t, b;
  glm::vec3 wo;
  LocalBsdf(const shared::BsdfParams& params, glm::dvec3 normal, glm::dvec3 toViewer) : m(params), n(normal) {
    if (glm::dot(n, toViewer) < 0.0) n = -n;
    const glm::dvec3 helper = std::abs(n.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    t = glm::normalize(glm::cross(helper, n));
    b = glm::cross(n, t);
    wo = local(toViewer);
  }
  glm::vec3 local(glm::dvec3 v) const {
    return glm::vec3(float(glm::dot(v, t)), float(glm::dot(v, b)), float(glm::dot(v, n)));
  }
  glm::dvec3 eval(glm::dvec3 wi) const { return glm::dvec3(shared::bsdfEval(m, wo, local(wi))); }
};

inline glm::dvec3 directRadiance(const shared::BsdfParams& m, glm::dvec3 x, glm::dvec3 n, glm::dvec3 toViewer,
                                 const std::vector<EmitterPoint>& emitters) {
  const LocalBsdf f(m, n, toViewer);
  glm::dvec3 sum(0.0);
  for (const EmitterPoint& e : emitters) {
    const glm::dvec3 d = e.position - x;
    const double dist2 = glm::dot(d, d);
    const glm::dvec3 wi = d / std::sqrt(dist2);
    const double cosX = glm::dot(wi, f.n);
    const double cosL = -glm::dot(wi, e.normal);
    if (cosX <= 0.0 || cosL <= 0.0) continue;
    sum += f.eval(wi) * e.weightedLe * (cosX * cosL / dist2);
  }
  return sum;
}

// Light from infinitely far away (an environment): quadrature nodes over directions.
struct DirectionNode {
  glm::dvec3 direction;   // unit, towards the light
  glm::dvec3 weightedLe;  // Le times the solid-angle weight of the node
};

inline glm::dvec3 directRadianceFromDirections(const shared::BsdfParams& m, glm::dvec3 n, glm::dvec3 toViewer,
                                               const std::vector<DirectionNode>& nodes) {
  const LocalBsdf f(m, n, toViewer);
  glm::dvec3 sum(0.0);
  for (const DirectionNode& d : nodes) {
    const double cosX = glm::dot(d.direction, f.n);
    if (cosX > 0.0) sum += f.eval(d.direction) * d.weightedLe * cosX;
  }
  return sum;
}

}  // namespace mixtrace::testing::analytic
