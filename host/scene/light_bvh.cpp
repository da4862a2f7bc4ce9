#include "scene/light_bvh.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mixtrace {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A cone of directions: within theta of w; empty where theta < 0.
struct Cone {
  glm::dvec3 w{0.0, 0.0, 1.0};
  double theta = -1.0;
  bool empty() const { return theta < 0.0; }
};

// The smallest cone holding both (pbrt-v4's DirectionCone Union): a cone rotated from a's axis
// towards b's by half the angle that the union adds.
Cone unite(const Cone& a, const Cone& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  double between = std::acos(std::clamp(glm::dot(a.w, b.w), -1.0, 1.0));
  if (std::min(between + b.theta, kPi) <= a.theta) return a;
  if (std::min(between + a.theta, kPi) <= b.theta) return b;
  double theta = 0.5 * (a.theta + between + b.theta);
  if (theta >= kPi) return Cone{a.w, kPi};
  glm::dvec3 axis = glm::cross(a.w, b.w);
  double axisLength = glm::length(axis);
  if (!(axisLength > 0.0)) return Cone{a.w, kPi};
  axis /= axisLength;
  double rotation = theta - a.theta;   // about `axis`, which is perpendicular to a.w
  glm::dvec3 w = a.w * std::cos(rotation) + glm::cross(axis, a.w) * std::sin(rotation);
  return Cone{glm::normalize(w), theta};
}

// What a subtree's lights can emit: box, power, normals within thetaO of the axis, each emitting
// within thetaE of its normal.
struct LightBounds {
  glm::dvec3 min{1e300}, max{-1e300};
  double power = 0.0;
  Cone normals;
  double thetaE = 0.0;
  glm::dvec3 centroid() const { return 0.5 * (min + max); }
  void add(const LightBounds& o) {
    min = glm::min(min, o.min);
    max = glm::max(max, o.max);
    power += o.power;
    normals = unite(normals, o.normals);
    thetaE = std::max(thetaE, o.thetaE);
  }
};

// pbrt-v4's split cost (BVHLightSampler::EvaluateCost): power x the solid-angle measure of the
// orientation bounds x the box's area, stretched along thin axes.
double splitCost(const LightBounds& b, const glm::dvec3& extent, int axis) {
  double thetaO = std::max(0.0, b.normals.theta);
  double thetaW = std::min(thetaO + b.thetaE, kPi);
  double sinO = std::sin(thetaO), cosO = std::cos(thetaO);
  double mOmega = 2.0 * kPi * (1.0 - cosO) +
                  0.5 * kPi * (2.0 * thetaW * sinO - std::cos(thetaO - 2.0 * thetaW) - 2.0 * thetaO * sinO + cosO);
  glm::dvec3 d = glm::max(b.max - b.min, glm::dvec3(0.0));
  double area = 2.0 * (d.x * d.y + d.y * d.z + d.z * d.x);
  double longest = std::max(extent.x, std::max(extent.y, extent.z));
  double kr = extent[axis] > 0.0 ? longest / extent[axis] : 1.0;
  return b.power * mOmega * kr * area;
}

LightBounds boundsOfLight(const PreparedScene& scene, uint32_t index) {
  const shared::LightGpu& l = scene.lights.lights[index];
  LightBounds b;
  b.power = scene.lights.power[index];
  if (l.kind == shared::kLightArea) {
    b.thetaE = 0.5 * kPi;   // cosine emission about each normal
    for (uint32_t e = l.firstEmitter; e < l.firstEmitter + l.emitterCount; ++e) {
      uint32_t t = scene.lights.emitters[e].triangle;
      const shared::TriangleGeom& g = scene.bvh.triangles[t];
      glm::dvec3 v0(g.v0), e1(g.e1), e2(g.e2);
      for (glm::dvec3 v : {v0, v0 + e1, v0 + e2}) {
        b.min = glm::min(b.min, v);
        b.max = glm::max(b.max, v);
      }
      const shared::MaterialGpu& m = scene.scene.materials[scene.shading[t].material];
      glm::dvec3 n = glm::cross(e1, e2);
      double len = glm::length(n);
      // Double-sided emitters (and degenerate triangles) face every way.
      bool everyWay = (m.flags & shared::kMaterialDoubleSided) != 0 || !(len > 0.0);
      b.normals = unite(b.normals, everyWay ? Cone{glm::dvec3(0, 0, 1), kPi} : Cone{n / len, 0.0});
    }
    return b;
  }
  b.min = b.max = glm::dvec3(l.position);
  if (l.kind == shared::kLightSpot && l.spotScale > 0.0f) {
    // glTF's falloff is 0 beyond the outer cone, where cos * scale + offset = 0.
    double cosOuter = std::clamp(-double(l.spotOffset) / double(l.spotScale), -1.0, 1.0);
    b.normals = Cone{glm::normalize(glm::dvec3(l.direction)), 0.0};
    b.thetaE = std::acos(cosOuter);
  } else {
    b.normals = Cone{glm::dvec3(0, 0, 1), kPi};
    b.thetaE = 0.5 * kPi;
  }
  return b;
}

