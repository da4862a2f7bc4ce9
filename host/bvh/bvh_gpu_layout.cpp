// Flattens the host-side BVH tree into the binary layout of shared/layouts.h.
#include "bvh/bvh_gpu_layout.h"

#include <string>

#include <glm/glm.hpp>

#include "util/error.h"

namespace mixtrace {
namespace {

uint32_t flattenInterior(const BvhTree& tree, uint32_t source, std::vector<shared::BvhNode>& out);

uint32_t childRef(const BvhTree& tree, uint32_t child, std::vector<shared::BvhNode>& out) {
  const BvhBuildNode& node = tree.nodes[child];
  return node.isLeaf() ? shared::bvhLeafRef(node.firstTriangle, node.triangleCount)
                       : flattenInterior(tree, child, out);
}

// Appends the interior tree node `source` with its children's boxes, then its left subtree and
// its right one (depth first, left first: the near child of a visit is often the next node in
// memory). Returns its index. `out` grows during the recursion, so it is indexed, never
// referenced across a call.
uint32_t flattenInterior(const BvhTree& tree, uint32_t source, std::vector<shared::BvhNode>& out) {
  const BvhBuildNode& node = tree.nodes[source];
  const uint32_t index = uint32_t(out.size());
  shared::BvhNode flat{};
  flat.leftMin = tree.nodes[node.left].bounds.min;
  flat.leftMax = tree.nodes[node.left].bounds.max;
  flat.rightMin = tree.nodes[node.right].bounds.min;
  flat.rightMax = tree.nodes[node.right].bounds.max;
  out.push_back(flat);
  const uint32_t left = childRef(tree, node.left, out);
  const uint32_t right = childRef(tree, node.right, out);
  out[index].leftRef = left;
  out[index].rightRef = right;
  return index;
}

shared::TriangleGeom makeGeom(const TriangleCorners& tri) {
  glm::vec3 e1 = tri.p[1] - tri.p[0];
  glm::vec3 e2 = tri.p[2] - tri.p[0];
  if (glm::cross(e1, e2) == glm::vec3(0.0f)) {
    // No area, no normal: with zero edges the determinant is exactly 0 for every ray, so the
    // traversal never reports it (a hit would only yield a NaN shading normal).
    e1 = glm::vec3(0.0f);
    e2 = glm::vec3(0.0f);
  }
  return shared::triangleGeom(tri.p[0], e1, e2);
}

}  // namespace

std::vector<shared::BvhNode> flattenBvhNodes(const BvhTree& tree) {
  // The leaf references address triangles with 28 bits; lavapipe's 128 MiB storage buffers hold
  // 3.7 M triangles, so this is a limit for GPUs only.
  if (tree.triangleOrder.size() > size_t(shared::kBvhLeafFirstMask) + 1)
    throw Error("the scene has " + std::to_string(tree.triangleOrder.size()) +
                " triangles; the BVH addresses at most 268,435,456");
  static_assert(kBvhMaxLeafSize <= (~shared::kBvhLeafRef >> shared::kBvhLeafCountShift),
                "a leaf's triangle count must fit its reference's count bits");
  std::vector<shared::BvhNode> out;
  const BvhBuildNode& root = tree.nodes[0];
  if (root.isLeaf()) {
    shared::BvhNode only{};
    only.leftMin = only.rightMin = root.bounds.min;
    only.leftMax = only.rightMax = root.bounds.max;
    only.leftRef = shared::bvhLeafRef(root.firstTriangle, root.triangleCount);
    only.rightRef = shared::bvhLeafRef(root.firstTriangle, 0);
    out.push_back(only);
    return out;
  }
  out.reserve(tree.nodes.size() / 2);  // one node per interior tree node
  flattenInterior(tree, 0, out);
  return out;
}

std::vector<shared::TriangleGeom> flattenBvhTriangles(const BvhTree& tree,
                                                      const std::vector<TriangleCorners>& triangles) {
  std::vector<shared::TriangleGeom> out(tree.triangleOrder.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = makeGeom(triangles[tree.triangleOrder[i]]);
  return out;
}

}  // namespace mixtrace
