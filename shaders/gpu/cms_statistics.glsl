// Adding one sample's terms to its cell's statistics (docs/estimator.md §4): with p = (.., p_k, ..,
// p_B) and the mixture density p_eff, A_ij += w p_i p_j / p_eff^2 and b_i += w f p_i / p_eff^2.
// Clusters are disjoint, so a sample touches only A_kk, A_kB, A_BB, b_k and b_B. Float atomics:
// many vertices of one cell add at once. Included by the shade and shadow stages, after
// gpu/buffers.glsl and gpu/cms_buffers.glsl.
#include "shared/cms_cells.h"
#include "shared/cms_sampling.h"
#include "shared/cms_layouts.h"

// Whether a sample of a vertex in `cell` adds to the statistics: when the host's training schedule
// says this sample pass gathers (cms/training_schedule.h: not the first with relative weighting,
// not the last iteration) and the cell holds fewer than kCellSampleCap vertices
// (shared/cms_layouts.h).
bool passGathersStatistics() { return pc.gatherStatistics != 0u; }

bool gatheringStatistics(uint cell) {
  return passGathersStatistics() && cellSamples[cell] < kCellSampleCap;
}

// The weight of a sample of `path`'s vertex with throughput `beta` in its cell (docs/estimator.md
// §5): relative to the estimate of the path's pixel made at the start of this iteration
// (shared/pixel_estimate.h), or 1 (--relative-weighting off); 0 while not gathering.
float sampleWeight(vec3 beta, uint path, uint cell) {
  if (!gatheringStatistics(cell)) return 0.0;
  return CMS_RELATIVE_WEIGHT ? relativeSampleWeight(beta, pixelEstimate[pc.pixelOffset + path]) : 1.0;
}

#ifndef CMS_FLOAT_ATOMICS
// Without float atomics (the plain shade and shadow modules: devices without
// VK_EXT_shader_atomic_float, --float-atomics off, and the methods that gather no statistics): a
// compare-and-swap loop on the bits, through a uint view of the same buffer.
layout(scalar, binding = BINDING_CELL_STATS) buffer CellStatsBits { uint cellStatsBits[]; };

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
#else   // the variants shade_float_atomics and shadow_float_atomics
void addStat(uint cell, uint index, float value) {
  if (value != 0.0) atomicAdd(cellStats[cell * cellStatsStride(pc.clusterCount) + index], value);
}
#endif

// k = kNoCell: the sample lies in no cluster's support (a BSDF sample that hit no light). The
// ratios p / p_eff (<= 1/c_k and <= 1) are formed first: p_eff^2 overflows for p_eff > 1.8e19
// (a tiny emitter seen edge-on), and Inf * 0 would put a NaN into the cell.
void addSampleToA(uint cell, uint k, float pk, float pB, float peff, float w) {
  uint L = pc.clusterCount;
  float rk = pk / peff;
  float rB = pB / peff;
  if (k != kNoCell) {
    addStat(cell, statsAkk(L, k), w * rk * rk);
    addStat(cell, statsAkB(L, k), w * rk * rB);
  }
  addStat(cell, statsABB(L), w * rB * rB);
}

// b_k += w f p_k / p_eff^2 and b_B += w f p_B / p_eff^2; f is the integrand (without throughput).
void addSampleToB(uint cell, uint k, vec3 f, float pk, float pB, float peff, float w) {
  uint L = pc.clusterCount;
  float scaleK = w * (pk / peff) / peff;
  float scaleB = w * (pB / peff) / peff;
  for (uint c = 0u; c < 3u; ++c) {
    if (k != kNoCell) addStat(cell, statsBk(L, k, c), f[c] * scaleK);
    addStat(cell, statsBB(L, c), f[c] * scaleB);
  }
}

// The control-variate and statistics terms of a light sample once its visibility is known (the
// shadow pass) or known not to matter (a hidden point, in the shade pass): the point z on cluster
// k has density c_k p_k from light sampling and pB from BSDF sampling (0 when hidden or blocked),
// integrand f (0 when blocked), at a vertex of `cell` with throughput `beta` on path `path`.
void settleLightSample(uint cell, uint k, float pk, float ck, float pB, vec3 f, vec3 beta, uint path) {
  uint L = pc.clusterCount;
  float peff = ck * pk + pB;
  if (!(peff > 0.0)) return;
  if (CMS_CONTROL_VARIATE && cellSolutionValid(cell, L))
    radiance[path] -= beta * (cellAlpha(cell, L, k) * pk + cellAlphaB(cell, L) * pB) / peff;
  float w = sampleWeight(beta, path, cell);
  if (w == 0.0) return;
  addSampleToA(cell, k, pk, pB, peff, w);
  if (!isBlack(f)) addSampleToB(cell, k, f, pk, pB, peff, w);
}
