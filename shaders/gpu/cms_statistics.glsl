// The GPU's side of the statistics of controlled mixture sampling (docs/estimator.md §4, §5): when
// a sample gathers, its weight, and the add of one term to a cell (float atomics, or compare-and-
// swap loops), which binds the accessor CMS_ADD_STAT of shared/cms_vertex_terms.h; the terms
// themselves are that header's. Many vertices of one cell add at once, hence the atomics.
// Included by the shade and shadow stages, after gpu/buffers.glsl and gpu/cms_buffers.glsl.
#include "shared/cms_cells.h"
#include "shared/cms_sampling.h"
#include "shared/cms_layouts.h"
#include "shared/cms_pair_state.h"

// Whether a sample of a vertex in `cell` adds to the statistics: when the host's training schedule
// says this sample pass gathers (cms/training_schedule.h: not the first with relative weighting,
// not the last iteration) and the cell holds fewer than kCellSampleCap vertices
// (shared/cms_layouts.h).
bool passGathersStatistics() { return pc.gatherStatistics != 0u; }

// The per-triangle control variate gathers far longer (kPairCellSampleCap, shared/cms_pair_state.h).
bool gatheringStatistics(uint cell) {
  return passGathersStatistics() && cellSamples[cell] < (CMS_PAIR_TECHNIQUES ? kPairCellSampleCap : kCellSampleCap);
}

// The weight of a sample of `path`'s vertex with throughput `beta` in its cell (docs/estimator.md
// §5): relative to the estimate of the path's pixel made at the start of this iteration
// (shared/pixel_estimate.h), or 1 (--relative-weighting off); 0 while not gathering and for no
// cell (kNoCell).
float sampleWeight(vec3 beta, uint path, uint cell) {
  if (cell == kNoCell || !gatheringStatistics(cell)) return 0.0;
  return CMS_RELATIVE_WEIGHT ? relativeSampleWeight(beta, pixelEstimate[pc.pixelOffset + path]) : 1.0;
}

// The cell grid the renderer pushes (VertexConstants, FusedConstants).
CellGrid pushedCellGrid() {
  CellGrid g;
  g.origin = pc.gridOrigin;
  g.invCellSize = pc.gridInvCellSize;
  g.tableSize = pc.cellTableSize;
  g.pad0 = 0u;
  g.pad1 = 0u;
  g.pad2 = 0u;
  return g;
}

// Counts a vertex in its cell while that gathers (docs/estimator.md §5: the cap above), or one
// whose probe sequence in the cell table was full (kNoCell), which adds no statistics.
void countCellVertex(uint cell) {
  if (cell == kNoCell) atomicAdd(queues.verticesWithoutCell, 1u);
  else if (gatheringStatistics(cell)) atomicAdd(cellSamples[cell], 1u);
}

#ifndef CMS_FLOAT_ATOMICS
// Without float atomics (the plain shade and shadow modules: devices without
// VK_EXT_shader_atomic_float, --float-atomics off, and the methods that gather no statistics): a
// compare-and-swap loop on the bits, through a uint view of the same buffer.
layout(scalar, binding = BINDING_CELL_STATS) buffer CellStatsBits { uint cellStatsBits[]; };

#ifdef PASS_PAIR_BUFFERS
layout(scalar, binding = BINDING_PAIR_STATS) buffer PairStatsBits { uint pairStatsBits[]; };
#endif

void addStat(uint cell, uint index, float value) {
  if (value == 0.0) return;
  uint i = cell * cellStatsStride(pc.clusterCount) + index;
  uint seen = cellStatsBits[i];
  for (;;) {
    uint expected = seen;
    seen = atomicCompSwap(cellStatsBits[i], expected, floatBitsToUint(uintBitsToFloat(expected) + value));
    if (seen == expected) break;
  }
}

#ifdef PASS_PAIR_BUFFERS
void addPairStat(uint index, float value) {
  if (value == 0.0) return;
  uint seen = pairStatsBits[index];
  for (;;) {
    uint expected = seen;
    seen = atomicCompSwap(pairStatsBits[index], expected, floatBitsToUint(uintBitsToFloat(expected) + value));
    if (seen == expected) break;
  }
}
#endif
#else   // the variants shade_float_atomics and shadow_float_atomics
void addStat(uint cell, uint index, float value) {
  if (value != 0.0) atomicAdd(cellStats[cell * cellStatsStride(pc.clusterCount) + index], value);
}

