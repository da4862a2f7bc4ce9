// Flattens the host-side BVH tree into the binary layout of shared/layouts.h.
#include "bvh/bvh_gpu_layout.h"

#include <glm/glm.hpp>

namespace mixtrace {
namespace {

// Writes the tree node `source` at `target` and, for an interior node, appends its two children
// as an adjacent pair, then lays out the left subtree before the right one (the order the
// traversal's memory accesses were tuned on; any order with adjacent children is valid).
void flattenNode(const BvhTree& tree, uint32_t source, uint32_t target,
                 std::vector<shared::BvhNode>& out) {
  const BvhBuildNode& node = tree.nodes[source];
  out[target].boundsMin = node.bounds.min;
  out[target].boundsMax = node.bounds.max;
  if (node.isLeaf()) {
    out[target].leftOrFirst = node.firstTriangle;
    out[target].triCount = node.triangleCount;
    return;
  }
  const uint32_t left = uint32_t(out.size());
  out[target].leftOrFirst = left;
  out[target].triCount = 0;
  out.emplace_back();
  out.emplace_back();
  flattenNode(tree, node.left, left, out);
  flattenNode(tree, node.right, left + 1, out);
}

shared::TriangleGeom makeGeom(const TriangleCorners& tri) {
  shared::TriangleGeom g;
  g.v0 = tri.p[0];
  g.e1 = tri.p[1] - tri.p[0];
  g.e2 = tri.p[2] - tri.p[0];
  if (glm::cross(g.e1, g.e2) == glm::vec3(0.0f)) {
    // No area, no normal: with zero edges the determinant is exactly 0 for every ray, so the
    // traversal never reports it (a hit would only yield a NaN shading normal).
    g.e1 = glm::vec3(0.0f);
    g.e2 = glm::vec3(0.0f);
  }
  return g;
}

}  // namespace

std::vector<shared::BvhNode> flattenBvhNodes(const BvhTree& tree) {
  std::vector<shared::BvhNode> out;
  out.reserve(tree.nodes.size());  // one GPU node per tree node: never reallocated
  out.emplace_back();
  flattenNode(tree, 0, 0, out);
  return out;
}

std::vector<shared::TriangleGeom> flattenBvhTriangles(const BvhTree& tree,
                                                      const std::vector<TriangleCorners>& triangles) {
  std::vector<shared::TriangleGeom> out(tree.triangleOrder.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = makeGeom(triangles[tree.triangleOrder[i]]);
  return out;
}

}  // namespace mixtrace
