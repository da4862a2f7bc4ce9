// Software BVH traversal (closest hit and any hit), written once for the GPU intersect/shadow
// passes and the CPU renderer. Walks the flattened BVH of host/bvh/bvh.h.
//
// The includer defines, before including this header:
//   BVH_NODE(i)      -> the BvhNode at index i
//   BVH_TRIANGLE(i)  -> the TriangleGeom at BVH-order index i
// and, optionally, BVH_ALPHA_PASSES(i, u, v, origin, direction) -> bool: the ray passes through
// triangle i there (alpha: shared/alpha.h); without it every triangle is opaque.
// In C++ the functions have internal linkage (an anonymous namespace inside
// mixtrace::shared), so two translation units that bind the macros to different buffers do not
// collide under the one-definition rule.
//
// Conventions: rays start exactly at `origin` (callers offset origins off surfaces); a hit
// counts when 0 < t < tMax, with t in units of `direction` (which need not be normalised).
// HitRecord.u/.v are the barycentric weights of v1 and v2.
//
// Speed: a node holds both children's boxes (shared/layouts.h BvhNode), so a visit is one 64-byte
// read; the nearer child is entered at once and the farther pushed as its reference with its
// entry distance, so the stack only holds boxes the ray does enter, a popped child needs no read
// to know whether it is a leaf, and the closest-hit search drops those that start beyond the
// best hit so far. (On lavapipe this took the intersect pass 10-16 % and the shadow pass 4-10 %
// below the layout with one box per node, which read both children per visit and a node again
// per pop: benchmarks/README.md, "BVH layout".)
#ifndef MIXTRACE_SHARED_BVH_TRAVERSE_H
#define MIXTRACE_SHARED_BVH_TRAVERSE_H
#include "shared/layouts.h"

#if !defined(BVH_NODE) || !defined(BVH_TRIANGLE)
#error "define BVH_NODE(i) and BVH_TRIANGLE(i) before including shared/bvh_traverse.h"
#endif

SHARED_BEGIN_WITH_BUFFERS

// How many of the current leaf's triangles one step of the walk tests. Scalar code (C++) tests
// the whole leaf before it pops the next box, the order of a recursive traversal. SIMD code (GLSL)
// tests one: a SIMD group runs every branch for all its lanes under a mask (lavapipe does even
// when they all agree), so a step costs one box pair plus one triangle whatever each lane needs,
// and a lane whose leaf still has triangles left goes on down the tree beside them instead of
// holding up the group (benchmarks/README.md, "What a pass costs on lavapipe").
#ifdef __cplusplus
#define BVH_TRIANGLE_STEP while
#else
#define BVH_TRIANGLE_STEP if
#endif

// The triangle test's rejections: scalar code returns at the first (most rays miss most
// triangles); SIMD code gathers them into one flag and decides once, since a SIMD group computes
// every line for all its lanes anyway and each early return costs it a lane mask to keep.
#ifdef __cplusplus
#define BVH_REJECTIONS
#define BVH_REJECT_IF(rejected) if (rejected) return false
#define BVH_NOT_REJECTED true
#else
#define BVH_REJECTIONS bool bvhRejected = false
#define BVH_REJECT_IF(rejected) bvhRejected = bvhRejected || (rejected)
#define BVH_NOT_REJECTED (!bvhRejected)
#endif

// One entry per tree level suffices; the builder caps the depth at 60 (kBvhMaxDepth).
const uint kBvhStackSize = 64u;
// Box entry distance meaning "missed" (any real entry is below it).
const float kBvhMiss = 3.0e38f;
// Direction components smaller than this are replaced by it (keeping the sign), so the
// reciprocal stays finite and the slab test never forms 0 * inf = NaN. A ray that moves 1e-20
// per unit along an axis is parallel to it for every box at scene scales of 1e-3 .. 1e3.
const float kBvhTinyDirection = 1.0e-20f;
// The slab test's exit distance is scaled up by a few ulps (Ize, "Robust BVH Ray Traversal",
// JCGT 2013: 1 + 2 * gamma(3)) so rounding can never cull a box whose triangles the ray hits,
// e.g. flat boxes around axis-aligned triangles. (The builder also pads every box by a few
// ulps of its coordinates, for the error of the triangle test itself.)
const float kBvhExitScale = 1.0000004f;

SHARED_FN float bvhSafeComponent(float d) {
  return abs(d) < kBvhTinyDirection ? (d < 0.0f ? -kBvhTinyDirection : kBvhTinyDirection) : d;
}

