#pragma once
// Groups a scene's lights into at most maxClusters light clusters: the sampling techniques of
// controlled mixture sampling (docs/estimator.md §2), one technique and one control-variate
// coefficient per cluster. This file only builds the grouping; sampling from it lives elsewhere.
//
// Rules
//   - every light is in exactly one cluster; a cluster holds either area lights or punctual
//     (delta) lights, never both, because the estimator measures delta techniques in counting
//     measure. Directional lights start in a group of their own (they sit at infinity) and share
//     a cluster with point/spot lights only when the budget leaves no other choice. The
//     environment is always a cluster of its own (its technique is the map's distribution);
//   - with no more lights than maxClusters, every light is its own cluster, and cluster i is
//     light i;
//   - otherwise the lights are split top-down (a kd-split, as light-tree builders do), which is
//     O(n) per split and so O(n * maxClusters) overall: ~milliseconds for 10k lights, where
//     agglomerative merging would need nearest-neighbour machinery to avoid O(n^2) per merge.
//     It starts from one group per light class (area, point/spot, directional, environment) and repeatedly
//     splits the group whose best split lowers the total cost most, until there are maxClusters
//     groups or no group has two lights. A group's cost is
//         power * diagonal(bounds)^2 * (2 - cos(normal-cone half-angle))
//     (a SAOH-like measure: big, bright, widely-oriented groups are bad techniques). Candidate
//     splits are planes between 16 bins along six keys of each light: its centroid (x, y, z) and
//     its cone axis (x, y, z), so lights at one place that face opposite ways can separate.
//     Directional lights use the scene's squared diagonal as their extent and split by direction
//     only. When no plane separates a group's lights (identical keys), it is halved by index.
//   - Per-light data: an area light's bounds are those of its emitter triangles and its cone is
//     around the emitter-pmf (area x radiance) weighted mean normal; double-sided emitters emit
//     in all directions (half-angle pi). Point lights: a point, all directions. Spot lights: a
//     point with the cone axis = spot direction, half-angle 0 (like an area light's normal cone,
//     the emission spread around the axis is not part of it). Directional: direction only.
//
// Output order: clusters are ordered by their smallest light index and list their lights in
// increasing index order, so the result is deterministic.
#include <cstdint>
#include <vector>

#include "scene/light_selection.h"
#include "scene/prepared_scene.h"
#include "shared/cluster_layout.h"
#include "shared/cms_layouts.h"

namespace mixtrace {

// What the default (not learned) selection pmf over clusters is, and the fixed pmf of a light
// inside its cluster. ProportionalToTriangles gives each cluster its triangles' share and each
// light its triangle count inside the cluster: with a uniform triangle inside the light, that is
// LightSelection::Uniform exactly (every emissive triangle equally likely, the paper's baseline).
// ProportionalToPower, with power-proportional pmfs inside the cluster, reproduces
// LightSelection::Power exactly. UniformOverClusters (power inside) is uniform over the techniques
// of a per-cluster control variate.
enum class ClusterSelection { UniformOverClusters, ProportionalToTriangles, ProportionalToPower };

struct LightClusters {
  std::vector<uint32_t> lightCluster;         // per light: its cluster
  std::vector<uint32_t> clusterLights;        // light indices grouped by cluster (contiguous)
  std::vector<shared::ClusterGpu> clusters;   // firstLight/lightCount index clusterLights
  std::vector<float> lightPmfInCluster;       // per light: its fixed probability inside its cluster,
                                              // by power (uniform in a zero-power cluster) or, for
                                              // ProportionalToTriangles, by triangle count
  bool uniformEmitters = false;               // a light's triangle is picked uniformly inside it
                                              // (ProportionalToTriangles), else by EmitterGpu.pmf
  std::vector<float> defaultSelection;        // per cluster: the default selection pmf, sums to 1
};

// Throws mixtrace::Error when maxClusters is 0 or above shared::kMaxClusters, or when it is 1 and
// the scene has both area and punctual lights (they cannot share a cluster). A scene without
// lights gives empty clusters.
LightClusters buildLightClusters(const PreparedScene& scene, uint32_t maxClusters, ClusterSelection defaults);

// The method's selection setting: LightSelection::Uniform -> ProportionalToTriangles, Power (and
// Bvh, whose clusters take the power defaults) -> ProportionalToPower.
LightClusters buildLightClusters(const PreparedScene& scene, uint32_t maxClusters, LightSelection defaults);

}  // namespace mixtrace
