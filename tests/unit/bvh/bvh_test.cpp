// The BVH builder and the shared traversal against brute force over every triangle, on random
// triangle soups and structured scenes at scales 1e-3 and 1e3, plus the structural invariants
// the GPU relies on (permutation, containment, leaf size, depth) and the GPU layout's relation
// to the layout-free tree it is flattened from (bvh_gpu_layout.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <limits>
#include <random>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/bvh_build.h"
#include "bvh/bvh_gpu_layout.h"
#include "util/error.h"

// The traversal reads the BVH through these pointers, as a shader reads its storage buffers.
namespace bvh_test_buffers {
const mixtrace::shared::BvhNode* nodes = nullptr;
const mixtrace::shared::TriangleGeom* triangles = nullptr;
}  // namespace bvh_test_buffers
#define BVH_NODE(i) (::bvh_test_buffers::nodes[i])
#define BVH_TRIANGLE(i) (::bvh_test_buffers::triangles[i])
#include "shared/bvh_traverse.h"

namespace mixtrace {
namespace {

using glm::vec3;
using shared::HitRecord;
using shared::kNoHit;

const float kFloatMax = std::numeric_limits<float>::max();

void bind(const Bvh& bvh) {
  bvh_test_buffers::nodes = bvh.nodes.data();
  bvh_test_buffers::triangles = bvh.triangles.data();
}

TriangleCorners makeTriangle(vec3 a, vec3 b, vec3 c) {
  TriangleCorners t{};
  t.p[0] = a;
  t.p[1] = b;
  t.p[2] = c;
  return t;
}

class Random {
 public:
  explicit Random(uint32_t seed) : engine_(seed) {}
  float uniform(float lo = 0.0f, float hi = 1.0f) {
    return std::uniform_real_distribution<float>(lo, hi)(engine_);
  }
  int index(int n) { return std::uniform_int_distribution<int>(0, n - 1)(engine_); }
  vec3 inBox(vec3 lo, vec3 hi) { return vec3(uniform(lo.x, hi.x), uniform(lo.y, hi.y), uniform(lo.z, hi.z)); }
  vec3 unitVector() {
    float z = uniform(-1.0f, 1.0f);
    float phi = uniform(0.0f, 6.2831853f);
    float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return vec3(r * std::cos(phi), r * std::sin(phi), z);
  }

