// Adding one sample's terms to its cell's statistics (cms.md §4): with p = (.., p_k, .., p_B)
// and the mixture density p_eff, A_ij += w p_i p_j / p_eff^2 and b_i += w f p_i / p_eff^2.
// Clusters are disjoint, so a sample touches only A_kk, A_kB, A_BB, b_k and b_B. Float atomics:
// many vertices of one cell add at once. Included by the shade and shadow stages, after
// gpu/buffers.glsl and gpu/cms_buffers.glsl.
#include "shared/cms_cells.h"
#include "shared/cms_layouts.h"

void addStat(uint cell, uint index, float value) {
  if (value != 0.0) atomicAdd(cellStats[cell * cellStatsStride(pc.clusterCount) + index], value);
}

// k = kNoCell: the sample lies in no cluster's support (a BSDF sample that hit no light).
void addSampleToA(uint cell, uint k, float pk, float pB, float peff, float w) {
  uint L = pc.clusterCount;
  float inv = w / (peff * peff);
  if (k != kNoCell) {
    addStat(cell, statsAkk(L, k), pk * pk * inv);
    addStat(cell, statsAkB(L, k), pk * pB * inv);
  }
  addStat(cell, statsABB(L), pB * pB * inv);
}

// scaleK = w p_k / p_eff^2, scaleB = w p_B / p_eff^2; f is the integrand (without throughput).
void addSampleToB(uint cell, uint k, vec3 f, float scaleK, float scaleB) {
  uint L = pc.clusterCount;
  for (uint c = 0u; c < 3u; ++c) {
    if (k != kNoCell) addStat(cell, statsBk(L, k, c), f[c] * scaleK);
    addStat(cell, statsBB(L, c), f[c] * scaleB);
  }
}