SHARED_FN vec3 bvhSafeReciprocal(vec3 d) {
  return vec3(1.0f / bvhSafeComponent(d.x), 1.0f / bvhSafeComponent(d.y),
              1.0f / bvhSafeComponent(d.z));
}

// min and max as one compare and select. Every operand here is finite (bvhSafeReciprocal keeps
// 1 / d finite and boxes are finite), so GLSL's min/max, which lavapipe makes NaN-aware (a
// compare for unordered operands and a blend more per call), would buy nothing.
SHARED_FN float bvhMin(float a, float b) { return a < b ? a : b; }
SHARED_FN float bvhMax(float a, float b) { return a > b ? a : b; }

// Distance at which the ray enters the box (0 when it starts inside), or kBvhMiss when it misses
// the box or reaches it only beyond tFar (give or take the rounding slack of kBvhExitScale).
SHARED_FN float bvhBoxEntry(vec3 boundsMin, vec3 boundsMax, vec3 origin, vec3 invDir, float tFar) {
  // (b - o) * invDir rather than b * invDir - o * invDir: the latter cancels catastrophically
  // when the origin is far from the world origin but close to the box.
  vec3 t0 = (boundsMin - origin) * invDir;
  vec3 t1 = (boundsMax - origin) * invDir;
  float lowX = bvhMin(t0.x, t1.x);
  float lowY = bvhMin(t0.y, t1.y);
  float lowZ = bvhMin(t0.z, t1.z);
  float highX = bvhMax(t0.x, t1.x);
  float highY = bvhMax(t0.y, t1.y);
  float highZ = bvhMax(t0.z, t1.z);
  float enter = bvhMax(bvhMax(lowX, lowY), bvhMax(lowZ, 0.0f));
  float exit = bvhMin(bvhMin(highX, highY), bvhMin(highZ, tFar)) * kBvhExitScale;
  return enter <= exit ? enter : kBvhMiss;
}

// Möller–Trumbore with the division deferred until the ray is known to cross the triangle (in C++;
// SIMD code divides for every lane and discards the rejected ones, BVH_REJECT_IF above):
// u, v and t are first formed scaled by the determinant and compared against it after flipping
// to a positive determinant. That needs no epsilon (which would be wrong at some scene scale):
// a ray parallel to the triangle (det == 0, as for every ray against a zero-area triangle,
// stored with zero edges) is rejected exactly, and near-parallel rays end up with
// barycentrics outside [0, 1] or a t beyond tMax. t is computed independently of tMax and then
// compared with it, so for one ray every caller sees the same t for a triangle: traceAny(tMax)
// is exactly "the closest hit has t < tMax". Edges use >= / <= on both sides, so a ray through
// a shared edge is kept by at least one of its triangles up to rounding. The scaled quantities
// are rescaled by the triangle's toUnit / fromUnit (shared/layouts.h triangleGeom says why).
SHARED_FN bool bvhIntersectTriangle(TriangleGeom tri, vec3 origin, vec3 direction, float tMax,
                                    OUT(float) t, OUT(float) u, OUT(float) v) {
  BVH_REJECTIONS;
  float toUnit = tri.toUnit;
  float fromUnit = tri.fromUnit;
  vec3 e1 = tri.e1 * toUnit;
  vec3 e2 = tri.e2 * toUnit;
  vec3 p = cross(direction, e2);
  float det = dot(e1, p);
  float flip = det < 0.0f ? -1.0f : 1.0f;
  float absDet = det * flip;
  vec3 s = (origin - tri.v0) * toUnit;
  float uScaled = dot(s, p) * flip;
  BVH_REJECT_IF(uScaled < 0.0f || uScaled > absDet);
  vec3 q = cross(s, e1);
  float vScaled = dot(direction, q) * flip;
  float tScaled = dot(e2, q) * flip;
  BVH_REJECT_IF(vScaled < 0.0f || uScaled + vScaled > absDet || tScaled <= 0.0f || absDet == 0.0f);
  float invDet = 1.0f / absDet;
  t = tScaled * invDet * fromUnit;
  u = uScaled * invDet;
  v = vScaled * invDet;
  return BVH_NOT_REJECTED && t > 0.0f && t < tMax;
}

// Tests triangle i (BVH order) against the ray and, when it is hit before hit.t (and, with alpha,
// not passed through there), makes it the hit. Returns whether it did.
SHARED_FN bool bvhLeafTriangle(uint i, vec3 origin, vec3 direction, INOUT(HitRecord) hit) {
  float t = 0.0f;
  float u = 0.0f;
  float v = 0.0f;
  if (!bvhIntersectTriangle(BVH_TRIANGLE(i), origin, direction, hit.t, t, u, v)) return false;
#ifdef BVH_ALPHA_PASSES
  if (BVH_ALPHA_PASSES(i, u, v, origin, direction)) return false;
#endif
  hit.t = t;
  hit.triangle = i;
  hit.u = u;
  hit.v = v;
  return true;
}

