// Light selection by a light BVH (method pt-bvh): from the root, each step picks one of the two
// children in proportion to an importance that bounds what its lights can send to the shading
// point: power x cos(the least angle between the cone of emission and the point) / squared
// distance x cos(the least angle of incidence at the point's normal) (Conty Estevez & Kulla,
// "Importance Sampling of Many Lights with Adaptive Tree Splitting", HPG 2018; the bounds as in
// pbrt-v4's LightBounds::Importance). Directional lights have no position and are chosen apart,
// with a fixed probability by power. The pmf of a given light walks its stored bit-trail from the
// root through the same importances, so it is exactly the pmf its selection returned: what the
// MIS weight of a BSDF sample that hits it needs.
//
// The includer defines LIGHT_BVH(i) (LightBvhNodeGpu, layout in shared/layouts.h).
#ifndef MIXTRACE_SHARED_LIGHT_BVH_H
#define MIXTRACE_SHARED_LIGHT_BVH_H
#include "shared/constants.h"
#include "shared/dialect.h"
#include "shared/layouts.h"
SHARED_BEGIN_WITH_BUFFERS

const uint kNoLightBvhNode = 0xffffffffu;
// The largest float below 1: a rescaled u stays in [0, 1).
const float kLightBvhOneMinusEpsilon = 0.99999994f;

// cos(max(0, a - b)) and sin(max(0, a - b)) from the sines and cosines of a and b.
SHARED_FN float cosSubClamped(float sinA, float cosA, float sinB, float cosB) {
  if (cosA > cosB) return 1.0f;
  return cosA * cosB + sinA * sinB;
}
SHARED_FN float sinSubClamped(float sinA, float cosA, float sinB, float cosB) {
  if (cosA > cosB) return 0.0f;
  return sinA * cosB - cosA * sinB;
}
SHARED_FN float safeSqrtOneMinusSquare(float c) { return sqrt(max(0.0f, 1.0f - c * c)); }

// The importance of node `b` for the point p with normal n (n = 0: no incidence term). 0 only
// where none of the node's lights can reach p: a conservative bound, so selection stays unbiased.
SHARED_FN float lightBvhImportance(LightBvhNodeGpu b, vec3 p, vec3 n) {
  if (!(b.power > 0.0f)) return 0.0f;
  vec3 center = 0.5f * (b.boundsMin + b.boundsMax);
  vec3 halfDiagonal = 0.5f * (b.boundsMax - b.boundsMin);
  float radius2 = dot(halfDiagonal, halfDiagonal);
  vec3 toPoint = p - center;
  float d2 = dot(toPoint, toPoint);
  // Inside the box's bounding sphere every direction is possible; the squared distance is at
  // least the sphere's (a squared length, so the importance is scale invariant).
  float cosThetaB = -1.0f;
  if (d2 > radius2) cosThetaB = sqrt(max(0.0f, 1.0f - radius2 / d2));
  d2 = max(d2, radius2);
  if (!(d2 > 0.0f)) return b.power;   // p at a point light: every child as likely as its power
  vec3 wi = b.axis;
  if (dot(toPoint, toPoint) > 0.0f) wi = normalize(toPoint);
  float cosThetaW = dot(b.axis, wi);
  float sinThetaW = safeSqrtOneMinusSquare(cosThetaW);
  float sinThetaB = safeSqrtOneMinusSquare(cosThetaB);
  float sinThetaO = safeSqrtOneMinusSquare(b.cosThetaO);
  // theta' = max(0, theta_w - theta_o - theta_b): the least angle between an emitter normal and
  // a direction from the box to p.
  float cosThetaX = cosSubClamped(sinThetaW, cosThetaW, sinThetaO, b.cosThetaO);
  float sinThetaX = sinSubClamped(sinThetaW, cosThetaW, sinThetaO, b.cosThetaO);
  float cosThetaP = cosSubClamped(sinThetaX, cosThetaX, sinThetaB, cosThetaB);
  if (cosThetaP <= b.cosThetaE) return 0.0f;
  float importance = b.power * cosThetaP / d2;
  if (dot(n, n) > 0.0f) {
    float cosThetaI = abs(dot(wi, n));
    float sinThetaI = safeSqrtOneMinusSquare(cosThetaI);
    importance *= cosSubClamped(sinThetaI, cosThetaI, sinThetaB, cosThetaB);
  }
  return max(importance, 0.0f);
}

