// The sparse statistics of the control variate (docs/estimator.md; issue 13):
// one technique per emissive triangle, so a cell's system has thousands of unknowns, of which only
// the (cell, technique) pairs that received samples have non-zero A_tt, A_tB, b_t. This table
// gives each such pair a slot, found or claimed by hashing the pair; the statistics live in
// arrays indexed by that slot (shared/cms_pair_layout.h: the layout, the memory per slot, the
// largest table).
//
// Open addressing, triangular probing (slot_i = h + i(i+1)/2): for a power-of-two capacity it
// visits every slot once in `capacity` probes, and it clusters less than linear probing at the
// loads a table of many techniques runs at. A slot is claimed with a 64-bit compare-and-swap, so
// any number of invocations may insert the same or different pairs at once: each distinct pair
// gets exactly one slot. Slots are never freed or overwritten; the host clears the whole key
// array (fill with 0) when the statistics restart.
//
// When no free slot is found within kPairProbes (a full or crowded table), or a triangle pair
// would take one of the last quarter of the slots (kept for remainder pairs), the pair gets
// kNoPairSlot. The caller (shared/cms_pair_terms.h settlePairSample) then gathers the sample in
// its cluster's remainder technique, or counts it refused when that pair does not fit either:
// unbiased either way, so a full table costs variance, never correctness (docs/estimator.md §4,
// "When the table fills").
//
// The includer defines PAIR_KEY_LOAD(slot) -> the uint64 key in that slot, and
// PAIR_KEY_CAS(slot, expected, desired) -> the previous key (an atomic compare-and-swap on the key
// array): GLSL binds them to a buffer and atomicCompSwap, C++ to std::atomic<uint64_t>; and
// PAIR_SLOT_CLAIMED(slot), called once per slot by the invocation whose swap claimed it, which
// appends the slot to the list of occupied slots (shared/cms_pair_state.h PAIR_OCCUPIED) that the
// solve walks, and PAIR_OCCUPIED_COUNT() -> that list's length.
#ifndef MIXTRACE_SHARED_CMS_PAIR_TABLE_H
#define MIXTRACE_SHARED_CMS_PAIR_TABLE_H
#include "shared/cms_layouts.h"
#include "shared/cms_pair_layout.h"
#include "shared/dialect.h"
SHARED_BEGIN_WITH_BUFFERS

// Whether the table may hold remainder pairs: only once the triangle pairs reached their limit
// (findOrInsertPair claims a remainder pair no earlier), and the occupied count never falls. A
// remainder claimed during this pass still has alpha_R = 0, so a sample that read the count just
// before loses nothing by not looking it up: the render skips the lookup below the limit exactly
// (shared/cms_pair_terms.h settlePairSample).
SHARED_FN bool remaindersMayExist(uint capacity) { return PAIR_OCCUPIED_COUNT() >= pairTriangleSlotLimit(capacity); }

// The slot of (cell, technique) in a table of `capacity` slots (a power of two), found, or with
// `insert` claimed when the pair is new; kNoPairSlot when it is absent (without `insert`), when the
// probe sequence holds no free slot, or when cell is kNoCell. One probe loop for both, so a SIMD
// group whose invocations do different ones (some gather, some only read) runs one loop.
// Without `insert`: a pair sits at the first slot of its probe sequence that was empty or its own
// when it was inserted, and slots are never freed, so reaching an empty slot proves it absent.
SHARED_FN uint probePair(uint capacity, uint cell, uint technique, bool insert) {
  if (cell == kNoCell) return kNoPairSlot;
  uint64_t key = pairKey(cell, technique);
  uint mask = capacity - 1u;
  uint slot = hashPairKey(key) & mask;
  uint probes = pairProbeBound(capacity);
  for (uint i = 0u; i < probes; ++i) {
    uint64_t seen = PAIR_KEY_LOAD(slot);
    if (seen == key) return slot;
    if (seen == uint64_t(0)) {
      // The last quarter of the table is the remainder pairs', and they are claimed only once the
      // triangle pairs have reached it (pairTriangleSlotLimit, remaindersMayExist).
      if (!insert || isRemainderTechnique(technique) != remaindersMayExist(capacity)) return kNoPairSlot;
      // Another invocation may claim this slot between the load and the swap: then the swap
      // returns its key, which is ours (the same pair, raced) or another's (probe on).
      uint64_t previous = PAIR_KEY_CAS(slot, uint64_t(0), key);
      if (previous == uint64_t(0)) {
        PAIR_SLOT_CLAIMED(slot);
        return slot;
      }
      if (previous == key) return slot;
    }
    slot = (slot + i + 1u) & mask;
  }
  return kNoPairSlot;
}

// Found or claimed (the vertices that gather).
SHARED_FN uint findOrInsertPair(uint capacity, uint cell, uint technique) {
  return probePair(capacity, cell, technique, true);
}

// Found only, never inserted (the solve pass, and vertices that only read coefficients).
SHARED_FN uint findPair(uint capacity, uint cell, uint technique) { return probePair(capacity, cell, technique, false); }

SHARED_END_WITH_BUFFERS
#endif
