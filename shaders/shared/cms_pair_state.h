// The buffers of the per-triangle control variate (docs/estimator.md §2, §4; ../shared/cms.md §4):
// one control-variate technique per emissive triangle (or per merged group of triangles, beyond
// the technique budget), its statistics stored sparsely per (cell, technique) pair in the hashed
// table of shared/cms_pair_table.h, and its solved coefficients per pair. Rows in the format of
// shared/buffer_table.h.
//
// What lives where:
//   - per cell (shared/cms_state.h, unchanged): A_BB, b_B and the sample count in the cell
//     statistics, which the per-cluster system shares (its BSDF row is the same); alpha_B, the
//     validity flag and sum alpha_t + alpha_B in the cell solution (solutionAlphaB, solutionValid,
//     solutionAlphaSum); the selection c_k as today.
//   - per pair slot (here): the key (cell, technique), A_tt, A_tB, b_t (shared/cms_pair_layout.h),
//     the pair's sample count, and alpha_t (RGB, kPairAlphaStride floats per slot).
//   - per technique source (here, TECHNIQUES): which technique a light sample's point belongs to
//     and that technique's share of its cluster's light sampling.
//
// Keys persist for the whole render (slots are never freed, so a pair keeps its slot and its
// alpha across iterations); statistics are zeroed per cell when the cell restarts (a new selection,
// docs/estimator.md §7). A sample whose pair the full table refuses adds to its cluster's remainder
// technique in the cell instead (shared/cms_pair_layout.h remainderTechnique), and one whose
// remainder pair is refused too adds to the cell's A_BB, b_B only (alpha_t = 0): unbiased either
// way, and counted in PAIR_COUNTERS.
#ifndef MIXTRACE_SHARED_CMS_PAIR_STATE_H
#define MIXTRACE_SHARED_CMS_PAIR_STATE_H
#include "shared/buffer_table.h"
#include "shared/cms_pair_layout.h"
#include "shared/dialect.h"

// Extents (host/wavefront/device_buffers.cpp): PAIR_SLOTS = the table's capacity (a power of two,
// pairTableCapacityFor), PAIR_STATS = capacity x kPairStatsStride, PAIR_ALPHAS = capacity x
// kPairAlphaStride; placeholders of one element for the methods without the per-triangle CV.
#define BUFFER_PAIR_KEYS(X) X(PAIR_KEYS, pairKeys, 34, READ_WRITE, uint64_t, PAIR_SLOTS, "CMS pair table keys")
#define BUFFER_PAIR_STATS(X) X(PAIR_STATS, pairStats, 35, READ_WRITE, float, PAIR_STATS, "CMS pair statistics")
#define BUFFER_PAIR_SAMPLES(X) X(PAIR_SAMPLES, pairSamples, 36, READ_WRITE, uint, PAIR_SLOTS, "CMS pair sample counts")
#define BUFFER_PAIR_ALPHA(X) X(PAIR_ALPHA, pairAlpha, 37, READ_WRITE, float, PAIR_ALPHAS, "CMS pair coefficients")
// Indexed by technique source: emitter index e for a point on an area light's emitter e (EmitterGpu),
// emitterCount + light for a punctual light (its own technique, counting measure).
#define BUFFER_TECHNIQUES(X) X(TECHNIQUES, techniques, 38, READ_ONLY, TechniqueRefGpu, UPLOADED, "CV techniques")
// Indexed by technique: its cluster and its share Q_t, for the solve's mass of each remainder
// technique (shared/cms_sparse_solve.h kSparseRemainderPairs).
#define BUFFER_TECHNIQUE_CLUSTERS(X) \
  X(TECHNIQUE_CLUSTERS, techniqueClusters, 47, READ_ONLY, TechniqueClusterGpu, UPLOADED, "CV technique clusters")
// Counters the host reads after the render (kPairCounter*), for the stats JSON.
#define BUFFER_PAIR_COUNTERS(X) \
  X(PAIR_COUNTERS, pairCounters, 39, READ_BACK, uint, PAIR_COUNTER_SLOTS, "CMS pair counters")
// The slots claimed so far, in the order they were claimed: entry kPairOccupiedCount holds their
// number, entries kPairOccupiedFirst.. the slots (extent PAIR_OCCUPIED_SLOTS = capacity +
// kPairOccupiedFirst). Slots are never freed, so the list only grows; the solve walks it instead of
// the whole table (a table of 2^22 slots that 112k pairs use, paper Veach MIS at 160x120, cost
// its pair stages a third of the render on lavapipe when they ran one invocation per slot).
#define BUFFER_PAIR_OCCUPIED(X) \
  X(PAIR_OCCUPIED, pairOccupied, 44, READ_WRITE, uint, PAIR_OCCUPIED_SLOTS, "CMS occupied pair slots")
// Binding 43 is the sparse solve's own scratch (per cell), binding 45 its dispatch arguments, both
// owned by its pass.

