#include "cms/light_clusters.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>
#include <utility>

#include "util/error.h"

namespace mixtrace {
namespace {

constexpr float kPi = 3.14159265358979323846f;
constexpr int kBins = 16;
constexpr int kKeys = 6;  // centroid x, y, z; cone axis x, y, z

// Lights of different classes never start in one group (light_clusters.h).
enum class LightClass { Area, Local, Directional, Environment };

// A cone of directions: axis and half-angle in [0, pi]; theta < 0 is the empty cone.
struct Cone {
  glm::vec3 axis{0.0f, 0.0f, 1.0f};
  float theta = -1.0f;
  bool empty() const { return theta < 0.0f; }
};

float angleBetween(const glm::vec3& a, const glm::vec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// The smallest cone around both (conservative): widen the wider cone towards the other one.
Cone coneUnion(Cone a, Cone b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  if (b.theta > a.theta) std::swap(a, b);
  if (a.theta >= kPi) return a;
  float d = angleBetween(a.axis, b.axis);
  if (d + b.theta <= a.theta) return a;
  float theta = 0.5f * (a.theta + d + b.theta);
  if (theta >= kPi) return Cone{a.axis, kPi};
  glm::vec3 w = glm::cross(a.axis, b.axis);
  float wl = glm::length(w);
  // Nearly parallel axes: no rotation plane, keep a's axis and cover b around it.
  if (!(wl > 1e-6f)) return d < 0.5f * kPi ? Cone{a.axis, std::min(kPi, d + b.theta)} : Cone{a.axis, kPi};
  w /= wl;
  // Rotate a's axis towards b's by the growth of the half-angle (w is orthogonal to a.axis).
  float r = theta - a.theta;
  glm::vec3 axis = a.axis * std::cos(r) + glm::cross(w, a.axis) * std::sin(r);
  return Cone{glm::normalize(axis), theta};
}

// What clustering needs to know about one light.
struct LightSummary {
  LightClass cls = LightClass::Area;
  Bounds bounds;        // empty for directional lights
  Cone cone;
  float key[kKeys]{};   // split keys: centroid, then cone axis (0 where the cone is all directions)
  double weight = 0.0;  // power used by the cost
};

// Sums of a set of lights, for the cost.
struct Aggregate {
  Bounds bounds;
  Cone cone;
  double weight = 0.0;
  uint32_t count = 0;
  void add(const LightSummary& s) {
    if (s.bounds.valid()) bounds.grow(s.bounds);
    cone = coneUnion(cone, s.cone);
    weight += s.weight;
    ++count;
  }
  void add(const Aggregate& a) {
    if (a.bounds.valid()) bounds.grow(a.bounds);
    cone = coneUnion(cone, a.cone);
    weight += a.weight;
    count += a.count;
  }
};

// The SAOH-like cost of light_clusters.h. Directional lights have no bounds: they illuminate the
// whole scene, so they use its squared diagonal (directionalDiag2).
double groupCost(const Aggregate& a, LightClass cls, double directionalDiag2) {
  if (a.count == 0) return 0.0;
  double diag2 = directionalDiag2;
  if (cls != LightClass::Directional) {
    glm::vec3 e = a.bounds.valid() ? a.bounds.extent() : glm::vec3(0.0f);
    diag2 = double(glm::dot(e, e));
  }
  double theta = a.cone.empty() ? 0.0 : double(std::min(a.cone.theta, kPi));
  return a.weight * diag2 * (2.0 - std::cos(theta));
}

LightSummary summariseAreaLight(const PreparedScene& scene, const shared::LightGpu& light) {
  LightSummary s;
  s.cls = LightClass::Area;
  glm::dvec3 normalSum(0.0);
  double pmfSum = 0.0;
  bool doubleSided = false;
  for (uint32_t e = light.firstEmitter; e < light.firstEmitter + light.emitterCount; ++e) {
    const shared::EmitterGpu& em = scene.lights.emitters[e];
    const shared::TriangleGeom& g = scene.bvh.triangles[em.triangle];
    s.bounds.grow(g.v0);
    s.bounds.grow(g.v0 + g.e1);
    s.bounds.grow(g.v0 + g.e2);
    glm::vec3 n = glm::cross(g.e1, g.e2);
    float len = glm::length(n);
    if (len > 0.0f) normalSum += glm::dvec3(n / len) * double(em.pmf);
    pmfSum += em.pmf;
    uint32_t material = scene.shading[em.triangle].material;
    if (scene.scene.materials[material].flags & shared::kMaterialDoubleSided) doubleSided = true;
  }
  double sumLength = glm::length(normalSum);
  if (doubleSided || !(sumLength > 1e-6 * pmfSum)) {
    s.cone = Cone{glm::vec3(0.0f, 0.0f, 1.0f), kPi};
  } else {
    glm::vec3 axis = glm::vec3(normalSum / sumLength);
    float theta = 0.0f;
    for (uint32_t e = light.firstEmitter; e < light.firstEmitter + light.emitterCount; ++e) {
      const shared::TriangleGeom& g = scene.bvh.triangles[scene.lights.emitters[e].triangle];
      glm::vec3 n = glm::cross(g.e1, g.e2);
      if (glm::length(n) > 0.0f) theta = std::max(theta, angleBetween(axis, glm::normalize(n)));
    }
    s.cone = Cone{axis, theta};
  }
  glm::vec3 c = s.bounds.center();
  s.key[0] = c.x; s.key[1] = c.y; s.key[2] = c.z;
  return s;
}

LightSummary summarisePunctualLight(const shared::LightGpu& light) {
  LightSummary s;
  if (light.kind == shared::kLightEnvironment) {
    s.cls = LightClass::Environment;
    s.cone = Cone{glm::vec3(0.0f, 0.0f, 1.0f), kPi};
  } else if (light.kind == shared::kLightDirectional) {
    s.cls = LightClass::Directional;
    s.cone = Cone{glm::normalize(light.direction), 0.0f};
  } else {
    s.cls = LightClass::Local;
    s.bounds.grow(light.position);
    s.cone = light.kind == shared::kLightSpot ? Cone{glm::normalize(light.direction), 0.0f}
                                               : Cone{glm::vec3(0.0f, 0.0f, 1.0f), kPi};
    s.key[0] = light.position.x; s.key[1] = light.position.y; s.key[2] = light.position.z;
  }
  return s;
}

std::vector<LightSummary> summariseLights(const PreparedScene& scene) {
  const LightSet& set = scene.lights;
  std::vector<LightSummary> out;
  out.reserve(set.lights.size());
  double totalPower = 0.0;
  for (double p : set.power) if (std::isfinite(p) && p > 0.0) totalPower += p;
  for (size_t i = 0; i < set.lights.size(); ++i) {
    const shared::LightGpu& l = set.lights[i];
    LightSummary s = l.kind == shared::kLightArea ? summariseAreaLight(scene, l) : summarisePunctualLight(l);
    if (!s.cone.empty() && s.cone.theta < kPi) {
      s.key[3] = s.cone.axis.x; s.key[4] = s.cone.axis.y; s.key[5] = s.cone.axis.z;
    }
    double p = i < set.power.size() ? set.power[i] : 0.0;
    // Without any power every light weighs the same, so the geometry alone decides.
    s.weight = totalPower > 0.0 ? ((std::isfinite(p) && p > 0.0) ? p : 0.0) : 1.0;
    out.push_back(s);
  }
  return out;
}

// A group of lights during the top-down split, with its best split precomputed.
struct Group {
  LightClass cls = LightClass::Area;
  std::vector<uint32_t> lights;
  double gain = 0.0;          // cost lowered by the best split
  int splitKey = -1;          // -1: halve by index (no plane separates the lights)
  float splitLo = 0.0f;
  float splitScale = 0.0f;
  int splitPlane = 0;         // lights in bins < splitPlane go left
};

int binOf(float key, float lo, float scale) {
  int b = int((key - lo) * scale);
  return std::clamp(b, 0, kBins - 1);
}

// Finds the binned plane (over all six keys) with the lowest summed cost of the two sides.
void findBestSplit(Group& g, const std::vector<LightSummary>& lights, double directionalDiag2) {
  g.gain = 0.0;
  g.splitKey = -1;
  if (g.lights.size() < 2) return;
  Aggregate all;
  for (uint32_t i : g.lights) all.add(lights[i]);
  double parentCost = groupCost(all, g.cls, directionalDiag2);
  double bestCost = std::numeric_limits<double>::infinity();
  // Directional lights have no position: only their direction can separate them.
  int firstKey = g.cls == LightClass::Directional ? 3 : 0;
  for (int k = firstKey; k < kKeys; ++k) {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (uint32_t i : g.lights) { lo = std::min(lo, lights[i].key[k]); hi = std::max(hi, lights[i].key[k]); }
    if (!(hi > lo)) continue;
    float scale = float(kBins) / (hi - lo);
    if (!std::isfinite(scale)) continue;
    Aggregate bins[kBins];
    for (uint32_t i : g.lights) bins[binOf(lights[i].key[k], lo, scale)].add(lights[i]);
    Aggregate right[kBins];  // right[b]: bins b .. kBins-1
    right[kBins - 1] = bins[kBins - 1];
    for (int b = kBins - 2; b >= 0; --b) { right[b] = bins[b]; right[b].add(right[b + 1]); }
    Aggregate left;
    for (int plane = 1; plane < kBins; ++plane) {
      left.add(bins[plane - 1]);
      if (left.count == 0 || right[plane].count == 0) continue;
      double cost = groupCost(left, g.cls, directionalDiag2) + groupCost(right[plane], g.cls, directionalDiag2);
      if (cost < bestCost) {
        bestCost = cost;
        g.splitKey = k;
        g.splitLo = lo;
        g.splitScale = scale;
        g.splitPlane = plane;
      }
    }
  }
  if (g.splitKey < 0) {
    Aggregate a, b;
    size_t half = g.lights.size() / 2;
    for (size_t j = 0; j < g.lights.size(); ++j) (j < half ? a : b).add(lights[g.lights[j]]);
    bestCost = groupCost(a, g.cls, directionalDiag2) + groupCost(b, g.cls, directionalDiag2);
  }
  g.gain = std::max(0.0, parentCost - bestCost);
}

std::pair<Group, Group> splitGroup(const Group& g, const std::vector<LightSummary>& lights) {
  Group a, b;
  a.cls = b.cls = g.cls;
  if (g.splitKey < 0) {
    size_t half = g.lights.size() / 2;
    a.lights.assign(g.lights.begin(), g.lights.begin() + std::ptrdiff_t(half));
    b.lights.assign(g.lights.begin() + std::ptrdiff_t(half), g.lights.end());
  } else {
    for (uint32_t i : g.lights)
      (binOf(lights[i].key[g.splitKey], g.splitLo, g.splitScale) < g.splitPlane ? a : b).lights.push_back(i);
  }
  return {std::move(a), std::move(b)};
}

// The starting groups: one per non-empty light class, punctual classes merged when the budget is
// too small for all of them. Throws when even that does not fit.
std::vector<Group> initialGroups(const std::vector<LightSummary>& lights, uint32_t maxClusters) {
  Group area, local, directional, environment;
  area.cls = LightClass::Area;
  local.cls = LightClass::Local;
  directional.cls = LightClass::Directional;
  environment.cls = LightClass::Environment;
  for (uint32_t i = 0; i < lights.size(); ++i) {
    const LightClass c = lights[i].cls;
    Group& g = c == LightClass::Area ? area : c == LightClass::Local ? local : c == LightClass::Directional ? directional
                                                                                                            : environment;
    g.lights.push_back(i);
  }
  std::vector<Group> groups;
  for (Group* g : {&area, &local, &directional})
    if (!g->lights.empty()) groups.push_back(std::move(*g));
  if (groups.size() + (environment.lights.empty() ? 0 : 1) > maxClusters && groups.size() >= 2 &&
      groups.back().cls == LightClass::Directional && groups[groups.size() - 2].cls == LightClass::Local) {
    // Budget too small: directional lights join the point/spot lights (both delta techniques).
    Group& merged = groups[groups.size() - 2];
    merged.lights.insert(merged.lights.end(), groups.back().lights.begin(), groups.back().lights.end());
    std::sort(merged.lights.begin(), merged.lights.end());
    groups.pop_back();
  }
  // The environment is always a cluster of its own (as in the reference implementation).
  if (!environment.lights.empty()) groups.push_back(std::move(environment));
  if (groups.size() > maxClusters)
    throw Error("maxClusters = " + std::to_string(maxClusters) +
                " cannot keep the scene's area lights, punctual lights and environment in separate clusters: use at "
                "least " + std::to_string(groups.size()));
  return groups;
}

std::vector<std::vector<uint32_t>> partitionLights(const std::vector<LightSummary>& lights, uint32_t maxClusters,
                                                   double directionalDiag2) {
  std::vector<std::vector<uint32_t>> result;
  if (lights.size() <= maxClusters) {
    for (uint32_t i = 0; i < lights.size(); ++i) result.push_back({i});
    return result;
  }
  std::vector<Group> groups = initialGroups(lights, maxClusters);
  for (Group& g : groups) findBestSplit(g, lights, directionalDiag2);
  while (groups.size() < maxClusters) {
    // Split where the cost drops most; among equal gains (e.g. all zero) the largest group.
    int best = -1;
    for (size_t i = 0; i < groups.size(); ++i) {
      if (groups[i].lights.size() < 2) continue;
      if (best < 0 || groups[i].gain > groups[size_t(best)].gain ||
          (groups[i].gain == groups[size_t(best)].gain && groups[i].lights.size() > groups[size_t(best)].lights.size()))
        best = int(i);
    }
    if (best < 0) break;
    auto [a, b] = splitGroup(groups[size_t(best)], lights);
    findBestSplit(a, lights, directionalDiag2);
    findBestSplit(b, lights, directionalDiag2);
    groups[size_t(best)] = std::move(a);
    groups.push_back(std::move(b));
  }
  for (Group& g : groups) {
    std::sort(g.lights.begin(), g.lights.end());
    result.push_back(std::move(g.lights));
  }
  std::sort(result.begin(), result.end(), [](const auto& x, const auto& y) { return x.front() < y.front(); });
  return result;
}

// Normalises non-negative weights to a pmf; uniform when they sum to zero.
std::vector<float> normalise(const std::vector<double>& weights) {
  double total = 0.0;
  for (double w : weights) total += w;
  std::vector<float> pmf(weights.size());
  for (size_t i = 0; i < weights.size(); ++i)
    pmf[i] = float(total > 0.0 ? weights[i] / total : 1.0 / double(weights.size()));
  return pmf;
}

}  // namespace

LightClusters buildLightClusters(const PreparedScene& scene, uint32_t maxClusters, ClusterSelection defaults) {
  if (maxClusters < 1 || maxClusters > shared::kMaxClusters)
    throw Error("maxClusters must be between 1 and " + std::to_string(shared::kMaxClusters) + ", got " +
                std::to_string(maxClusters));
  const LightSet& set = scene.lights;
  std::vector<LightSummary> summaries = summariseLights(scene);
  glm::vec3 sceneExtent = scene.scene.bounds.valid() ? scene.scene.bounds.extent() : glm::vec3(1.0f);
  double directionalDiag2 = std::max(double(glm::dot(sceneExtent, sceneExtent)), 1e-12);
  std::vector<std::vector<uint32_t>> partition = partitionLights(summaries, maxClusters, directionalDiag2);

  LightClusters out;
  out.uniformEmitters = defaults == ClusterSelection::ProportionalToTriangles;
  out.lightCluster.assign(set.lights.size(), 0u);
  out.lightPmfInCluster.assign(set.lights.size(), 0.0f);
  std::vector<double> clusterPower, clusterTriangles, clusterLightCount;
  const bool byTriangles = out.uniformEmitters;
  for (uint32_t c = 0; c < partition.size(); ++c) {
    const std::vector<uint32_t>& members = partition[c];
    shared::ClusterGpu cluster{};
    cluster.firstLight = uint32_t(out.clusterLights.size());
    cluster.lightCount = uint32_t(members.size());
    const uint32_t kind = set.lights[members.front()].kind;
    cluster.kind = kind == shared::kLightArea || kind == shared::kLightEnvironment ? shared::kClusterArea
                                                                                    : shared::kClusterDelta;
    std::vector<double> power, triangles;
    for (uint32_t i : members) {
      double p = i < set.power.size() ? set.power[i] : 0.0;
      power.push_back(std::isfinite(p) && p > 0.0 ? p : 0.0);
      triangles.push_back(uniformSelectionWeight(set.lights[i]));
      out.lightCluster[i] = c;
      out.clusterLights.push_back(i);
    }
    std::vector<float> pmf = normalise(byTriangles ? triangles : power);
    for (size_t j = 0; j < members.size(); ++j) out.lightPmfInCluster[members[j]] = pmf[j];
    double total = std::accumulate(power.begin(), power.end(), 0.0);
    cluster.power = float(total);
    out.clusters.push_back(cluster);
    clusterPower.push_back(total);
    clusterTriangles.push_back(std::accumulate(triangles.begin(), triangles.end(), 0.0));
    clusterLightCount.push_back(double(members.size()));
  }

  switch (defaults) {
    case ClusterSelection::UniformOverClusters: out.defaultSelection = normalise(std::vector<double>(partition.size(), 1.0)); break;
    case ClusterSelection::ProportionalToTriangles: out.defaultSelection = normalise(clusterTriangles); break;
    case ClusterSelection::ProportionalToPower: {
      double total = std::accumulate(clusterPower.begin(), clusterPower.end(), 0.0);
      out.defaultSelection = normalise(total > 0.0 ? clusterPower : clusterLightCount);
      break;
    }
  }
  return out;
}

LightClusters buildLightClusters(const PreparedScene& scene, uint32_t maxClusters, LightSelection defaults) {
  return buildLightClusters(scene, maxClusters,
                            defaults == LightSelection::Uniform ? ClusterSelection::ProportionalToTriangles
                                                                : ClusterSelection::ProportionalToPower);
}

}  // namespace mixtrace