 private:
  std::mt19937 engine_;
};

// ---- scenes

// Triangles of random size (1e-3 .. 0.5) in [-1, 1]^3, with the awkward cases mixed in:
// axis-aligned triangles (flat boxes), overlapping coplanar ones, exact duplicates (ties in t),
// zero-area ones, slivers and a few spanning the whole soup.
std::vector<TriangleCorners> randomSoup(uint32_t seed, int count) {
  Random rng(seed);
  std::vector<TriangleCorners> tris;
  while (int(tris.size()) < count) {
    float kind = rng.uniform();
    vec3 c = rng.inBox(vec3(-1.0f), vec3(1.0f));
    float size = std::pow(10.0f, rng.uniform(-3.0f, -0.3f));
    if (kind < 0.6f) {
      tris.push_back(makeTriangle(c + size * rng.unitVector(), c + size * rng.unitVector(),
                                  c + size * rng.unitVector()));
    } else if (kind < 0.72f) {
      // Flat in one axis; half of them on the shared plane 0.25 so they overlap.
      int axis = rng.index(3);
      if (rng.uniform() < 0.5f) c[axis] = 0.25f;
      vec3 p[3];
      for (vec3& v : p) {
        v = c + size * rng.unitVector();
        v[axis] = c[axis];
      }
      tris.push_back(makeTriangle(p[0], p[1], p[2]));
    } else if (kind < 0.8f && !tris.empty()) {
      tris.push_back(tris[rng.index(int(tris.size()))]);  // exact duplicate
    } else if (kind < 0.86f) {
      vec3 a = c + size * rng.unitVector();
      vec3 b = c + size * rng.unitVector();
      float pick = rng.uniform();
      if (pick < 0.33f) tris.push_back(makeTriangle(c, c, c));
      else if (pick < 0.66f) tris.push_back(makeTriangle(a, a, b));
      else tris.push_back(makeTriangle(a, b, a + 0.5f * (b - a)));  // collinear, up to rounding
    } else if (kind < 0.95f) {
      vec3 a = rng.inBox(vec3(-1.0f), vec3(1.0f));
      vec3 b = rng.inBox(vec3(-1.0f), vec3(1.0f));
      tris.push_back(makeTriangle(a, b, a + 1e-3f * rng.unitVector()));  // sliver
    } else {
      tris.push_back(makeTriangle(rng.inBox(vec3(-1.0f), vec3(1.0f)),
                                  rng.inBox(vec3(-1.0f), vec3(1.0f)),
                                  rng.inBox(vec3(-1.0f), vec3(1.0f))));
    }
  }
  return tris;
}

void addQuad(std::vector<TriangleCorners>& tris, vec3 a, vec3 b, vec3 c, vec3 d) {
  tris.push_back(makeTriangle(a, b, c));
  tris.push_back(makeTriangle(a, c, d));
}

void addBox(std::vector<TriangleCorners>& tris, vec3 lo, vec3 hi) {
  vec3 p[8];
  for (int i = 0; i < 8; ++i)
    p[i] = vec3(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
  addQuad(tris, p[0], p[1], p[3], p[2]);
  addQuad(tris, p[4], p[5], p[7], p[6]);
  addQuad(tris, p[0], p[1], p[5], p[4]);
  addQuad(tris, p[2], p[3], p[7], p[6]);
  addQuad(tris, p[0], p[2], p[6], p[4]);
  addQuad(tris, p[1], p[3], p[7], p[5]);
}

// A closed room with a tessellated floor, boxes and a sphere, shifted off the world origin and
// scaled, so that coordinates, edges and t values all live at `scale`.
std::vector<TriangleCorners> roomScene(float scale) {
  std::vector<TriangleCorners> tris;
  addBox(tris, vec3(0.0f), vec3(1.0f));
  const int grid = 30;
  for (int i = 0; i < grid; ++i) {
    for (int j = 0; j < grid; ++j) {
      float x0 = 0.1f + 0.8f * i / grid, x1 = 0.1f + 0.8f * (i + 1) / grid;
      float z0 = 0.1f + 0.8f * j / grid, z1 = 0.1f + 0.8f * (j + 1) / grid;
      addQuad(tris, vec3(x0, 0.05f, z0), vec3(x1, 0.05f, z0), vec3(x1, 0.05f, z1), vec3(x0, 0.05f, z1));
    }
  }
  addBox(tris, vec3(0.15f, 0.05f, 0.2f), vec3(0.4f, 0.6f, 0.45f));
  addBox(tris, vec3(0.6f, 0.05f, 0.6f), vec3(0.85f, 0.3f, 0.85f));
  const int rings = 24, segments = 48;
  const vec3 center(0.55f, 0.5f, 0.35f);
  auto spherePoint = [&](int ring, int seg) {
    float theta = 3.14159265f * ring / rings, phi = 6.2831853f * seg / segments;
    return center + 0.15f * vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                 std::sin(theta) * std::sin(phi));
  };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s)
      addQuad(tris, spherePoint(r, s), spherePoint(r + 1, s), spherePoint(r + 1, s + 1),
              spherePoint(r, s + 1));
  const vec3 offset(3.0f, -2.0f, 5.0f);
  for (TriangleCorners& t : tris)
    for (vec3& p : t.p) p = (p + offset) * scale;
  return tris;
}

// ---- structural checks

struct Box {
  vec3 min, max;
};

bool contains(const Box& box, vec3 p) {
  return glm::all(glm::lessThanEqual(box.min, p)) && glm::all(glm::lessThanEqual(p, box.max));
}

using shared::bvhLeafCount;
using shared::bvhLeafFirst;
using shared::bvhRefIsLeaf;

void checkStructure(const Bvh& bvh, const std::vector<TriangleCorners>& input) {
  const size_t n = input.size();
  ASSERT_EQ(bvh.triangleOrder.size(), n);
  ASSERT_EQ(bvh.triangles.size(), n);
  std::vector<int> seen(n, 0);
  for (uint32_t original : bvh.triangleOrder) {
    ASSERT_LT(original, n);
    ++seen[original];
  }
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(seen[i], 1) << "input triangle " << i;

  // Stored geometry is the input's, in BVH order (zero-area triangles collapsed to a point).
  for (size_t i = 0; i < n; ++i) {
    const TriangleCorners& t = input[bvh.triangleOrder[i]];
    const shared::TriangleGeom& g = bvh.triangles[i];
    ASSERT_EQ(g.v0, t.p[0]);
    vec3 e1 = t.p[1] - t.p[0], e2 = t.p[2] - t.p[0];
    if (glm::cross(e1, e2) == vec3(0.0f)) {
      ASSERT_EQ(g.e1, vec3(0.0f));
      ASSERT_EQ(g.e2, vec3(0.0f));
    } else {
      ASSERT_EQ(g.e1, e1);
      ASSERT_EQ(g.e2, e2);
    }
  }

  // Walk from the root: every node reached exactly once, each after its parent and its left
  // subtree right after it (depth first, left first), boxes nested, leaves small, every
  // BVH-order triangle owned by exactly one leaf.
  std::vector<int> visits(bvh.nodes.size(), 0);
  std::vector<int> owned(n, 0);
  struct Item { uint32_t ref, depth; Box box; };
  const shared::BvhNode& root = bvh.nodes.at(0);
  Box rootBox{glm::min(root.leftMin, root.rightMin), glm::max(root.leftMax, root.rightMax)};
  std::vector<Item> todo{{0, 0, rootBox}};
  uint32_t deepest = 0;
  uint32_t nextNode = 0;  // the index the next interior node reached (left first) must have
  while (!todo.empty()) {
    Item item = todo.back();
    todo.pop_back();
    deepest = std::max(deepest, item.depth);
    if (bvhRefIsLeaf(item.ref)) {
      const uint32_t first = bvhLeafFirst(item.ref), count = bvhLeafCount(item.ref);
      ASSERT_LE(count, kBvhMaxLeafSize);
      ASSERT_LE(size_t(first) + count, n);
      for (uint32_t i = first; i < first + count; ++i) {
        ++owned[i];
        for (const vec3& p : input[bvh.triangleOrder[i]].p)
          ASSERT_TRUE(contains(item.box, p)) << "leaf at " << first << " triangle " << i;
      }
      continue;
    }
    ASSERT_EQ(item.ref, nextNode);
    ++nextNode;
    ASSERT_LT(item.ref, bvh.nodes.size());
    ++visits[item.ref];
    const shared::BvhNode& node = bvh.nodes[item.ref];
    Box left{node.leftMin, node.leftMax}, right{node.rightMin, node.rightMax};
    for (const Box& child : {left, right}) {
      ASSERT_TRUE(contains(item.box, child.min)) << "node " << item.ref;
      ASSERT_TRUE(contains(item.box, child.max)) << "node " << item.ref;
    }
    todo.push_back({node.rightRef, item.depth + 1, right});
    todo.push_back({node.leftRef, item.depth + 1, left});
  }
  for (size_t i = 0; i < visits.size(); ++i) ASSERT_EQ(visits[i], 1) << "node " << i;
  // A single-leaf tree is one node whose right child is an empty leaf: depth 1 in this walk.
  if (bvh.maxDepth == 0) deepest = 0;
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(owned[i], 1) << "BVH-order triangle " << i;
  EXPECT_EQ(deepest, bvh.maxDepth);
  EXPECT_LE(bvh.maxDepth, kBvhMaxDepth);
}

// ---- rays against brute force

struct Ray {
  vec3 origin;
  vec3 direction;
  float tMax;
};

HitRecord bruteClosest(const Bvh& bvh, const Ray& ray) {
  HitRecord best;
  best.t = ray.tMax;
  best.triangle = kNoHit;
  best.u = best.v = 0.0f;
  for (uint32_t i = 0; i < bvh.triangles.size(); ++i) {
    float t, u, v;
    if (shared::bvhIntersectTriangle(bvh.triangles[i], ray.origin, ray.direction, best.t, t, u, v)) {
      best.t = t;
      best.triangle = i;
      best.u = u;
      best.v = v;
    }
  }
  return best;
}

// A mix of ray kinds: origins inside and outside the bounds, rays aimed at triangles, exactly
// axis-aligned directions, directions with one zero component (some with the origin on a
// vertex's coordinate plane, so they run inside flat boxes), unnormalised lengths, finite tMax.
std::vector<Ray> makeRays(const std::vector<TriangleCorners>& tris, uint32_t seed, int count) {
  Bounds bounds;
  for (const TriangleCorners& t : tris)
    for (const vec3& p : t.p) bounds.grow(p);
  const vec3 center = bounds.center();
  const vec3 half = 0.5f * bounds.extent();
  const float radius = glm::length(half);
  const vec3 outerLo = center - 2.0f * half, outerHi = center + 2.0f * half;
  Random rng(seed);
  std::vector<Ray> rays;
  rays.reserve(count);
  for (int i = 0; i < count; ++i) {
    Ray ray;
    const int kind = i % 6;
    ray.origin = kind == 0 ? rng.inBox(bounds.min, bounds.max) : rng.inBox(outerLo, outerHi);
    const float length = radius * std::pow(10.0f, rng.uniform(-1.0f, 1.0f));
    if (kind == 0) {
      ray.direction = length * rng.unitVector();
    } else if (kind == 1) {
      ray.direction = rng.inBox(bounds.min, bounds.max) - ray.origin;
    } else if (kind == 2) {
      const TriangleCorners& t = tris[rng.index(int(tris.size()))];
      float a = rng.uniform(), b = rng.uniform();
      if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
      ray.direction = t.p[0] + a * (t.p[1] - t.p[0]) + b * (t.p[2] - t.p[0]) - ray.origin;
    } else if (kind == 3) {
      ray.direction = vec3(0.0f);
      ray.direction[rng.index(3)] = rng.uniform() < 0.5f ? -length : length;
    } else {
      ray.direction = length * rng.unitVector();
      int axis = rng.index(3);
      ray.direction[axis] = 0.0f;
      if (kind == 5) ray.origin[axis] = tris[rng.index(int(tris.size()))].p[rng.index(3)][axis];
    }
    const float pick = rng.uniform();
    ray.tMax = pick < 0.6f ? kFloatMax
             : pick < 0.7f ? std::numeric_limits<float>::infinity()
                           : 3.0f * radius / glm::length(ray.direction) * rng.uniform();
    rays.push_back(ray);
  }
  return rays;
}

// Möller–Trumbore in float loses the barycentrics of a near-collinear sliver far from the ray
// origin (errors ~ eps * distance / (size * sin(angle))), so it can report a "hit" whose point
// is nowhere near the triangle. Brute force and the BVH then agree only as far as the BVH
// happens to enter the sliver's box; such hits are excluded from the exact-boundary checks.
bool isPhantom(const Bvh& bvh, const Ray& ray, const HitRecord& hit) {
  const shared::TriangleGeom& g = bvh.triangles[hit.triangle];
  Bounds b;
  b.grow(g.v0);
  b.grow(g.v0 + g.e1);
  b.grow(g.v0 + g.e2);
  vec3 p = ray.origin + hit.t * ray.direction;
  vec3 magnitude = glm::max(glm::abs(ray.origin), glm::max(glm::abs(b.min), glm::abs(b.max)));
  float tolerance = 1e-5f * std::max(std::max(magnitude.x, magnitude.y), magnitude.z);
  return glm::any(glm::lessThan(p, b.min - tolerance)) ||
         glm::any(glm::greaterThan(p, b.max + tolerance));
}

struct Mismatches {
  int closest = 0;
  int any = 0;
  int hits = 0;
};

// Closest hit: same hit/miss as brute force, t within 1e-5 relative, and the reported triangle
// really is hit at the reported t (with two triangles at one t, either may be reported).
// Any hit: exactly "closest t < tMax", tested at tMax and just around the closest t.
Mismatches compareWithBruteForce(const Bvh& bvh, const std::vector<Ray>& rays) {
  bind(bvh);
  Mismatches m;
  int printed = 0;
  auto report = [&](const char* what, const Ray& r, const HitRecord& expected,
                    const HitRecord& got) {
    if (printed++ < 5)
      std::printf("mismatch (%s): origin %.9g %.9g %.9g dir %.9g %.9g %.9g tMax %.9g: "
                  "brute force triangle %u t %.9g, BVH triangle %u t %.9g\n", what,
                  r.origin.x, r.origin.y, r.origin.z, r.direction.x, r.direction.y,
                  r.direction.z, r.tMax, expected.triangle, expected.t, got.triangle, got.t);
  };
  for (const Ray& ray : rays) {
    HitRecord expected = bruteClosest(bvh, ray);
    HitRecord got = shared::traceClosest(ray.origin, ray.direction, ray.tMax);
    bool ok;
    if (expected.triangle == kNoHit) {
      ok = got.triangle == kNoHit && got.t == ray.tMax;
    } else {
      ++m.hits;
      ok = got.triangle < bvh.triangles.size() &&
           std::abs(got.t - expected.t) <= 1e-5f * expected.t;
      float t, u, v;
      ok = ok && shared::bvhIntersectTriangle(bvh.triangles[got.triangle], ray.origin,
                                              ray.direction, kFloatMax, t, u, v) &&
           t == got.t && u == got.u && v == got.v;
    }
    if (!ok) {
      ++m.closest;
      report("closest", ray, expected, got);
    }

    bool anyOk = shared::traceAny(ray.origin, ray.direction, ray.tMax) ==
                 (expected.triangle != kNoHit);
    if (expected.triangle != kNoHit && !isPhantom(bvh, ray, expected)) {
      // Nothing is closer than the closest hit; a ray reaching a little past it is blocked.
      // (Not exactly at t: Möller–Trumbore's t carries rounding error, amplified on slivers,
      // so a box can be entered a few ulps after its triangle's computed t.)
      anyOk = anyOk && !shared::traceAny(ray.origin, ray.direction, expected.t) &&
              shared::traceAny(ray.origin, ray.direction, expected.t * (1.0f + 1e-5f));
    }
    if (!anyOk) {
      ++m.any;
      report("any", ray, expected, got);
    }
  }
  return m;
}

void expectAgreement(const std::vector<TriangleCorners>& tris, uint32_t seed, int rayCount) {
  Bvh bvh = buildBvh(tris);
  checkStructure(bvh, tris);
  if (testing::Test::HasFatalFailure()) return;
  Mismatches m = compareWithBruteForce(bvh, makeRays(tris, seed, rayCount));
  EXPECT_EQ(m.closest, 0);
  EXPECT_EQ(m.any, 0);
  // The ray mix must actually hit things, or the comparison proves little.
  EXPECT_GT(m.hits, rayCount / 4);
}

// ---- tests

TEST(Bvh, RandomSoupsMatchBruteForce) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE(seed);
    expectAgreement(randomSoup(seed, 3000), 100 + seed, 10000);
  }
}

