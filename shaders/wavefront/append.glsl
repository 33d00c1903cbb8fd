// Appending to queues from a workgroup: each subgroup counts its appenders to a queue with a ballot
// and adds them to the workgroup's count in shared memory, then one invocation per queue reserves
// the workgroup's places with a single atomic on the queue's length (and, with APPEND_ARGS, grows
// the queue's indirect arguments in b_args_out by the workgroups the new places begin, so they
// always hold ceil(length / QUEUE_GROUP)), and each appender takes its place by its rank. A
// workgroup thus makes one atomic per queue on memory every invocation shares, not one per
// subgroup or per path.
//
// Requires APPEND_QUEUES (how many queues the kernel appends to, at most its workgroup size), the
// subgroup ballot extension and b_counts (read-write) declared. Every invocation of the workgroup
// calls append_begin, append_rank once per queue, then append_reserve, in uniform control flow
// (they hold barriers); append_place then gives an appender its place.
#ifndef LUCID_WAVEFRONT_APPEND_GLSL
#define LUCID_WAVEFRONT_APPEND_GLSL

shared uint append_count[APPEND_QUEUES];
shared uint append_first[APPEND_QUEUES];

void append_begin() {
    if (gl_LocalInvocationIndex < APPEND_QUEUES) {
        append_count[gl_LocalInvocationIndex] = 0u;
    }
    memoryBarrierShared();
    barrier();
}

// This invocation's rank among the workgroup's appenders to queue `queue` (< APPEND_QUEUES) when
// `wanted` (undefined otherwise).
uint append_rank(bool wanted, uint queue) {
    uvec4 ballot = subgroupBallot(wanted);
    uint added = subgroupBallotBitCount(ballot);
    uint offset = 0u;
    if (subgroupElect() && added > 0u) {
        offset = atomicAdd(append_count[queue], added);
    }
    return subgroupBroadcastFirst(offset) + subgroupBallotExclusiveBitCount(ballot);
}

// Reserves the workgroup's places in each queue q, whose length is b_counts.c[slots[q]].
void append_reserve(uint slots[APPEND_QUEUES]) {
    memoryBarrierShared();
    barrier();
    uint q = gl_LocalInvocationIndex;
    if (q < APPEND_QUEUES) {
        uint added = append_count[q];
        uint first = added > 0u ? atomicAdd(b_counts.c[slots[q]], added) : 0u;
        append_first[q] = first;
#ifdef APPEND_ARGS
        uint groups = (first + added + QUEUE_GROUP - 1u) / QUEUE_GROUP - (first + QUEUE_GROUP - 1u) / QUEUE_GROUP;
        if (groups > 0u) {
            atomicAdd(b_args_out.a[4u * slots[q]], groups);
        }
#endif
    }
    memoryBarrierShared();
    barrier();
}

// The place in queue `queue` of the appender of rank `rank` (after append_reserve).
uint append_place(uint queue, uint rank) {
    return append_first[queue] + rank;
}

#endif