shared::LightBvhNodeGpu toGpu(const LightBounds& b, uint32_t kind) {
  shared::LightBvhNodeGpu n{};
  n.boundsMin = glm::vec3(b.min);
  n.boundsMax = glm::vec3(b.max);
  n.power = float(b.power);
  n.axis = glm::vec3(b.normals.w);
  // Rounded outwards, so the float bounds still hold every light (the importance is then never 0
  // where a light reaches).
  n.cosThetaO = std::max(-1.0f, float(std::cos(std::max(0.0, b.normals.theta))) - 1e-6f);
  n.cosThetaE = std::max(-1.0f, float(std::cos(b.thetaE)) - 1e-6f);
  n.kind = kind;
  return n;
}

struct Builder {
  const std::vector<LightBounds>& lights;
  std::vector<shared::LightBvhNodeGpu>& nodes;

  // Builds the subtree of lights [begin, end) and returns its node; trail/depth are the path from
  // the root to it.
  uint32_t build(std::vector<uint32_t>& order, size_t begin, size_t end, uint32_t trail, uint32_t depth) {
    if (end - begin == 1) {
      uint32_t light = order[begin];
      shared::LightBvhNodeGpu& leaf = nodes[1 + light];
      leaf = toGpu(lights[light], shared::kLightBvhLeaf);
      leaf.first = light;
      leaf.second = trail;
      leaf.third = depth;
      return 1 + light;
    }
    LightBounds all, centroids;
    for (size_t i = begin; i < end; ++i) {
      all.add(lights[order[i]]);
      glm::dvec3 c = lights[order[i]].centroid();
      centroids.min = glm::min(centroids.min, c);
      centroids.max = glm::max(centroids.max, c);
    }
    size_t mid = split(order, begin, end, all, centroids, depth);
    uint32_t self = uint32_t(nodes.size());
    nodes.push_back(toGpu(all, shared::kLightBvhInterior));
    uint32_t first = build(order, begin, mid, trail, depth + 1);
    uint32_t second = build(order, mid, end, trail | (1u << depth), depth + 1);
    nodes[self].first = first;
    nodes[self].second = second;
    return self;
  }

