// Binned SAH BVH builder: top-down, one recursive pass. At each node the triangles' centroids are
// binned along all three axes and the plane of least surface-area cost is taken. A node becomes a
// leaf when it holds one triangle, or at most kBvhMaxLeafSize and splitting would cost more than
// testing them all. A median split takes over where SAH cannot split (all centroids in one
// point) and where the depth budget demands it.
//
// The result is the plain host-side tree of bvh_build.h; the layouts the traversals walk are made
// from it afterwards (bvh_gpu_layout.cpp).
#include <algorithm>
#include <cmath>
#include <string>

#include "bvh/bvh_build.h"
#include "util/error.h"

namespace mixtrace {
namespace {

constexpr int kBinCount = 16;
// Cost of visiting a node relative to one triangle test (the SAH's C_trav / C_isect). One
// node visit tests two child boxes, about the price of a triangle.
constexpr float kTraversalCost = 1.0f;

// Half the surface area: the SAH only compares areas, so the factor 2 is irrelevant.
float halfArea(const Bounds& b) {
  glm::vec3 e = b.extent();
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

// Boxes are stored grown by a few ulps of their largest coordinate. The intersection test works
// on v0 + e1, v0 + e2 with rounded edges and its t carries rounding error, so a hit on a
// triangle touching its box's face can land a hair outside the exact box; and a ray with a zero
// direction component whose origin lies exactly on a face plane (an axis-aligned ray along a
// wall's edge) would see the box as empty. Growing by the magnitude (not the size) keeps a small
// box far from the origin padded by more than the rounding of its coordinates. Monotone in the
// bounds, so parents still contain their padded children.
constexpr float kRelativePadding = 1.0f / 1048576.0f;  // 2^-20: 8 ulps
float boundsPadding(const Bounds& b) {
  glm::vec3 magnitude = glm::max(glm::abs(b.min), glm::abs(b.max));
  return std::max(std::max(magnitude.x, magnitude.y), magnitude.z) * kRelativePadding + 1e-30f;
}

// Median splits halve a node, so a node of `count` triangles needs this many more levels
// before every leaf holds at most kBvhMaxLeafSize.
uint32_t medianLevels(uint32_t count) {
  uint32_t levels = 0;
  while (count > kBvhMaxLeafSize) {
    count = (count + 1) / 2;
    ++levels;
  }
  return levels;
}

// Maps a centroid coordinate to its bin along one axis. Clamped, so the centroid at the upper
// bound (and any rounding past it) lands in the last bin.
struct AxisBinning {
  float lo = 0.0f;
  float scale = 0.0f;  // bins per unit length; 0 when the axis cannot be binned
  int bin(float c) const {
    int b = int((c - lo) * scale);
    return std::min(std::max(b, 0), kBinCount - 1);
  }
};

struct SahSplit {
  bool found = false;
  int axis = 0;
  int bin = 0;         // triangles in bins < bin go left
  float cost = 0.0f;   // sum over both sides of halfArea * triangle count
};

class BinnedSahBuilder {
 public:
  BinnedSahBuilder(const std::vector<TriangleCorners>& triangles, BvhTree& out)
      : out_(out), bounds_(triangles.size()), centroids_(triangles.size()) {
    for (size_t i = 0; i < triangles.size(); ++i) {
      for (const glm::vec3& p : triangles[i].p) bounds_[i].grow(p);
      centroids_[i] = bounds_[i].center();
    }
  }

  void build() {
    const uint32_t count = uint32_t(bounds_.size());
    out_.triangleOrder.resize(count);
    for (uint32_t i = 0; i < count; ++i) out_.triangleOrder[i] = i;
    out_.nodes.clear();
    out_.nodes.reserve(2 * size_t(count));  // a binary tree with <= count leaves: < 2 * count nodes
    out_.nodes.emplace_back();
    out_.maxDepth = 0;
    subdivide(0, 0, count, 0);
  }

 private:
  // Invariant: depth + medianLevels(count) <= kBvhMaxDepth for every node, which holds at the
  // root and is kept by both kinds of split below, so no leaf is deeper than kBvhMaxDepth.
  void subdivide(uint32_t nodeIndex, uint32_t first, uint32_t count, uint32_t depth) {
    Bounds nodeBounds, centroidBounds;
    for (uint32_t i = first; i < first + count; ++i) {
      uint32_t t = out_.triangleOrder[i];
      nodeBounds.grow(bounds_[t]);
      centroidBounds.grow(centroids_[t]);
    }
    BvhBuildNode& node = out_.nodes[nodeIndex];  // reserve() above: never reallocated
    const float pad = boundsPadding(nodeBounds);
    node.bounds.min = nodeBounds.min - pad;
    node.bounds.max = nodeBounds.max + pad;
    out_.maxDepth = std::max(out_.maxDepth, depth);

    uint32_t leftCount = 0;  // 0: make a leaf
    if (count > 1) {
      // An SAH split may leave count - 1 triangles on one side; it is allowed only while that
      // child could still be finished by median splits within the depth limit.
      const bool sahAllowed = depth + 1 + medianLevels(count - 1) <= kBvhMaxDepth;
      SahSplit split;
      if (sahAllowed) split = findSahSplit(first, count, centroidBounds);
      const float area = halfArea(nodeBounds);
      // Splitting pays when traversal + both children is cheaper than testing every triangle
      // (in units of triangle tests, scaled by the parent's area to avoid dividing by it).
      const bool splitPays =
          split.found && kTraversalCost * area + split.cost < float(count) * area;
      if (split.found && (splitPays || count > kBvhMaxLeafSize)) {
        leftCount = partitionSah(first, count, split, centroidBounds);
      } else if (count > kBvhMaxLeafSize) {
        leftCount = partitionMedian(first, count, centroidBounds);
      }
    }

    if (leftCount == 0) {
      node.firstTriangle = first;
      node.triangleCount = count;
      return;
    }
    const uint32_t left = uint32_t(out_.nodes.size());
    node.left = left;
    node.right = left + 1;
    node.triangleCount = 0;
    out_.nodes.emplace_back();
    out_.nodes.emplace_back();
    subdivide(left, first, leftCount, depth + 1);
    subdivide(left + 1, first + leftCount, count - leftCount, depth + 1);
  }

  AxisBinning binning(const Bounds& centroidBounds, int axis) const {
    AxisBinning b;
    b.lo = centroidBounds.min[axis];
    float extent = centroidBounds.max[axis] - centroidBounds.min[axis];
    float scale = float(kBinCount) / extent;
    // All centroids in one plane (or an extent so small its inverse overflows): nothing to bin.
    if (extent > 0.0f && std::isfinite(scale)) b.scale = scale;
    return b;
  }

  SahSplit findSahSplit(uint32_t first, uint32_t count, const Bounds& centroidBounds) const {
    SahSplit best;
    for (int axis = 0; axis < 3; ++axis) {
      const AxisBinning binner = binning(centroidBounds, axis);
      if (binner.scale == 0.0f) continue;
      Bounds binBounds[kBinCount];
      uint32_t binCount[kBinCount] = {};
      for (uint32_t i = first; i < first + count; ++i) {
        uint32_t t = out_.triangleOrder[i];
        int b = binner.bin(centroids_[t][axis]);
        binBounds[b].grow(bounds_[t]);
        ++binCount[b];
      }
      // Plane p lies between bins p - 1 and p: sweep from the left for the left sides' area
      // and count, then from the right evaluating each plane.
      float leftArea[kBinCount];
      uint32_t leftCount[kBinCount];
      Bounds sweep;
      uint32_t n = 0;
      for (int p = 1; p < kBinCount; ++p) {
        sweep.grow(binBounds[p - 1]);
        n += binCount[p - 1];
        leftArea[p] = n > 0 ? halfArea(sweep) : 0.0f;
        leftCount[p] = n;
      }
      sweep = Bounds();
      n = 0;
      for (int p = kBinCount - 1; p >= 1; --p) {
        sweep.grow(binBounds[p]);
        n += binCount[p];
        if (n == 0 || leftCount[p] == 0) continue;
        float cost = leftArea[p] * float(leftCount[p]) + halfArea(sweep) * float(n);
        if (!best.found || cost < best.cost) {
          best.found = true;
          best.axis = axis;
          best.bin = p;
          best.cost = cost;
        }
      }
    }
    return best;
  }

  // Both sides are non-empty: the split was chosen among planes with triangles on both sides,
  // and partitioning recomputes exactly the same bins.
  uint32_t partitionSah(uint32_t first, uint32_t count, const SahSplit& split,
                        const Bounds& centroidBounds) {
    const AxisBinning binner = binning(centroidBounds, split.axis);
    auto begin = out_.triangleOrder.begin() + first;
    auto middle = std::partition(begin, begin + count, [&](uint32_t t) {
      return binner.bin(centroids_[t][split.axis]) < split.bin;
    });
    return uint32_t(middle - begin);
  }

  // Halves the node along the axis of largest centroid spread; when every centroid coincides
  // the order is arbitrary, which is as good as any split.
  uint32_t partitionMedian(uint32_t first, uint32_t count, const Bounds& centroidBounds) {
    glm::vec3 spread = centroidBounds.extent();
    int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
    auto begin = out_.triangleOrder.begin() + first;
    uint32_t half = count / 2;
    std::nth_element(begin, begin + half, begin + count, [&](uint32_t a, uint32_t b) {
      return centroids_[a][axis] < centroids_[b][axis];
    });
    return half;
  }

  BvhTree& out_;
  std::vector<Bounds> bounds_;          // per input triangle
  std::vector<glm::vec3> centroids_;    // centre of the triangle's bounds
};

void validate(const std::vector<TriangleCorners>& triangles) {
  if (triangles.empty()) throw Error("cannot build a BVH: the scene has no triangles");
  if (triangles.size() > 0x7fffffffu)
    throw Error("cannot build a BVH: more than 2^31 triangles");
  for (size_t i = 0; i < triangles.size(); ++i) {
    for (const glm::vec3& p : triangles[i].p) {
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw Error("cannot build a BVH: triangle " + std::to_string(i) +
                    " has a non-finite vertex");
    }
  }
}

}  // namespace

BvhTree buildBvhTree(const std::vector<TriangleCorners>& triangles) {
  validate(triangles);
  BvhTree tree;
  BinnedSahBuilder(triangles, tree).build();
  return tree;
}

}  // namespace mixtrace
