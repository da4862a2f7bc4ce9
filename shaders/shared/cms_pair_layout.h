// The layout of the (cell, technique) pair table of shared/cms_pair_table.h: its keys, the
// statistics each slot holds, its memory and its capacity. Apart from the probing functions so the
// host (allocation, the solve's readback) includes it without binding the key array.
#ifndef MIXTRACE_SHARED_CMS_PAIR_LAYOUT_H
#define MIXTRACE_SHARED_CMS_PAIR_LAYOUT_H
#include "shared/dialect.h"
#include "shared/hash64.h"
SHARED_BEGIN

// The slot of a pair the table refused (or of a vertex that has no cell).
const uint kNoPairSlot = 0xffffffffu;

// Probes before a pair is refused. At a load of 1/2 (the capacity pairTableCapacityFor picks) a
// triangular probe sequence almost never gets this long; the bound only stops a full table from
// being scanned end to end by every vertex. 128, not 64: runs of consecutive techniques
// (hashPairKey) crowd a table more than scattered keys, and 64 refused one pair of 2.56 M at a
// load of 0.61 (CmsPairTable.TenThousandTechniquesTimesCellsFitAndInsertFast).
const uint kPairProbes = 128u;

// Statistics of one pair, floats, kPairStatsStride per slot in one array (the cell keeps A_BB and
// b_B itself): interleaved so the five atomics of one sample touch one cache line.
//   0        A_tt
//   1        A_tB
//   [2, 5)   b_t, RGB
// The number of samples the pair received is kept apart, as a uint (exact past 2^24).
const uint kPairStatsStride = 5u;
SHARED_FN uint pairStatsAtt(uint slot) { return kPairStatsStride * slot; }
SHARED_FN uint pairStatsAtB(uint slot) { return kPairStatsStride * slot + 1u; }
SHARED_FN uint pairStatsBt(uint slot, uint channel) { return kPairStatsStride * slot + 2u + channel; }

// Memory: 8 bytes of key + 20 of statistics + 4 of sample count = 32 bytes per slot. The largest
// single buffer is the statistics (20 bytes per slot); lavapipe's maxStorageBufferRange is 128 MiB,
// so 2^22 slots (4,194,304 pairs; statistics 80 MiB, keys 32 MiB, counts 16 MiB, 128 MiB in all)
// is the largest power-of-two table; 2^23 would need 160 MiB of statistics in one buffer.
const uint kPairBytesPerSlot = 32u;
const uint kPairKeyBytes = 8u;
const uint kPairStatsBytes = 4u * kPairStatsStride;
const uint kPairCountBytes = 4u;
const uint kMaxPairTableLog2 = 22u;

// The capacity (a power of two, at most 2^kMaxPairTableLog2) for an expected number of pairs: at
// least twice that many slots, so the load stays at or below 1/2 and probe sequences stay short.
SHARED_FN uint pairTableCapacityFor(uint expectedPairs) {
  uint capacity = 1u;
  uint log2 = 0u;
  while (log2 < kMaxPairTableLog2 && capacity / 2u < expectedPairs) {  // capacity < 2 x pairs, without overflow
    capacity *= 2u;
    ++log2;
  }
  return capacity;
}

// The key of a pair: the cell's slot + 1 in the high word (so a key is never 0, the empty slot)
// and the technique in the low word. cell must not be kNoCell (the functions below refuse it).
SHARED_FN uint64_t pairKey(uint cell, uint technique) {
  return (uint64_t(cell + 1u) << 32) | uint64_t(technique);
}
SHARED_FN uint pairKeyCell(uint64_t key) { return uint(key >> 32) - 1u; }
SHARED_FN uint pairKeyTechnique(uint64_t key) { return uint(key); }

// The remainder technique of cluster k in a cell (docs/estimator.md §4, "When the table fills"):
// the coarser technique a sample falls back to when the full table refuses its own (cell, t)
// pair. Its density is p_k restricted to the triangles of k that have no solved pair in the cell,
// so it stays disjoint from every triangle technique there (the system stays an arrowhead). Its id
// sets the top bit, which no triangle technique reaches (techniques are counted in the thousands).
const uint kRemainderTechniqueBit = 0x80000000u;
SHARED_FN uint remainderTechnique(uint cluster) { return kRemainderTechniqueBit | cluster; }
SHARED_FN bool isRemainderTechnique(uint technique) { return (technique & kRemainderTechniqueBit) != 0u; }
SHARED_FN uint remainderTechniqueCluster(uint technique) { return technique & ~kRemainderTechniqueBit; }

// A triangle technique's pair is claimed only while fewer than this many slots are occupied, a
// remainder pair only from then on: the last quarter of the table is kept for remainder pairs, and
// a table below the limit holds none (so the render need not look for one). A soft bound (invocations that read the
// count at once may all claim), and never reached by a table sized for its scene
// (pairTableCapacityFor keeps the load at or below 1/2).
SHARED_FN uint pairTriangleSlotLimit(uint capacity) { return capacity - capacity / 4u; }

// The first slot of a key's probe sequence. Techniques are numbered light by light, triangle by
// triangle, so a vertex's neighbours in a cell reach neighbouring techniques: a run of
// kPairRunLength consecutive techniques of one cell starts at one hashed slot and fills the slots
// after it, which share cache lines (the lookup's cost on a CPU device is its cache misses);
// the runs themselves, and one technique in neighbouring cells, land far apart (shared/hash64.h).
// Runs stay short, so a probe that starts inside another cell's run leaves it within a few probes.
const uint kPairRunLength = 16u;
SHARED_FN uint hashPairKey(uint64_t key) {
  uint technique = pairKeyTechnique(key);
  return hash64To32(pairKey(pairKeyCell(key), technique / kPairRunLength)) + technique % kPairRunLength;
}

SHARED_FN uint pairProbeBound(uint capacity) { return min(kPairProbes, capacity); }

SHARED_END
#endif
