#pragma once
// The white furnace inside an emissive sphere, solved by quadrature for the glTF BRDF as
// implemented (shared::bsdfEval).
//
// Inside a sphere a chord meets the wall at both ends at the same angle to the normal, so the
// radiance leaving the wall depends only on the cosine mu to the local normal, and the Mitsuba
// depth recursion is one-dimensional:
//   L_1(mu) = Le
//   L_k(mu_o) = Le + integral over the hemisphere of f(wo, wi) cos_i L_(k-1)(cos_i) dwi.
// The integral is taken in (theta_i, phi) with composite Gauss rules (theta, not mu, as the
// variable: a narrow GGX lobe around the normal is resolved far better). L_(k-1) is needed at
// the theta_i nodes only, so the recursion runs on those nodes (Nystroem's method) and the
// final L_D is evaluated at any mu with one more application of the kernel.
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "shared/bsdf.h"
#include "support/analytic/quadrature.h"

namespace mixtrace::testing::analytic {

class SphereFurnace {
 public:
  SphereFurnace(const shared::BsdfParams& m, glm::dvec3 le, int maxDepth, int thetaPanels = 24, int phiPanels = 16)
      : m_(m), le_(le), maxDepth_(maxDepth) {
    const double pi = 3.14159265358979323846;
    theta_ = compositeGauss(0.0, 0.5 * pi, thetaPanels, 8);
    phi_ = compositeGauss(0.0, pi, phiPanels, 8);  // f is even in phi: [0, pi] counted twice
    const size_t n = theta_.size();
    kernel_.resize(n * n);
    for (size_t o = 0; o < n; ++o) {
      const std::vector<glm::dvec3> row = kernelRow(theta_[o].x);
      for (size_t i = 0; i < n; ++i) kernel_[o * n + i] = row[i];
    }
    // previous_ = L_(D-1) on the theta nodes.
    previous_.assign(n, le_);
    for (int k = 2; k <= maxDepth_ - 1; ++k) {
      std::vector<glm::dvec3> next(n, le_);
      for (size_t o = 0; o < n; ++o)
        for (size_t i = 0; i < n; ++i) next[o] += kernel_[o * n + i] * previous_[i];
      previous_.swap(next);
    }
  }

  // L_D at the cosine mu between the outgoing direction and the wall normal.
  glm::dvec3 radiance(double mu) const {
    if (maxDepth_ <= 1) return le_;
    const std::vector<glm::dvec3> row = kernelRow(std::acos(glm::clamp(mu, 0.0, 1.0)));
    glm::dvec3 l = le_;
    for (size_t i = 0; i < row.size(); ++i) l += row[i] * previous_[i];
    return l;
  }

  // Directional albedo at mu (the integral of f cos over the hemisphere), for the informational prints.
  glm::dvec3 albedo(double mu) const {
    glm::dvec3 a(0.0);
    for (const glm::dvec3& k : kernelRow(std::acos(glm::clamp(mu, 0.0, 1.0)))) a += k;
    return a;
  }

 private:
  // Weights K_i with integral f(wo, wi) cos_i g(theta_i) dwi ~ sum_i K_i g(theta_i), wo at thetaO.
  std::vector<glm::dvec3> kernelRow(double thetaO) const {
    const glm::vec3 wo(float(std::sin(thetaO)), 0.0f, float(std::cos(thetaO)));
    std::vector<glm::dvec3> row(theta_.size(), glm::dvec3(0.0));
    for (size_t i = 0; i < theta_.size(); ++i) {
      const double st = std::sin(theta_[i].x), ct = std::cos(theta_[i].x);
      glm::dvec3 sum(0.0);
      for (const Node1D& p : phi_) {
        const glm::vec3 wi(float(st * std::cos(p.x)), float(st * std::sin(p.x)), float(ct));
        sum += p.w * glm::dvec3(shared::bsdfEval(m_, wo, wi));
      }
      row[i] = 2.0 * sum * ct * st * theta_[i].w;  // 2: phi in [pi, 2 pi]; sin: the solid angle
    }
    return row;
  }

  shared::BsdfParams m_;
  glm::dvec3 le_;
  int maxDepth_;
  std::vector<Node1D> theta_, phi_;
  std::vector<glm::dvec3> kernel_;
  std::vector<glm::dvec3> previous_;
};

}  // namespace mixtrace::testing::analytic