TEST(Bvh, MillimetreSceneMatchesBruteForce) { expectAgreement(roomScene(1e-3f), 7, 10000); }

TEST(Bvh, KilometreSceneMatchesBruteForce) { expectAgreement(roomScene(1e3f), 8, 10000); }

TEST(Bvh, SingleTriangle) {
  std::vector<TriangleCorners> tris{makeTriangle(vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f))};
  Bvh bvh = buildBvh(tris);
  checkStructure(bvh, tris);
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_EQ(bvh.nodes[0].leftRef, shared::kBvhLeafRef | (1u << shared::kBvhLeafCountShift));
  EXPECT_EQ(bvh.nodes[0].rightRef, shared::kBvhLeafRef);  // the empty leaf
  bind(bvh);
  HitRecord hit = shared::traceClosest(vec3(0.25f, 0.5f, 2.0f), vec3(0.0f, 0.0f, -2.0f), kFloatMax);
  EXPECT_EQ(hit.triangle, 0u);
  EXPECT_FLOAT_EQ(hit.t, 1.0f);  // in units of the unnormalised direction
  EXPECT_FLOAT_EQ(hit.u, 0.25f);
  EXPECT_FLOAT_EQ(hit.v, 0.5f);
  EXPECT_EQ(shared::traceClosest(vec3(0.75f, 0.5f, 2.0f), vec3(0.0f, 0.0f, -1.0f), kFloatMax).triangle,
            kNoHit);
  EXPECT_EQ(shared::traceClosest(vec3(0.25f, 0.25f, 2.0f), vec3(0.0f, 0.0f, 1.0f), kFloatMax).triangle,
            kNoHit);  // behind the origin
  EXPECT_TRUE(shared::traceAny(vec3(0.25f, 0.25f, 2.0f), vec3(0.0f, 0.0f, -1.0f), 2.5f));
  EXPECT_FALSE(shared::traceAny(vec3(0.25f, 0.25f, 2.0f), vec3(0.0f, 0.0f, -1.0f), 2.0f));  // t < tMax
  EXPECT_FALSE(shared::traceAny(vec3(0.25f, 0.25f, 2.0f), vec3(0.0f, 0.0f, -1.0f), 1.5f));
}

