#pragma once
// The binary BVH layout the shared traversal walks (shaders/shared/bvh_traverse.h, on the GPU
// and on the CPU), flattened from the host-side tree of bvh_build.h: a copy of these arrays is
// all the GPU needs.
#include <vector>

#include "bvh/bvh_build.h"
#include "bvh/triangle_corners.h"
#include "shared/layouts.h"

namespace mixtrace {

// Node 0 is the root. Interior nodes (triCount == 0) have their children adjacent, at
// leftOrFirst and leftOrFirst + 1, allocated when their parent is written, and the left
// subtree is laid out before the right one; leaves own triangles [leftOrFirst,
// leftOrFirst + triCount) of the tree's triangle order. Boxes are the tree's, unchanged.
std::vector<shared::BvhNode> flattenBvhNodes(const BvhTree& tree);

// Intersection data in the tree's triangle order: v0, e1 = v1 - v0, e2 = v2 - v0. A triangle
// whose cross(e1, e2) is exactly zero (zero area: it has no normal) is stored with e1 = e2 = 0,
// which no ray can hit.
std::vector<shared::TriangleGeom> flattenBvhTriangles(const BvhTree& tree,
                                                      const std::vector<TriangleCorners>& triangles);

}  // namespace mixtrace
