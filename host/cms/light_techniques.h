#pragma once
// The control-variate techniques of controlled mixture sampling at the paper's granularity
// (../shared/cms.md §2, docs/estimator.md §2): one technique per emissive triangle (EmitterGpu) of
// an area light and one per punctual light, while the light clusters (cms/light_clusters.h) stay
// the unit of selection. Device-free: both backends upload `sources` as the TECHNIQUES buffer
// (shared/cms_pair_state.h), and the CPU reference reads it directly.
//
// A light sample's point, or a BSDF sample's hit, has a technique *source*: its emitter e, or
// emitterCount + light for a punctual light. sources[source] = {technique t, share Q_t}, with Q_t
// the probability, once t's cluster is chosen, of sampling inside t (the sum over t's emitters of
// the light's pmf in its cluster times the emitter's pmf in its light). t's normalised density
// is p_t(z) = p_k(z) / Q_t on its support.
//
// Budget: with more sources than maxTechniques, the emitters of each area light merge into groups
// of `groupSize` contiguous emitters (the smallest group size that fits); when even one technique
// per light does not fit, every cluster becomes one technique (the per-cluster control variate).
// Any grouping keeps the estimator unbiased (techniques stay disjoint and normalised), so merging
// costs variance only; `merged` says whether it happened.
#include <cstdint>
#include <vector>

#include "cms/light_clusters.h"
#include "scene/light_set.h"
#include "shared/cms_pair_state.h"

namespace mixtrace {

// The default --max-techniques. A coefficient per technique needs samples per (cell, technique)
// pair: with too many techniques each pair holds a handful and its alpha_t is mostly noise.
// Measured on the paper's Veach MIS (4 spheres of 480 triangles; CPU, 160x120, 64 spp, --cells
// auto = 19, relMSE against a 1024-spp reference; pt-uniform 0.0694): cv 0.0557 / 0.0513 / 0.0508
// / 0.0556 / 0.0882 and cms 0.0398 / 0.0372 / 0.0364 / 0.0372 / 0.0533 with 32 / 64 / 128 / 240 /
// 1920 techniques (per cluster: cv 0.0648, cms 0.0473); on Modern Hall (280 triangles) 95 and 280
// techniques are equal (cv 0.0253 / 0.0247, cms 0.0172 / 0.0166). Scenes of up to 128 emissive
// triangles keep one technique per triangle; --max-techniques 16384 gives 10,000 triangles one each.
constexpr uint32_t kDefaultMaxTechniques = 128;

// How the emitters were grouped.
enum class TechniqueGrouping { PerTriangle, EmitterGroups, PerCluster };

struct LightTechniques {
  std::vector<shared::TechniqueRefGpu> sources;   // emitters, then punctual lights (by light index)
  std::vector<shared::TechniqueClusterGpu> byTechnique;   // per technique: its cluster and Q_t
  uint32_t techniqueCount = 0;
  uint32_t emitterCount = 0;                      // where the punctual lights' sources start
  TechniqueGrouping grouping = TechniqueGrouping::PerTriangle;
  uint32_t groupSize = 1;                         // emitters per technique with EmitterGroups
  bool merged() const { return grouping != TechniqueGrouping::PerTriangle; }
};

// Throws mixtrace::Error when maxTechniques is below the number of clusters (it must hold one
// technique per cluster, the coarsest grouping). An empty light set gives no techniques.
LightTechniques buildLightTechniques(const LightSet& lights, const LightClusters& clusters, uint32_t maxTechniques);

// The (cell, technique) pair table's capacity, one rule for both backends: room for every pair of
// `cellSlots` cells and `techniqueCount` techniques, within 2^21 pairs (docs/estimator.md §4), or
// `requestedSlots` rounded as the table rounds (--pair-table-slots, a testing aid; 0: automatic).
uint32_t pairTableCapacity(uint32_t requestedSlots, uint32_t cellSlots, uint32_t techniqueCount);

}  // namespace mixtrace