TEST(Bvh, IdenticalCentroidsStillSplit) {
  // 2000 triangles sharing one centroid: SAH has nothing to bin, median splits must take over.
  Random rng(11);
  std::vector<TriangleCorners> tris;
  for (int i = 0; i < 2000; ++i) {
    vec3 a = rng.unitVector(), b = rng.unitVector();
    tris.push_back(makeTriangle(vec3(0.3f) + a, vec3(0.3f) + b, vec3(0.3f) - a - b));
  }
  for (int i = 0; i < 500; ++i) tris.push_back(tris[0]);  // and exact copies
  Bvh bvh = buildBvh(tris);
  checkStructure(bvh, tris);
  Mismatches m = compareWithBruteForce(bvh, makeRays(tris, 12, 2000));
  EXPECT_EQ(m.closest, 0);
  EXPECT_EQ(m.any, 0);
}

TEST(Bvh, DepthStaysBoundedOnPathologicalInput) {
  // Triangles shrinking geometrically towards a point: each SAH split peels off only the few
  // largest, which without the depth guard nests far deeper than the 64-entry stack allows.
  std::vector<TriangleCorners> tris;
  for (int i = 0; i < 120; ++i) {
    for (int k = 0; k < 4; ++k) {
      float s = std::ldexp(1.0f, -i) * (1.0f + 0.1f * k);
      tris.push_back(makeTriangle(vec3(s, 0.0f, 0.0f), vec3(s, s, 0.0f), vec3(s, 0.0f, s)));
    }
  }
  Bvh bvh = buildBvh(tris);
  std::printf("pathological input: %zu triangles, depth %u\n", tris.size(), bvh.maxDepth);
  checkStructure(bvh, tris);
  Mismatches m = compareWithBruteForce(bvh, makeRays(tris, 13, 3000));
  EXPECT_EQ(m.closest, 0);
  EXPECT_EQ(m.any, 0);
}

