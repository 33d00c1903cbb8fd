// The wavefront path tracer's queues (passes/src/light_transport/wavefront/queues.rs): per sample,
// one slot per queue, 2k for the rays of bounce k and 2k + 1 for bounce k's shadow rays. b_counts
// holds each slot's length, the indirect-argument buffers each slot's VkDispatchIndirectCommand
// (4 words: groups x, y, z, unused) in two buffers by parity (a kernel reads its own queue's
// arguments and appends to the other buffer, never both in one), and the queues hold path indices.
#ifndef LUCID_WAVEFRONT_QUEUES_GLSL
#define LUCID_WAVEFRONT_QUEUES_GLSL

// Invocations per workgroup of the kernels that run over a queue (one path each).
const uint QUEUE_GROUP = 128u;
// A hit record's instance when the ray hit nothing.
const uint MISS = 0xffffffffu;

// A shadow ray by path (what shade writes for the shadow kernel): the ShadowRay of common/path.glsl.
struct ShadowRecord {
    vec4 origin;    // origin, t_max
    vec4 direction; // direction, 0
    vec4 radiance;  // what it brings when unoccluded, 0
};

// With material binning (the *_binned kernels), extend sorts each bounce's hits into bins, a
// miss or the material kind it hit (MATERIAL_*), each bin a queue of its own: slot
// material_bin_slot(depth, bin) after the queue slots, its places at bin x paths in the binned
// queue; shade walks the bins one after the other, so a workgroup shades one kind of material
// but where two bins meet.
const uint MATERIAL_BINS = 5u;

// The queue slots of paths at most `max_depth` segments long (queues::slots in Rust).
uint queue_slots(uint max_depth) {
    return 2u * max_depth + 1u;
}

// The bin of a hit: 0 for a miss, else 1 + its material's kind.
uint material_bin(uint instance, uint material_kind) {
    return instance == MISS ? 0u : 1u + min(material_kind, MATERIAL_BINS - 2u);
}

uint material_bin_slot(uint depth, uint bin, uint max_depth) {
    return queue_slots(max_depth) + depth * MATERIAL_BINS + bin;
}

uint ray_slot(uint depth) {
    return 2u * depth;
}

uint shadow_slot(uint depth) {
    return 2u * depth + 1u;
}

#endif
