#pragma once
// The BVH layout the shared traversal walks (shaders/shared/bvh_traverse.h, on the GPU
// and on the CPU), flattened from the host-side tree of bvh_build.h: a copy of these arrays is
// all the GPU needs.
#include <vector>

#include "bvh/bvh_build.h"
#include "bvh/triangle_corners.h"
#include "shared/layouts.h"

namespace mixtrace {

// One node per interior tree node, holding both children's boxes (the tree's, unchanged) and
// references to them (shared/layouts.h BvhNode): node 0 is the root, and each node's subtree
// follows it, the left one first. A tree that is a single leaf gives one node whose left child is
// that leaf. Throws mixtrace::Error above 2^28 triangles.
std::vector<shared::BvhNode> flattenBvhNodes(const BvhTree& tree);

// Intersection data in the tree's triangle order: v0, e1 = v1 - v0, e2 = v2 - v0. A triangle
// whose cross(e1, e2) is exactly zero (zero area: it has no normal) is stored with e1 = e2 = 0,
// which no ray can hit.
std::vector<shared::TriangleGeom> flattenBvhTriangles(const BvhTree& tree,
                                                      const std::vector<TriangleCorners>& triangles);

}  // namespace mixtrace
