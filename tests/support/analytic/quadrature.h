#pragma once
// Numerical integration rules for the expectations: Gauss-Legendre nodes (Newton iteration on
// the Legendre recurrence), composite rules on an interval and a product rule on a triangle.
#include <cmath>
#include <vector>

#include <glm/glm.hpp>

namespace mixtrace::testing::analytic {

struct Node1D {
  double x;
  double w;
};

// n-point Gauss-Legendre rule on [-1, 1].
inline std::vector<Node1D> gaussLegendre(int n) {
  std::vector<Node1D> nodes(size_t(n), Node1D{0.0, 0.0});
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(pi * (i + 0.75) / (n + 0.5));  // Tricomi's first guess for the i-th root
    double derivative = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;  // P_0, P_1, then up to P_n by the three-term recurrence
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) p0 = 1.0;
      derivative = n * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-15) break;
    }
    nodes[size_t(i)] = {x, 2.0 / ((1.0 - x * x) * derivative * derivative)};
  }
  return nodes;
}

// `panels` equal sub-intervals of [a, b], each with an `order`-point Gauss-Legendre rule.
inline std::vector<Node1D> compositeGauss(double a, double b, int panels, int order) {
  const std::vector<Node1D> base = gaussLegendre(order);
  std::vector<Node1D> out;
  const double h = (b - a) / panels;
  for (int p = 0; p < panels; ++p)
    for (const Node1D& n : base) out.push_back({a + h * (p + 0.5 * (n.x + 1.0)), 0.5 * h * n.w});
  return out;
}

struct TriangleNode {
  glm::dvec3 point;
  double weight;  // area element: the weights of one triangle sum to its area
};

// Integrates over triangle (a, b, c): the triangle is split into 4^levels congruent pieces and
// each piece gets the collapsed (Duffy) product of two `order`-point Gauss rules,
// p = a' + s (b' - a') + s t (c' - b') with Jacobian s * 2 * area.
inline void appendTriangleRule(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, int levels, int order,
                               std::vector<TriangleNode>& out) {
  if (levels > 0) {
    const glm::dvec3 ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
    appendTriangleRule(a, ab, ca, levels - 1, order, out);
    appendTriangleRule(ab, b, bc, levels - 1, order, out);
    appendTriangleRule(ca, bc, c, levels - 1, order, out);
    appendTriangleRule(ab, bc, ca, levels - 1, order, out);
    return;
  }
  const double twoArea = glm::length(glm::cross(b - a, c - a));
  const std::vector<Node1D> g = gaussLegendre(order);
  for (const Node1D& ns : g)
    for (const Node1D& nt : g) {
      const double s = 0.5 * (ns.x + 1.0), t = 0.5 * (nt.x + 1.0);
      out.push_back({a + s * (b - a) + s * t * (c - b), 0.25 * ns.w * nt.w * s * twoArea});
    }
}

}  // namespace mixtrace::testing::analytic
