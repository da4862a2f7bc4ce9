#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
// Test kernel: the (cell, technique) pair table's concurrent find-or-insert and its lookup
// (tests/pair_lookup_interface.h).
#include "tests/pair_lookup_interface.h"
#define PASS_BUFFERS PAIR_LOOKUP_BUFFERS
#define PASS_CONSTANTS PairLookupConstants
#include "gpu/buffers.glsl"

#include "gpu/pair_table_access.glsl"
#include "shared/cms_pair_table.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (pc.mode == kPairLookupInsertInOrder) {
    if (i != 0u) return;
    for (uint q = 0u; q < pc.queryCount; ++q)
      pairSlots[q] = findOrInsertPair(pc.capacity, pairQueries[q].x, pairQueries[q].y);
    return;
  }
  if (i >= pc.queryCount) return;
  uvec2 q = pairQueries[i];
  pairSlots[i] = pc.mode == kPairLookupInsert ? findOrInsertPair(pc.capacity, q.x, q.y)
                                              : findPair(pc.capacity, q.x, q.y);
}
