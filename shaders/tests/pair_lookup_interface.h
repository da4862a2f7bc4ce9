// Test kernel tests/pair_lookup.comp: every invocation finds (or, in kPairLookupInsert mode,
// finds or claims) the slot of one (cell, technique) pair of shared/cms_pair_table.h given by the
// host, and writes it to pairSlots[i] (tests/gpu/cms_pair_table_test.cpp); in
// kPairLookupInsertInOrder mode one invocation inserts them all in order, so its slots are
// deterministic and comparable with the C++ build's.
// The rows are the test's own (bindings 40-42 and 46, clear of the renderer's); its key row has its own
// ID (PAIR_LOOKUP_KEYS) so that a file may include it beside the renderer's pair table rows
// (shared/cms_pair_state.h: PAIR_KEYS at 34), as tests/gpu/layout_contract_test.cpp does.
#ifndef MIXTRACE_TESTS_PAIR_LOOKUP_INTERFACE_H
#define MIXTRACE_TESTS_PAIR_LOOKUP_INTERFACE_H
#include "shared/buffer_table.h"
#include "shared/cms_pair_layout.h"
#include "shared/cms_pair_state.h"   // kPairOccupied*

// (cell, technique) per invocation.
#define BUFFER_PAIR_QUERIES(X) X(PAIR_QUERIES, pairQueries, 40, READ_ONLY, uvec2, UPLOADED, "pair queries")
#define BUFFER_PAIR_SLOTS(X) X(PAIR_SLOTS, pairSlots, 41, READ_BACK, uint, UPLOADED, "pair slots")
// The hashed pair keys, 0 = an empty slot; the capacity is PairLookupConstants::capacity.
#define BUFFER_PAIR_LOOKUP_KEYS(X) X(PAIR_LOOKUP_KEYS, pairKeys, 42, READ_WRITE, uint64_t, UPLOADED, "pair table keys")

// The claimed slots as the renderer lists them (shared/cms_pair_state.h PAIR_OCCUPIED): count, then slots.
#define BUFFER_PAIR_LOOKUP_OCCUPIED(X) \
  X(PAIR_LOOKUP_OCCUPIED, pairOccupied, 46, READ_WRITE, uint, UPLOADED, "occupied pair slots")

#define PAIR_LOOKUP_BUFFERS(X) \
  BUFFER_PAIR_QUERIES(X) BUFFER_PAIR_SLOTS(X) BUFFER_PAIR_LOOKUP_KEYS(X) BUFFER_PAIR_LOOKUP_OCCUPIED(X)

SHARED_BEGIN
PAIR_LOOKUP_BUFFERS(BUFFER_BINDING_CONSTANT)

const uint kPairLookupFind = 0u;    // findPair: look up only
const uint kPairLookupInsert = 1u;  // findOrInsertPair, every invocation one query, all at once
const uint kPairLookupInsertInOrder = 2u;  // findOrInsertPair, invocation 0 alone, queries in order

struct PairLookupConstants {
  uint queryCount;
  uint capacity;  // slots in pairKeys, a power of two
  uint mode;      // kPairLookup*
  uint pad0;
};
SHARED_END
#endif