// The intersection test's rescaling, computed once per triangle (shared/layouts.h triangleGeom):
// powers of two, inverse to each other, bringing the largest edge component into [1, 2).
TEST(Bvh, TriangleRescalingIsAnExactPowerOfTwoNearTheEdges) {
  for (float scale : {1e-30f, 1e-12f, 1e-3f, 1.0f, 3.0f, 1e3f, 1e15f, 1e30f}) {
    const shared::TriangleGeom g = shared::triangleGeom(vec3(5.0f), vec3(scale, 0.0f, 0.0f), vec3(0.0f, -0.5f * scale, 0.0f));
    int e1 = 0, e2 = 0;
    EXPECT_EQ(std::frexp(g.toUnit, &e1), 0.5f) << scale;
    EXPECT_EQ(std::frexp(g.fromUnit, &e2), 0.5f) << scale;
    EXPECT_EQ(g.toUnit * g.fromUnit, 1.0f) << scale;
    const float unit = scale * g.toUnit;
    EXPECT_GE(unit, 1.0f) << scale;
    EXPECT_LT(unit, 2.0f) << scale;
  }
  // Zero edges (a degenerate triangle, as the builder stores it) still get a finite pair.
  const shared::TriangleGeom z = shared::triangleGeom(vec3(1.0f), vec3(0.0f), vec3(0.0f));
  EXPECT_TRUE(std::isfinite(z.toUnit) && std::isfinite(z.fromUnit));
  EXPECT_EQ(z.toUnit * z.fromUnit, 1.0f);
}

