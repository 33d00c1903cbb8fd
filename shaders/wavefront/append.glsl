// Appending to a queue from a subgroup: one atomic per subgroup reserves the places of every
// invocation that appends, each takes its place by its rank among them. Requires the subgroup
// ballot extension and b_counts (read-write) declared.
#ifndef LUCID_WAVEFRONT_APPEND_GLSL
#define LUCID_WAVEFRONT_APPEND_GLSL

// This invocation's place in queue `slot` when `wanted` (undefined otherwise); `first` and `added`
// are the subgroup's first place and the places it took. Every invocation that may append calls
// it once per queue.
uint queue_reserve(bool wanted, uint slot, out uint first, out uint added) {
    uvec4 ballot = subgroupBallot(wanted);
    added = subgroupBallotBitCount(ballot);
    uint base = 0u;
    if (subgroupElect() && added > 0u) {
        base = atomicAdd(b_counts.c[slot], added);
    }
    first = subgroupBroadcastFirst(base);
    return first + subgroupBallotExclusiveBitCount(ballot);
}

#endif
