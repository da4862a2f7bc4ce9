// The renderer's BVH: the layout-free build, then its flattening into the GPU layout.
#include "bvh/bvh.h"

#include <chrono>
#include <utility>

#include "bvh/bvh_gpu_layout.h"

namespace mixtrace {

Bvh buildBvh(const std::vector<TriangleCorners>& triangles) {
  const auto start = std::chrono::steady_clock::now();
  BvhTree tree = buildBvhTree(triangles);
  Bvh bvh;
  bvh.nodes = flattenBvhNodes(tree);
  bvh.triangles = flattenBvhTriangles(tree, triangles);
  bvh.maxDepth = tree.maxDepth;
  bvh.triangleOrder = std::move(tree.triangleOrder);
  bvh.buildSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace mixtrace