TEST(Bvh, ZeroAreaTrianglesAreNeverHit) {
  std::vector<TriangleCorners> tris{
      makeTriangle(vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(2.0f, 0.0f, 0.0f)),  // collinear
      makeTriangle(vec3(0.5f), vec3(0.5f), vec3(0.5f))};                           // a point
  Bvh bvh = buildBvh(tris);
  checkStructure(bvh, tris);
  bind(bvh);
  // Straight through the segment and the point.
  EXPECT_EQ(shared::traceClosest(vec3(1.0f, 0.0f, 1.0f), vec3(0.0f, 0.0f, -1.0f), kFloatMax).triangle, kNoHit);
  EXPECT_EQ(shared::traceClosest(vec3(0.5f, 0.5f, 1.0f), vec3(0.0f, 0.0f, -1.0f), kFloatMax).triangle, kNoHit);
  EXPECT_FALSE(shared::traceAny(vec3(0.5f, 0.5f, 1.0f), vec3(0.0f, 0.0f, -1.0f), kFloatMax));
}

// Bit for bit: the same floats and integers, so +0 and -0 or two NaNs are told apart.
template <typename T>
bool sameBytes(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// Every GPU node is its tree node: the same (padded) box bit for bit, the same leaf range, and
// for an interior node its children at leftOrFirst and leftOrFirst + 1 are the tree node's left
// and right child; every tree node appears once.
void expectFlatteningOf(const BvhTree& tree, const std::vector<shared::BvhNode>& nodes) {
  std::vector<int> seen(tree.nodes.size(), 0);
  size_t interior = 0;
  for (const BvhBuildNode& node : tree.nodes) interior += node.isLeaf() ? 0 : 1;
  ASSERT_EQ(nodes.size(), std::max<size_t>(interior, 1));
  if (tree.nodes[0].isLeaf()) {
    ASSERT_EQ(nodes[0].leftRef, shared::kBvhLeafRef | (tree.nodes[0].triangleCount << shared::kBvhLeafCountShift) |
                                    tree.nodes[0].firstTriangle);
    return;
  }
  std::vector<std::pair<uint32_t, uint32_t>> todo{{0u, 0u}};  // (interior tree node, GPU node)
  while (!todo.empty()) {
    auto [source, target] = todo.back();
    todo.pop_back();
    ASSERT_LT(source, tree.nodes.size());
    ASSERT_LT(target, nodes.size());
    ++seen[source];
    const BvhBuildNode& from = tree.nodes[source];
    const shared::BvhNode& to = nodes[target];
    const uint32_t children[2] = {from.left, from.right};
    const vec3 mins[2] = {to.leftMin, to.rightMin};
    const vec3 maxs[2] = {to.leftMax, to.rightMax};
    const uint32_t refs[2] = {to.leftRef, to.rightRef};
    for (int c = 0; c < 2; ++c) {
      const BvhBuildNode& child = tree.nodes[children[c]];
      ASSERT_TRUE(sameBytes(mins[c], child.bounds.min)) << "node " << target << " child " << c;
      ASSERT_TRUE(sameBytes(maxs[c], child.bounds.max)) << "node " << target << " child " << c;
      if (child.isLeaf()) {
        ++seen[children[c]];
        ASSERT_TRUE(bvhRefIsLeaf(refs[c]));
        ASSERT_EQ(bvhLeafFirst(refs[c]), child.firstTriangle);
        ASSERT_EQ(bvhLeafCount(refs[c]), child.triangleCount);
      } else {
        ASSERT_FALSE(bvhRefIsLeaf(refs[c]));
        todo.push_back({children[c], refs[c]});
      }
    }
  }
  for (size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], 1) << "tree node " << i;
}

