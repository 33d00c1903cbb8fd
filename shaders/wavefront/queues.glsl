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

uint ray_slot(uint depth) {
    return 2u * depth;
}

uint shadow_slot(uint depth) {
    return 2u * depth + 1u;
}

#endif
