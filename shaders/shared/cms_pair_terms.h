// The per-vertex terms of the per-triangle control variate (docs/estimator.md §3, §4;
// ../shared/cms.md §2-§4), written once for both backends beside shared/cms_vertex_terms.h, whose
// per-cluster terms they replace where the cell's coefficients are per technique: the selection,
// the densities p_k, p_B, p_eff and the cell statistics stay those of cms_vertex_terms.h; a sample
// that lies on a light technique t also finds its (cell, t) pair (shared/cms_pair_table.h), reads
// alpha_t there and adds A_tt, A_tB, b_t to it (settlePairSample; when the table is full, its
// cluster's remainder technique serves instead).
//
// Only the pipelines of the per-triangle control variate include this header (the CPU reference
// always does; it costs nothing there).
//
// The includer defines, besides what cms_vertex_terms.h and cms_pair_table.h need:
//   TECHNIQUE(source)                  -> TechniqueRefGpu of a technique source (shared/cms_pair_state.h)
//   PAIR_ALPHA(i)                      -> float, alpha_t RGB at pairAlphaIndex(slot, channel)
//   CMS_ADD_PAIR_STAT(index, value)    adds to entry `index` of the pair statistics (pairStats*)
//   CMS_ADD_PAIR_SAMPLE(slot)          adds 1 to the pair's sample count
//   CMS_COUNT_PAIR(counter)            adds 1 to PAIR_COUNTERS[counter] (kPairCounter*)
#ifndef MIXTRACE_SHARED_CMS_PAIR_TERMS_H
#define MIXTRACE_SHARED_CMS_PAIR_TERMS_H
#include "shared/cms_pair_state.h"
#include "shared/cms_pair_table.h"
#include "shared/cms_sampling.h"
#include "shared/cms_technique_source.h"
#include "shared/dialect.h"
#include "shared/lights.h"
SHARED_BEGIN_WITH_BUFFERS

// alpha of the pair in `slot` (0 for kNoPairSlot; not named pairAlpha: GLSL declares the PAIR_ALPHA
// row by that name). Written only by the solve between iterations, so it never depends on the
// samples it is applied to.
SHARED_FN vec3 pairCoefficient(uint slot) {
  if (slot == kNoPairSlot) return vec3(0.0f);
  return vec3(PAIR_ALPHA(pairAlphaIndex(slot, 0u)), PAIR_ALPHA(pairAlphaIndex(slot, 1u)),
              PAIR_ALPHA(pairAlphaIndex(slot, 2u)));
}

// Whether the last solve put the triangle pair in `slot` into its valid cell's system.
SHARED_FN bool pairSolved(uint slot) { return slot != kNoPairSlot && PAIR_ALPHA(pairSolvedIndex(slot)) > 0.5f; }

// What a sample subtracts at a vertex of a cell with a valid solution: T g(z) / p_eff(z) with
// g(z) = alpha p(z) + alpha_B p_B(z), alpha and p those of the light technique the sample lies on
// (slot = kNoPairSlot, p = 0: alpha_B p_B alone). The integral T (sum alpha + alpha_B) is
// cms_vertex_terms.h's controlVariateIntegral: the solve stores it as the cell's solutionAlphaSum.
SHARED_FN vec3 pairControlVariateTerm(vec3 T, uint cell, uint L, uint slot, float p, float pB, float peff) {
  vec3 g = cellAlphaB(cell, L) * pB + pairCoefficient(slot) * p;
  return T * g / peff;
}