void expectSameArrays(const Bvh& a, const Bvh& b) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  ASSERT_EQ(a.triangles.size(), b.triangles.size());
  EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(a.nodes[0])), 0);
  EXPECT_EQ(std::memcmp(a.triangles.data(), b.triangles.data(),
                        a.triangles.size() * sizeof(a.triangles[0])),
            0);
  EXPECT_EQ(a.triangleOrder, b.triangleOrder);
  EXPECT_EQ(a.maxDepth, b.maxDepth);
}

std::vector<std::vector<TriangleCorners>> layoutInputs() {
  std::vector<TriangleCorners> sameCentroid;  // median splits only
  Random rng(31);
  for (int i = 0; i < 300; ++i) {
    vec3 a = rng.unitVector(), b = rng.unitVector();
    sameCentroid.push_back(makeTriangle(a, b, -a - b));
  }
  return {randomSoup(4, 2000), roomScene(1.0f), sameCentroid,
          {makeTriangle(vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f))}};
}

TEST(Bvh, GpuLayoutIsTheTreeFlattened) {
  for (const std::vector<TriangleCorners>& tris : layoutInputs()) {
    SCOPED_TRACE(tris.size());
    BvhTree tree = buildBvhTree(tris);
    Bvh flat;
    flat.nodes = flattenBvhNodes(tree);
    flat.triangles = flattenBvhTriangles(tree, tris);
    flat.triangleOrder = tree.triangleOrder;
    flat.maxDepth = tree.maxDepth;
    expectFlatteningOf(tree, flat.nodes);
    checkStructure(flat, tris);
    // buildBvh is exactly this build and flattening, and both are deterministic.
    expectSameArrays(buildBvh(tris), flat);
  }
}