// The one walk behind traceClosest and traceAny. With stopAtFirstHit it returns at the first
// triangle hit with 0 < t < tMax (any hit will do: shadow rays), otherwise it keeps the closest.
// Callers pass a constant, so the compiler folds the flag and each caller gets its own loop.
// Until a hit, hit.t is tMax, so both searches test the same boxes in the same order; and every
// box the any-hit search pushes starts before tMax * kBvhExitScale, so the pop test below
// passes there and is skipped.
// Each turn of the loop is one step of the walk (a node's boxes, or taking the next leaf once the
// last one's triangles are done) and one step through the leaf's triangles (BVH_TRIANGLE_STEP).
// The any-hit search tests its triangles first, so a blocker ends the walk a step sooner; the
// closest-hit search tests them before it pops, so the pop culls against the nearest hit yet.
SHARED_FN HitRecord bvhTraverse(vec3 origin, vec3 direction, float tMax, bool stopAtFirstHit) {
  HitRecord hit;
  hit.t = tMax;
  hit.triangle = kNoHit;
  hit.u = 0.0f;
  hit.v = 0.0f;
  vec3 invDir = bvhSafeReciprocal(direction);

  uint stack[kBvhStackSize];
  float stackEntry[kBvhStackSize];
  uint stackSize = 0u;
  uint current = 0u;  // the next child to visit; node 0, the root, is the first
  bool walking = true;  // false once the stack holds no box the ray still needs
  uint triNext = 0u;  // the triangles [triNext, triEnd) of the leaf being tested
  uint triEnd = 0u;
  while (walking || triNext < triEnd) {
    if (stopAtFirstHit) {
      BVH_TRIANGLE_STEP (triNext < triEnd) {
        if (bvhLeafTriangle(triNext++, origin, direction, hit)) return hit;
      }
    }
    // The walk's step.
    bool pop = false;
    if (walking) {
      if (bvhRefIsLeaf(current)) {
        if (triNext == triEnd) {
          triNext = bvhLeafFirst(current);
          triEnd = triNext + bvhLeafCount(current);
          pop = true;
        }
      } else {
        BvhNode node = BVH_NODE(current);
        float nearEntry = bvhBoxEntry(node.leftMin, node.leftMax, origin, invDir, hit.t);
        float farEntry = bvhBoxEntry(node.rightMin, node.rightMax, origin, invDir, hit.t);
        uint nearRef = node.leftRef;
        uint farRef = node.rightRef;
        // Nearer first: the closest hit shrinks the search sooner, and blockers near the origin
        // are found sooner on average.
        if (farEntry < nearEntry) {
          float swapEntry = nearEntry;
          nearEntry = farEntry;
          farEntry = swapEntry;
          uint swapRef = nearRef;
          nearRef = farRef;
          farRef = swapRef;
        }
        if (nearEntry < kBvhMiss) {
          if (farEntry < kBvhMiss) {
            stack[stackSize] = farRef;
            stackEntry[stackSize] = farEntry;
            ++stackSize;
          }
          current = nearRef;
        } else {
          pop = true;
        }
      }
    }
    if (!stopAtFirstHit) {
      BVH_TRIANGLE_STEP (triNext < triEnd) bvhLeafTriangle(triNext++, origin, direction, hit);
    }
    // Resume with the most recently pushed box that still starts before the closest hit.
    if (pop) {
      walking = false;
      while (stackSize > 0u) {
        --stackSize;
        if (stopAtFirstHit || stackEntry[stackSize] <= hit.t * kBvhExitScale) {
          current = stack[stackSize];
          walking = true;
          break;
        }
      }
    }
  }
  return hit;
}

// Closest hit with 0 < t < tMax; triangle == kNoHit when nothing is hit (t is then tMax).
SHARED_FN HitRecord traceClosest(vec3 origin, vec3 direction, float tMax) {
  return bvhTraverse(origin, direction, tMax, false);
}

// True when some triangle is hit with 0 < t < tMax (shadow rays); stops at the first one found.
SHARED_FN bool traceAny(vec3 origin, vec3 direction, float tMax) {
  return bvhTraverse(origin, direction, tMax, true).triangle != kNoHit;
}

#undef BVH_TRIANGLE_STEP
#undef BVH_REJECTIONS
#undef BVH_REJECT_IF
#undef BVH_NOT_REJECTED

SHARED_END_WITH_BUFFERS
#endif