// Every pair row but the coefficients, which the settling passes read through their view.
#define CMS_PAIR_TABLE_BUFFERS(X) \
  BUFFER_PAIR_KEYS(X) BUFFER_PAIR_STATS(X) BUFFER_PAIR_SAMPLES(X) BUFFER_TECHNIQUES(X) BUFFER_PAIR_COUNTERS(X) \
  BUFFER_PAIR_OCCUPIED(X)
#define CMS_PAIR_BUFFERS(X) CMS_PAIR_TABLE_BUFFERS(X) BUFFER_PAIR_ALPHA(X)
// The coefficients as the passes that only read them see them: a view (shared/cms_state.h,
// CMS_STATE_VIEWS) of PAIR_ALPHA as texels, one texel per slot (kPairAlphaStride floats).
#define BUFFER_PAIR_ALPHA_TEXELS(X) \
  X(PAIR_ALPHA_TEXELS, pairAlphaTexels, 59, TEXELS, float, PAIR_ALPHAS, "CMS pair coefficients (texels)")
#define CMS_PAIR_VIEWS(X) BUFFER_PAIR_ALPHA_TEXELS(X)
#define CMS_PAIR_VIEWED(V) V(PAIR_ALPHA_TEXELS, PAIR_ALPHA)
// The pair rows of the passes that settle samples (shadow, fused): the coefficients as texels.
#define CMS_PAIR_SETTLE_BUFFERS(X) CMS_PAIR_TABLE_BUFFERS(X) BUFFER_PAIR_ALPHA_TEXELS(X)

SHARED_BEGIN
CMS_PAIR_BUFFERS(BUFFER_BINDING_CONSTANT)
CMS_PAIR_VIEWS(BUFFER_BINDING_CONSTANT)
BUFFER_TECHNIQUE_CLUSTERS(BUFFER_BINDING_CONSTANT)

// alpha_t of the pair in `slot`, RGB at kPairAlphaStride * slot + channel, then one more float:
//   - a triangle technique's pair: 1 when the last solve put it in the system of a valid cell (its
//     alpha_t p_t is used), else 0 (its samples take the remainder technique's alpha_R p_k instead);
//   - a remainder technique's pair: the solve's own (the sum of Q_t over the cell's solved pairs of
//     its cluster, gathered on the GPU as float bits), read by nothing else.
const uint kPairAlphaStride = 4u;
SHARED_FN uint pairAlphaIndex(uint slot, uint channel) { return kPairAlphaStride * slot + channel; }
SHARED_FN uint pairSolvedIndex(uint slot) { return kPairAlphaStride * slot + 3u; }

// The technique a light point belongs to, and the technique's share Q_t of its cluster's light
// sampling: the summed probability, once the cluster is chosen, of picking one of its triangles
// (sum over its emitters of the light's pmf in the cluster x the emitter's pmf in the light). The
// technique's normalised density is p_t(z) = p_k(z) / Q_t on its support (docs/estimator.md §2):
// for a technique of one triangle, exactly the point's density on that triangle.
struct TechniqueRefGpu {
  uint technique;   // in [0, techniqueCount)
  float share;      // Q_t, in (0, 1]
};

// A technique's cluster and share Q_t (the share of every source of it, as in TechniqueRefGpu).
struct TechniqueClusterGpu {
  uint cluster;
  float share;
};

// A cell of the per-technique control variate gathers far past kCellSampleCap (shared/cms_layouts.h):
// its system has one unknown per technique the cell sees (a sphere light alone is 480 triangles),
// so 4096 vertices leave a few samples per pair, and alpha_t from a handful of samples adds more
// variance than it removes. Measured (CPU, paper Veach MIS 160x120, 64 spp, --cells 8, cv):
// relMSE 0.0548 with no cap against 0.085 with the 4096 cap (both with 8 samples per pair).
const uint kPairCellSampleCap = 1u << 20;

// A pair's alpha_t is used from this many samples on (fewer: alpha_t = 0, host/cms/sparse_solve.h
// minTechniqueSamples). Measured as above: 1 -> 0.0548, 8 -> 0.0506 (per-cluster cv: 0.0649).
const uint kPairMinSamples = 8u;

// PAIR_COUNTERS entries.
const uint kPairCounterPairSamples = 0u;      // light-technique samples that found or claimed their pair
const uint kPairCounterRefusedSamples = 1u;   // ... whose own pair and remainder pair the table refused
const uint kPairCounterRemainderSamples = 2u; // ... whose own pair was refused, added to the remainder's
const uint kPairCounterSlots = 3u;            // PAIR_COUNTER_SLOTS: the counters' extent

// PAIR_OCCUPIED entries.
const uint kPairOccupiedCount = 0u;   // how many slots are claimed
const uint kPairOccupiedFirst = 1u;   // the first claimed slot; the list's i-th at kPairOccupiedFirst + i
SHARED_END
#endif
