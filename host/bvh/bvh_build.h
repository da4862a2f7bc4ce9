#pragma once
// The BVH build, apart from any GPU layout: binned SAH over plain host-side nodes
// (bvh_builder.cpp). A layout for the traversal is made from the tree afterwards: the binary one
// the shaders walk is bvh_gpu_layout.h; a second one (a wide BVH) can be flattened from the same
// tree beside it.
#include <cstdint>
#include <vector>

#include "bvh/triangle_corners.h"
#include "util/bounds.h"

namespace mixtrace {

// Deepest node depth the builder produces (root = 0). The traversal stack holds at most one
// entry per level, so this keeps the shared traversal's 64-entry stack from overflowing.
constexpr uint32_t kBvhMaxDepth = 60;
// Most triangles in a leaf.
constexpr uint32_t kBvhMaxLeafSize = 4;

struct BvhBuildNode {
  // Conservative: grown by a few ulps of its largest coordinate against rounding (the
  // traversal's triangle test and slab test both rely on it), so it contains its children's.
  Bounds bounds;
  // A leaf (triangleCount > 0) owns triangleOrder[firstTriangle, firstTriangle + triangleCount).
  uint32_t firstTriangle = 0;
  uint32_t triangleCount = 0;
  // An interior node's children, indices into BvhTree::nodes; the left one holds the triangles
  // of the lower part of the node's range.
  uint32_t left = 0;
  uint32_t right = 0;
  bool isLeaf() const { return triangleCount > 0; }
};

struct BvhTree {
  std::vector<BvhBuildNode> nodes;    // nodes[0] is the root
  std::vector<uint32_t> triangleOrder;  // tree-order index -> input triangle index
  uint32_t maxDepth = 0;                // deepest node, root = 0
};

// Throws mixtrace::Error when there are no triangles or a vertex is not finite.
BvhTree buildBvhTree(const std::vector<TriangleCorners>& triangles);

}  // namespace mixtrace
