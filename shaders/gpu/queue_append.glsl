// Appending to a queue from many invocations at once: one atomic per subgroup instead of one per
// invocation. The subgroup's active invocations count themselves with a ballot, the first of them
// reserves that many slots with a single atomicAdd, and each takes the slot of its rank among
// them. Slots stay in invocation order within a subgroup, so a queue's order is what per-invocation
// atomics would give when nothing else appends at the same time.
//
// Why: lavapipe runs an atomic as a loop over the 8 lanes, each a `lock xadd` on the counter's
// cache line, which both worker threads share; in the shade pass those two counters were 16 % of
// its time (benchmarks/README.md, "What a pass costs on lavapipe"). GPUs gain as well: their
// compilers aggregate atomics like this themselves only where they can prove the address uniform.
#ifndef MIXTRACE_GPU_QUEUE_APPEND_GLSL
#define MIXTRACE_GPU_QUEUE_APPEND_GLSL
#extension GL_KHR_shader_subgroup_ballot : require

// slot = the next free entry of the queue whose counter is `counter` (a uint in a storage buffer);
// every active invocation of the subgroup that reaches it gets its own. A macro, because GLSL
// passes no buffer member by reference.
#define QUEUE_APPEND(counter, slot)                                      \
  {                                                                      \
    uvec4 queueBallot_ = subgroupBallot(true);                           \
    uint queueBase_ = 0u;                                                \
    if (subgroupElect())                                                 \
      queueBase_ = atomicAdd(counter, subgroupBallotBitCount(queueBallot_)); \
    slot = subgroupBroadcastFirst(queueBase_) + subgroupBallotExclusiveBitCount(queueBallot_); \
  }

#endif
