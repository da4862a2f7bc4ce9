#include "cms/light_techniques.h"

#include <algorithm>
#include <string>

#include "shared/cms_pair_layout.h"
#include "util/error.h"

namespace mixtrace {
namespace {

// Techniques with emitter groups of `size` emitters inside each area light, plus one per punctual light.
uint64_t techniquesWithGroups(const LightSet& lights, uint32_t size) {
  uint64_t n = 0;
  for (const shared::LightGpu& l : lights.lights)
    n += l.kind == shared::kLightArea ? (uint64_t(l.emitterCount) + size - 1) / size : 1;
  return n;
}

// The probability inside its cluster of sampling emitter e (the light's pmf in the cluster times
// the emitter's in the light, as shared/lights.h's emitterPmf gives it), or of a punctual light.
double sourceProbability(const LightSet& lights, const LightClusters& clusters, uint32_t light, uint32_t emitter,
                         bool punctual) {
  double p = clusters.lightPmfInCluster[light];
  if (punctual) return p;
  return p * double(shared::emitterPmfInLight(lights.emitters[emitter], lights.lights[light].emitterCount,
                                              clusters.uniformEmitters));
}

}  // namespace

LightTechniques buildLightTechniques(const LightSet& lights, const LightClusters& clusters, uint32_t maxTechniques) {
  LightTechniques t;
  const uint32_t lightCount = uint32_t(lights.lights.size());
  t.emitterCount = uint32_t(lights.emitters.size());
  if (lightCount == 0) return t;
  const uint32_t clusterCount = uint32_t(clusters.clusters.size());
  if (maxTechniques < clusterCount)
    throw Error("--max-techniques " + std::to_string(maxTechniques) + " is below the " +
                std::to_string(clusterCount) + " light clusters (each needs at least one technique)");

  // The grouping: per triangle when it fits, else the smallest group size that fits (the count
  // falls as the size grows, so a binary search finds it), else per cluster.
  uint32_t largestLight = 1;
  for (const shared::LightGpu& l : lights.lights)
    if (l.kind == shared::kLightArea) largestLight = std::max(largestLight, l.emitterCount);
  if (techniquesWithGroups(lights, 1) <= maxTechniques) {
    t.grouping = TechniqueGrouping::PerTriangle;
  } else if (techniquesWithGroups(lights, largestLight) <= maxTechniques) {
    uint32_t lo = 2, hi = largestLight;
    while (lo < hi) {
      uint32_t mid = lo + (hi - lo) / 2;
      if (techniquesWithGroups(lights, mid) <= maxTechniques) hi = mid; else lo = mid + 1;
    }
    t.grouping = TechniqueGrouping::EmitterGroups;
    t.groupSize = lo;
  } else {
    t.grouping = TechniqueGrouping::PerCluster;
  }

  t.sources.assign(size_t(t.emitterCount) + lightCount, shared::TechniqueRefGpu{0u, 1.0f});
  std::vector<double> share;
  auto newTechnique = [&](uint32_t cluster) {
    t.byTechnique.push_back(shared::TechniqueClusterGpu{cluster, 1.0f});
    share.push_back(0.0);
    return uint32_t(t.byTechnique.size() - 1);
  };
  std::vector<uint32_t> clusterTechnique(clusterCount, shared::kNoPairSlot);
  // Lights in cluster order, so a cluster's techniques are contiguous (deterministic numbering).
  for (uint32_t k = 0; k < clusterCount; ++k) {
    const shared::ClusterGpu& c = clusters.clusters[k];
    for (uint32_t i = c.firstLight; i < c.firstLight + c.lightCount; ++i) {
      const uint32_t light = clusters.clusterLights[i];
      const shared::LightGpu& l = lights.lights[light];
      const bool punctual = l.kind != shared::kLightArea;
      const uint32_t first = punctual ? t.emitterCount + light : l.firstEmitter;
      const uint32_t count = punctual ? 1u : l.emitterCount;
      uint32_t current = shared::kNoPairSlot;
      for (uint32_t j = 0; j < count; ++j) {
        const uint32_t source = first + j;
        if (t.grouping == TechniqueGrouping::PerCluster) {
          if (clusterTechnique[k] == shared::kNoPairSlot) clusterTechnique[k] = newTechnique(k);
          current = clusterTechnique[k];
        } else if (j % t.groupSize == 0) {
          current = newTechnique(k);
        }
        t.sources[source].technique = current;
        share[current] += sourceProbability(lights, clusters, light, punctual ? 0u : source, punctual);
      }
    }
  }
  t.techniqueCount = uint32_t(t.byTechnique.size());
  // Q_t in (0, 1]. A technique of zero probability is never sampled and its emitters emit nothing
  // (by power the emitter pmf is area x radiance), so its density p_k / Q_t is 0 anywhere it is evaluated;
  // share 1 keeps that division finite.
  for (uint32_t i = 0; i < t.techniqueCount; ++i)
    t.byTechnique[i].share = share[i] > 0.0 ? float(std::min(share[i], 1.0)) : 1.0f;
  for (shared::TechniqueRefGpu& source : t.sources) source.share = t.byTechnique[source.technique].share;
  return t;
}

uint32_t pairTableCapacity(uint32_t requestedSlots, uint32_t cellSlots, uint32_t techniqueCount) {
  if (requestedSlots) return shared::pairTableCapacityFor((requestedSlots + 1) / 2);
  const uint64_t pairs = std::min<uint64_t>(uint64_t(cellSlots) * techniqueCount, 1ull << 21);
  return shared::pairTableCapacityFor(uint32_t(pairs));
}

}  // namespace mixtrace
