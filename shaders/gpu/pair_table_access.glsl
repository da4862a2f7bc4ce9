// The GLSL binding of the pair table's accessors (shared/cms_pair_table.h): the keys in `pairKeys`,
// claimed with a 64-bit compare-and-swap, and each claimed slot appended to `pairOccupied` (a
// count, then the slots: shared/cms_pair_state.h). One binding for the renderer's passes
// (gpu/cms_buffers.glsl) and the table's test kernel (tests/pair_lookup.comp), whose rows use
// these names.
#define PAIR_KEY_LOAD(slot) pairKeys[slot]
#define PAIR_KEY_CAS(slot, expected, desired) atomicCompSwap(pairKeys[slot], expected, desired)
#define PAIR_SLOT_CLAIMED(slot) \
  pairOccupied[kPairOccupiedFirst + atomicAdd(pairOccupied[kPairOccupiedCount], 1u)] = (slot)
#define PAIR_OCCUPIED_COUNT() pairOccupied[kPairOccupiedCount]