#ifdef PASS_PAIR_BUFFERS
void addPairStat(uint index, float value) {
  if (value != 0.0) atomicAdd(pairStats[index], value);
}
#endif
#endif

#define CMS_STAT_REAL float
#define CMS_ADD_STAT(cell, index, value) addStat(cell, index, value)
#include "shared/cms_vertex_terms.h"
// The per-triangle control variate's pair terms, in the pass that binds the pair rows (the shadow
// pass defines PASS_PAIR_BUFFERS); folded away unless CMS_PAIR_TECHNIQUES.
#ifdef PASS_PAIR_BUFFERS
#define CMS_ADD_PAIR_STAT(index, value) addPairStat(index, value)
#define CMS_ADD_PAIR_SAMPLE(slot) atomicAdd(pairSamples[slot], 1u)
#define CMS_COUNT_PAIR(counter) atomicAdd(pairCounters[counter], 1u)
#include "shared/cms_pair_terms.h"

// Two records of one path (its light sample and its previous BSDF sample) may be settled in one
// shadow dispatch: with the per-triangle control variate the shadow pass adds to the radiance
// through compare-and-swap on a uint view of it.
layout(scalar, binding = BINDING_RADIANCE) buffer RadianceBits { uint radianceBits[]; };

void addRadiance(uint path, vec3 value) {
  if (!CMS_PAIR_TECHNIQUES) {
    radiance[path] += value;
    return;
  }
  for (uint c = 0u; c < 3u; ++c) {
    if (value[c] == 0.0) continue;
    uint i = 3u * path + c;
    uint seen = radianceBits[i];
    for (;;) {
      uint expected = seen;
      seen = atomicCompSwap(radianceBits[i], expected, floatBitsToUint(uintBitsToFloat(expected) + value[c]));
      if (seen == expected) break;
    }
  }
}

// A BSDF sample's pair terms once shade found its hit on a light technique (kShadowRayBsdfPair;
// host/cpu/cpu_cms_path.cpp settlePendingBsdfSample): its pair, the control-variate term with the
// pair's alpha_t, its statistics. The cell's own terms were added by shade.
void settleBsdfPair(uint cell, uint j, uint source, float pj, float pB, float peff, vec3 f, vec3 beta, uint path,
                    float w) {
  uint L = pc.clusterCount;
  bool cv = CMS_CONTROL_VARIATE && cellSolutionValid(cell, L);
  vec3 term = settlePairSample(pc.pairCapacity, cell, L, j, source, pj, pB, peff, f, w, beta, cv);
  if (cv) addRadiance(path, -term);
}
#endif

// The control-variate and statistics terms of a light sample once its visibility is known (the
// shadow pass) or known not to matter (a hidden point, in the shade pass): the point z on cluster
// k has density c_k p_k from light sampling (carried as ck and pk on the shadow ray) and pB from
// BSDF sampling (0 when hidden or blocked), integrand f (0 when blocked), at a vertex of `cell`
// with throughput `beta` on path `path`. With the per-triangle control variate the point's
// technique source `source` (techniqueSourceOfLightSample) finds its pair, hidden or blocked alike
// (host/cpu/cpu_cms_path.cpp sampleLight).
void settleLightSample(uint cell, uint k, float pk, float ck, float pB, vec3 f, vec3 beta, uint path, uint source) {
  uint L = pc.clusterCount;
  float peff = lightSampleMixtureDensity(ck * pk, pB);
  if (!(peff > 0.0)) return;
  float w = sampleWeight(beta, path, cell);
#ifdef PASS_PAIR_BUFFERS
  if (CMS_PAIR_TECHNIQUES) {
    bool cv = CMS_CONTROL_VARIATE && cellSolutionValid(cell, L);
    vec3 term = settlePairSample(pc.pairCapacity, cell, L, k, source, pk, pB, peff, f, w, beta, cv);
    if (cv) addRadiance(path, -term);
  } else
#endif
  if (CMS_CONTROL_VARIATE && cellSolutionValid(cell, L)) {
    radiance[path] -= controlVariateTerm(beta, cell, L, k, pk, pB, peff);
  }
  addSampleStatistics(cell, L, k, pk, pB, peff, f, w);
}