  // Where to split [begin, end): the cheapest of 12 buckets per axis by splitCost, or the median
  // of the longest axis where no bucket split exists or the trail would outgrow 32 bits.
  size_t split(std::vector<uint32_t>& order, size_t begin, size_t end, const LightBounds& all,
               const LightBounds& centroids, uint32_t depth) {
    glm::dvec3 extent = glm::max(all.max - all.min, glm::dvec3(0.0));
    glm::dvec3 cExtent = centroids.max - centroids.min;
    double bestCost = INFINITY;
    int bestAxis = -1, bestBucket = 0;
    constexpr int kBuckets = 12;
    double log2Count = std::ceil(std::log2(double(end - begin)));
    bool roomToSpare = double(depth) + log2Count < 30.0;
    for (int axis = 0; axis < 3 && roomToSpare; ++axis) {
      if (!(cExtent[axis] > 0.0)) continue;
      LightBounds buckets[kBuckets];
      for (size_t i = begin; i < end; ++i) buckets[bucketOf(lights[order[i]], centroids, axis)].add(lights[order[i]]);
      for (int s = 0; s < kBuckets - 1; ++s) {
        LightBounds below, above;
        for (int k = 0; k <= s; ++k) if (buckets[k].min.x <= buckets[k].max.x) below.add(buckets[k]);
        for (int k = s + 1; k < kBuckets; ++k) if (buckets[k].min.x <= buckets[k].max.x) above.add(buckets[k]);
        if (!(below.min.x <= below.max.x) || !(above.min.x <= above.max.x)) continue;
        double cost = splitCost(below, extent, axis) + splitCost(above, extent, axis);
        if (cost < bestCost) {
          bestCost = cost;
          bestAxis = axis;
          bestBucket = s;
        }
      }
    }
    auto first = order.begin() + long(begin), last = order.begin() + long(end);
    if (bestAxis >= 0) {
      auto midIt = std::partition(first, last, [&](uint32_t l) { return bucketOf(lights[l], centroids, bestAxis) <= bestBucket; });
      size_t mid = size_t(midIt - order.begin());
      if (mid > begin && mid < end) return mid;
    }
    int axis = cExtent.x >= cExtent.y && cExtent.x >= cExtent.z ? 0 : (cExtent.y >= cExtent.z ? 1 : 2);
    size_t mid = begin + (end - begin) / 2;
    std::nth_element(first, order.begin() + long(mid), last,
                     [&](uint32_t a, uint32_t b) { return lights[a].centroid()[axis] < lights[b].centroid()[axis]; });
    return mid;
  }

  static int bucketOf(const LightBounds& b, const LightBounds& centroids, int axis) {
    double extent = centroids.max[axis] - centroids.min[axis];
    int k = int(12.0 * (b.centroid()[axis] - centroids.min[axis]) / extent);
    return std::clamp(k, 0, 11);
  }
};

}  // namespace

std::vector<shared::LightBvhNodeGpu> buildLightBvh(const PreparedScene& scene) {
  const LightSet& set = scene.lights;
  const uint32_t count = uint32_t(set.lights.size());
  std::vector<shared::LightBvhNodeGpu> nodes(1 + count);
  std::vector<LightBounds> bounds(count);
  std::vector<uint32_t> positioned, directional;
  double directionalPower = 0.0, positionedPower = 0.0;
  for (uint32_t i = 0; i < count; ++i) {
    // Lights at infinity (directional, the environment) have no position: chosen apart.
    const uint32_t kind = set.lights[i].kind;
    if (kind == shared::kLightDirectional || kind == shared::kLightEnvironment) {
      directional.push_back(i);
      directionalPower += set.power[i];
    } else {
      bounds[i] = boundsOfLight(scene, i);
      positioned.push_back(i);
      positionedPower += set.power[i];
    }
  }
  // The directional lights' share: their power against the tree's (all of it without a tree,
  // none without directional lights, half each where nothing has power).
  double pDirectional = 0.0;
  if (!directional.empty()) {
    double total = directionalPower + positionedPower;
    pDirectional = positioned.empty() ? 1.0 : (total > 0.0 ? directionalPower / total : 0.5);
  }
  // nodes grows below: the header is written through its index.
  const float pDirectionalGpu = float(pDirectional);
  nodes[0].kind = shared::kLightBvhHeader;
  nodes[0].power = pDirectionalGpu;
  nodes[0].second = 1 + count;
  nodes[0].third = uint32_t(directional.size());
  double cdf = 0.0;
  for (size_t k = 0; k < directional.size(); ++k) {
    uint32_t i = directional[k];
    double inSet = directionalPower > 0.0 ? set.power[i] / directionalPower : 1.0 / double(directional.size());
    cdf += inSet;
    shared::LightBvhNodeGpu entry{};
    entry.kind = shared::kLightBvhDirectional;
    entry.first = i;
    entry.power = k + 1 == directional.size() ? 1.0f : float(cdf);
    nodes.push_back(entry);
    shared::LightBvhNodeGpu& own = nodes[1 + i];
    own.kind = shared::kLightBvhDirectional;
    own.first = i;
    own.power = float(double(pDirectionalGpu) * inSet);
  }
  if (positioned.empty()) {
    nodes[0].first = 0xffffffffu;
    return nodes;
  }
  Builder builder{bounds, nodes};
  uint32_t root = builder.build(positioned, 0, positioned.size(), 0u, 0u);
  nodes[0].first = root;
  return nodes;
}

}  // namespace mixtrace
