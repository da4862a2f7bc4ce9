#pragma once
// The software BVH the renderer traverses (shaders/shared/bvh_traverse.h, on the GPU and on the
// CPU): built on the host with binned SAH and flattened into the node layout of
// shared/layouts.h, so uploading it is a plain copy of `nodes` and `triangles`.
#include <cstdint>
#include <vector>

#include "scene/scene.h"
#include "shared/layouts.h"

namespace mixtrace {

// Deepest node depth the builder produces (root = 0). The traversal stack holds at most one
// entry per level, so this keeps the shared traversal's 64-entry stack from overflowing.
constexpr uint32_t kBvhMaxDepth = 60;
// Most triangles in a leaf.
constexpr uint32_t kBvhMaxLeafSize = 4;

struct Bvh {
  // Node 0 is the root. Interior nodes (triCount == 0) have their children adjacent, at
  // leftOrFirst and leftOrFirst + 1; leaves own triangles [leftOrFirst, leftOrFirst + triCount).
  // Boxes are conservative: grown by a few ulps of their largest coordinate against rounding.
  std::vector<shared::BvhNode> nodes;
  std::vector<uint32_t> triangleOrder;           // BVH-order index -> input triangle index
  // Intersection data in BVH order: v0, e1 = v1 - v0, e2 = v2 - v0. A triangle whose
  // cross(e1, e2) is exactly zero (zero area: it has no normal) is stored with e1 = e2 = 0,
  // which no ray can hit.
  std::vector<shared::TriangleGeom> triangles;
  double buildSeconds = 0.0;
  uint32_t maxDepth = 0;                         // deepest node, root = 0
};

// Throws mixtrace::Error when there are no triangles or a vertex is not finite.
Bvh buildBvh(const std::vector<Triangle>& triangles);

}  // namespace mixtrace
