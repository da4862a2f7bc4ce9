#pragma once
// The software BVH the renderer traverses (shaders/shared/bvh_traverse.h, on the GPU and on the
// CPU): built on the host with binned SAH (bvh_build.h) and flattened into the node layout of
// shared/layouts.h (bvh_gpu_layout.h), so uploading it is a plain copy of `nodes` and
// `triangles`.
#include <cstdint>
#include <vector>

#include "bvh/bvh_build.h"
#include "bvh/triangle_corners.h"
#include "shared/layouts.h"

namespace mixtrace {

struct Bvh {
  // The layouts of bvh_gpu_layout.h: see flattenBvhNodes and flattenBvhTriangles.
  std::vector<shared::BvhNode> nodes;
  std::vector<uint32_t> triangleOrder;           // BVH-order index -> input triangle index
  std::vector<shared::TriangleGeom> triangles;
  double buildSeconds = 0.0;                     // build and flattening together
  uint32_t maxDepth = 0;                         // deepest node, root = 0
};

// Throws mixtrace::Error when there are no triangles or a vertex is not finite.
Bvh buildBvh(const std::vector<TriangleCorners>& triangles);

}  // namespace mixtrace