TEST(Bvh, GpuLayoutOrderDoesNotDependOnTheTreesStorage) {
  // The layout fixes its own node order: a tree stored in another order (here reversed, root
  // still first) flattens to the same bytes.
  for (const std::vector<TriangleCorners>& tris : layoutInputs()) {
    SCOPED_TRACE(tris.size());
    BvhTree tree = buildBvhTree(tris);
    const uint32_t count = uint32_t(tree.nodes.size());
    auto moved = [count](uint32_t i) { return i == 0 ? 0 : count - i; };
    BvhTree reordered = tree;
    for (uint32_t i = 0; i < count; ++i) {
      BvhBuildNode node = tree.nodes[i];
      node.left = moved(node.left);
      node.right = moved(node.right);
      reordered.nodes[moved(i)] = node;
    }
    const std::vector<shared::BvhNode> expected = flattenBvhNodes(tree);
    const std::vector<shared::BvhNode> got = flattenBvhNodes(reordered);
    ASSERT_EQ(got.size(), expected.size());
    EXPECT_EQ(std::memcmp(got.data(), expected.data(), got.size() * sizeof(got[0])), 0);
  }
}

TEST(Bvh, RejectsUnusableInput) {
  EXPECT_THROW(buildBvh({}), Error);
  std::vector<TriangleCorners> tris{makeTriangle(vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f))};
  tris[0].p[1].y = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(buildBvh(tris), Error);
  tris[0].p[1].y = std::numeric_limits<float>::infinity();
  EXPECT_THROW(buildBvh(tris), Error);
}

double threadSeconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Not a pass/fail test: rough single-thread figures for the build and the traversal, in CPU
// time of this thread (the test machines are shared). The scene is a closed, finely tessellated
// bumpy sphere seen from inside, like an interior: every closest-hit ray hits.
TEST(Bvh, PrintsSpeed) {
  const int rings = 250, segments = 400;
  auto point = [&](int r, int s) {
    float theta = 3.14159265f * r / rings, phi = 6.2831853f * s / segments;
    float radius = 1.0f + 0.05f * std::sin(7.0f * theta) * std::cos(5.0f * phi);
    return radius * vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
  };
  std::vector<TriangleCorners> tris;
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      tris.push_back(makeTriangle(point(r, s), point(r + 1, s), point(r + 1, s + 1)));
      tris.push_back(makeTriangle(point(r, s), point(r + 1, s + 1), point(r, s + 1)));
    }
  }
  Bvh bvh = buildBvh(tris);
  std::printf("build: %zu triangles in %.3f s (wall), %zu nodes, depth %u\n", tris.size(),
              bvh.buildSeconds, bvh.nodes.size(), bvh.maxDepth);
  bind(bvh);
  Random rng(21);
  std::vector<Ray> rays;
  for (int i = 0; i < 100000; ++i)
    rays.push_back({0.5f * rng.uniform() * rng.unitVector(), rng.unitVector(), rng.uniform(0.0f, 1.5f)});
  double start = threadSeconds();
  uint32_t hits = 0;
  for (const Ray& r : rays) hits += shared::traceClosest(r.origin, r.direction, kFloatMax).triangle != kNoHit;
  double closestSeconds = threadSeconds() - start;
  start = threadSeconds();
  uint32_t blocked = 0;
  for (const Ray& r : rays) blocked += shared::traceAny(r.origin, r.direction, r.tMax);
  double anySeconds = threadSeconds() - start;
  std::printf("closest hit: %.2f Mrays/s (%u of %zu hit), any hit: %.2f Mrays/s (%u blocked)\n",
              rays.size() / closestSeconds * 1e-6, hits, rays.size(),
              rays.size() / anySeconds * 1e-6, blocked);
  EXPECT_EQ(hits, rays.size());  // closed surface around every origin
}

}  // namespace
}  // namespace mixtrace