// The probability of the first child of interior node `node` at (p, n); -1 where neither child
// can reach p.
SHARED_FN float lightBvhFirstChildProbability(LightBvhNodeGpu node, vec3 p, vec3 n) {
  float i0 = lightBvhImportance(LIGHT_BVH(node.first), p, n);
  float i1 = lightBvhImportance(LIGHT_BVH(node.second), p, n);
  if (!(i0 + i1 > 0.0f)) return -1.0f;
  return i0 / (i0 + i1);
}

// The one walk both selection and the pmf take: from the root, at each interior node the first
// child's probability at (p, n). With `select` it picks by u, returning the light (pmf its
// probability; 0, returning kNoLightBvhNode, where no light can reach p); without, it follows
// `light`'s bit-trail and pmf is the probability with which the selection picks it. One loop for
// both, so the products are the same floats and a subgroup whose invocations do different ones
// (controlled mixture sampling draws some lights by the BVH and evaluates others,
// shared/cms_sampling.h) walks the tree once.
SHARED_FN uint lightBvhWalk(vec3 p, vec3 n, bool select, float u, uint light, OUT(float) pmf) {
  LightBvhNodeGpu header = LIGHT_BVH(0u);
  pmf = 0.0f;
  float pDirectional = header.power;
  if (select ? u < pDirectional : LIGHT_BVH(1u + light).kind == kLightBvhDirectional) {
    if (select) {
      u = min(u / pDirectional, kLightBvhOneMinusEpsilon);
      uint last = header.second + header.third - 1u;
      uint i = header.second;
      while (i < last && !(u < LIGHT_BVH(i).power)) ++i;
      light = LIGHT_BVH(i).first;
    }
    pmf = LIGHT_BVH(1u + light).power;
    return light;
  }
  if (header.first == kNoLightBvhNode) return kNoLightBvhNode;
  uint trail = select ? 0u : LIGHT_BVH(1u + light).second;
  uint length = select ? 0xffffffffu : LIGHT_BVH(1u + light).third;
  if (select) u = min((u - pDirectional) / (1.0f - pDirectional), kLightBvhOneMinusEpsilon);
  float p0 = 1.0f - pDirectional;
  uint index = header.first;
  LightBvhNodeGpu node = LIGHT_BVH(index);
  for (uint depth = 0u; node.kind == kLightBvhInterior && depth < length; ++depth) {
    float first = lightBvhFirstChildProbability(node, p, n);
    if (first < 0.0f) return kNoLightBvhNode;
    bool second = select ? !(u < first) : (trail & (1u << depth)) != 0u;
    if (!second) {
      if (select) u = min(u / first, kLightBvhOneMinusEpsilon);
      p0 *= first;
      index = node.first;
    } else {
      if (select) u = min((u - first) / (1.0f - first), kLightBvhOneMinusEpsilon);
      p0 *= 1.0f - first;
      index = node.second;
    }
    node = LIGHT_BVH(index);
  }
  // A root that is a leaf was not weighed against a sibling.
  if (!(lightBvhImportance(node, p, n) > 0.0f)) return kNoLightBvhNode;
  pmf = p0;
  return node.first;
}

// Picks a light for the point p with normal n; pmf is its probability (0, returning
// kNoLightBvhNode, where no light can reach p).
SHARED_FN uint selectLightBvh(vec3 p, vec3 n, float u, OUT(float) pmf) { return lightBvhWalk(p, n, true, u, 0u, pmf); }

// The probability with which selectLightBvh(p, n, ...) picks `light`: the same products along the
// light's bit-trail.
SHARED_FN float lightBvhPmf(vec3 p, vec3 n, uint light) {
  float pmf;
  lightBvhWalk(p, n, false, 0.0f, light, pmf);
  return pmf;
}

SHARED_END_WITH_BUFFERS
#endif