// Adds a light-technique sample's terms to the pair in `slot` (not kNoPairSlot), whose technique
// has density p there: A_tt += w (p/p_eff)^2, A_tB += w (p/p_eff) (p_B/p_eff), b_t += w f (p/p_eff)
// / p_eff and one sample (ratios first, as addSampleStatistics forms them). The cell's own A_BB and
// b_B come from addSampleStatistics.
SHARED_FN void addPairStatistics(uint slot, CMS_STAT_REAL p, CMS_STAT_REAL pB, CMS_STAT_REAL peff, vec3 f,
                                 CMS_STAT_REAL w) {
  CMS_STAT_REAL rt = p / peff;
  CMS_STAT_REAL rB = pB / peff;
  CMS_ADD_PAIR_STAT(pairStatsAtt(slot), w * rt * rt);
  CMS_ADD_PAIR_STAT(pairStatsAtB(slot), w * rt * rB);
  if (!isBlack(f)) {
    CMS_STAT_REAL scale = w * rt / peff;
    for (uint c = 0u; c < 3u; ++c) CMS_ADD_PAIR_STAT(pairStatsBt(slot, c), CMS_STAT_REAL(f[c]) * scale);
  }
  CMS_ADD_PAIR_SAMPLE(slot);
}

// The light-technique side of one sample whose point z lies on the technique of `source`, in
// cluster k, at a vertex of `cell` (docs/estimator.md §4): returns what the sample subtracts when
// the cell's control variate is in use (`cv`; else 0), and adds its statistics when it gathers
// (w > 0). p_k, p_B, p_eff, f and the throughput T as at the call sites (host/cpu/cpu_cms_path.cpp,
// shaders/gpu/cms_statistics.glsl).
//   - The control variate: alpha_t p_t(z) when the sample's own pair was solved, else the cluster's
//     remainder technique, alpha_R p_k(z) (0 when the cell has none). The solve gives alpha_R the
//     integral P_R = 1 - sum of Q_t over the solved pairs of k, exactly the mass of p_k where it
//     applies, so any alpha keeps the estimator unbiased.
//   - The statistics: to the sample's own pair (claimed when new); when the full table refuses
//     it, to the remainder pair with density p_k; when that is refused too, to nothing but the
//     cell's A_BB and b_B. Each outcome is counted (kPairCounter*).
SHARED_FN vec3 settlePairSample(uint capacity, uint cell, uint L, uint k, uint source, float pk, float pB,
                                float peff, vec3 f, CMS_STAT_REAL w, vec3 T, bool cv) {
  TechniqueRefGpu ref = TECHNIQUE(source);
  float pt = pk / ref.share;   // p_t = p_k / Q_t: the normalised density of the sample's technique
  bool gathers = w > CMS_STAT_REAL(0);
  uint own = probePair(capacity, cell, ref.technique, gathers);
  bool ownSolved = pairSolved(own);
  // The remainder pair serves the control variate where the own pair was not solved (below the
  // triangle pairs' limit none exists: the lookup is skipped, not its term) and the statistics
  // where the table refused the own pair. One lookup for both, inserting for the second: a
  // remainder claimed here has alpha_R = 0, the same term as none. (SIMD code runs every lookup
  // site for every invocation, so the sites are as few as the logic allows.)
  bool remainderForStatistics = gathers && own == kNoPairSlot;
  bool remainderForTerm = cv && !ownSolved && remaindersMayExist(capacity);
  uint remainder = kNoPairSlot;
  if (remainderForTerm || remainderForStatistics)
    remainder = probePair(capacity, cell, remainderTechnique(k), remainderForStatistics);
  vec3 term = vec3(0.0f);
  if (cv) term = pairControlVariateTerm(T, cell, L, ownSolved ? own : remainder, ownSolved ? pt : pk, pB, peff);
  if (!gathers) return term;
  // The statistics go to the own pair with p_t, else to the remainder with p_k, else nowhere but
  // the cell's A_BB and b_B; each outcome is counted.
  uint slot = own != kNoPairSlot ? own : remainder;
  if (slot != kNoPairSlot)
    addPairStatistics(slot, CMS_STAT_REAL(own != kNoPairSlot ? pt : pk), CMS_STAT_REAL(pB), CMS_STAT_REAL(peff), f, w);
  CMS_COUNT_PAIR(own != kNoPairSlot ? kPairCounterPairSamples
                                    : (remainder != kNoPairSlot ? kPairCounterRemainderSamples : kPairCounterRefusedSamples));
  return term;
}

SHARED_END_WITH_BUFFERS
#endif
