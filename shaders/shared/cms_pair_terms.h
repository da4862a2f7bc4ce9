// The per-vertex terms of the per-triangle control variate (docs/estimator.md §3, §4;
// ../shared/cms.md §2-§4), written once for both backends beside shared/cms_vertex_terms.h, whose
// per-cluster terms they replace where the cell's coefficients are per technique: the selection,
// the densities p_k, p_B, p_eff and the cell statistics stay those of cms_vertex_terms.h; a sample
// that lies on a light technique t also finds its (cell, t) pair (shared/cms_pair_table.h), reads
// alpha_t there and adds A_tt, A_tB, b_t to it.
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

// p_t(z) = p_k(z) / Q_t: the normalised density of the technique holding `source`, from the
// density p_k of its cluster's light sampling.
SHARED_FN float techniqueDensity(uint source, float pk) { return pk / TECHNIQUE(source).share; }

// The pair slot of a sample of `source` at a vertex of `cell`: claimed when the sample gathers
// statistics, only looked up when it does not (a pair absent from the table has alpha_t = 0, like
// one the table refused). kNoPairSlot: absent or refused.
SHARED_FN uint pairSlotOfSample(uint capacity, uint cell, uint source, bool gathers) {
  uint technique = TECHNIQUE(source).technique;
  return gathers ? findOrInsertPair(capacity, cell, technique) : findPair(capacity, cell, technique);
}

// alpha_t of the pair in `slot` (0 for kNoPairSlot; not named pairAlpha: GLSL declares the PAIR_ALPHA
// row by that name). Written only by the solve between
// iterations, so it never depends on the samples it is applied to.
SHARED_FN vec3 pairCoefficient(uint slot) {
  if (slot == kNoPairSlot) return vec3(0.0f);
  return vec3(PAIR_ALPHA(pairAlphaIndex(slot, 0u)), PAIR_ALPHA(pairAlphaIndex(slot, 1u)),
              PAIR_ALPHA(pairAlphaIndex(slot, 2u)));
}

// What a sample subtracts at a vertex of a cell with a valid solution: T g(z) / p_eff(z) with
// g(z) = alpha_t p_t(z) + alpha_B p_B(z) (slot = kNoPairSlot, pt = 0: alpha_B p_B alone). The
// integral T (sum_t alpha_t + alpha_B) is cms_vertex_terms.h's controlVariateIntegral: the solve
// stores it as the cell's solutionAlphaSum.
SHARED_FN vec3 pairControlVariateTerm(vec3 T, uint cell, uint L, uint slot, float pt, float pB, float peff) {
  vec3 g = cellAlphaB(cell, L) * pB + pairCoefficient(slot) * pt;
  return T * g / peff;
}

// Adds a light-technique sample's terms to its pair: A_tt += w (p_t/p_eff)^2, A_tB += w (p_t/p_eff)
// (p_B/p_eff), b_t += w f (p_t/p_eff) / p_eff and one sample (ratios first, as
// addSampleStatistics forms them). The cell's own A_BB and b_B come from addSampleStatistics. A
// refused pair (kNoPairSlot while gathering) adds nothing here and is counted: its alpha_t stays 0.
SHARED_FN void addPairStatistics(uint slot, CMS_STAT_REAL pt, CMS_STAT_REAL pB, CMS_STAT_REAL peff, vec3 f,
                                 CMS_STAT_REAL w) {
  if (!(w > CMS_STAT_REAL(0))) return;
  if (slot == kNoPairSlot) {
    CMS_COUNT_PAIR(kPairCounterRefusedSamples);
    return;
  }
  CMS_STAT_REAL rt = pt / peff;
  CMS_STAT_REAL rB = pB / peff;
  CMS_ADD_PAIR_STAT(pairStatsAtt(slot), w * rt * rt);
  CMS_ADD_PAIR_STAT(pairStatsAtB(slot), w * rt * rB);
  if (!isBlack(f)) {
    CMS_STAT_REAL scale = w * rt / peff;
    for (uint c = 0u; c < 3u; ++c) CMS_ADD_PAIR_STAT(pairStatsBt(slot, c), CMS_STAT_REAL(f[c]) * scale);
  }
  CMS_ADD_PAIR_SAMPLE(slot);
  CMS_COUNT_PAIR(kPairCounterPairSamples);
}

SHARED_END_WITH_BUFFERS
#endif
