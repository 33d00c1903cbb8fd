// Long paths: with PARK_DEPTH set, a path still alive after PARK_DEPTH segments (Russian roulette's
// start) is parked rather than traced on: its state goes to its pixel's record in b_parked and its
// flag in b_parked_flags is set. long_paths_list.comp then lists the flagged pixels and
// long_paths.comp continues their paths, one invocation each, over that compacted list, so that
// the few paths the roulette keeps no longer hold whole subgroups of the path tracer
// (bench/README.md). One sample a pixel: a pixel parks at most one path a frame. 0: off. Each
// part's non-finite radiance is dropped and counted on its own: where the first part was dropped,
// the pixel keeps what the continuation adds (one kernel drops the whole path).
#ifndef LUCID_LONG_PATHS_GLSL
#define LUCID_LONG_PATHS_GLSL

layout(constant_id = 122) const uint PARK_DEPTH = 0u;

// What trace_path_from needs to go on with a path: its next ray, throughput, MIS state and random
// number generator, 64 bytes.
struct ParkedPath {
    vec3 o;
    uint rng;
    vec3 d;
    uint prev_delta;
    vec3 beta;
    float prev_pdf;
    vec3 prev_p;
    uint pad;
};

#ifdef LONG_PATHS_CONTINUE
layout(set = 0, binding = 23, std430) readonly buffer Parked { ParkedPath p[]; } b_parked;
#else
layout(set = 0, binding = 23, std430) writeonly buffer Parked { ParkedPath p[]; } b_parked;
layout(set = 0, binding = 24, std430) writeonly buffer ParkedFlags { uint f[]; } b_parked_flags;

// Parks the path of this invocation's pixel (a plain store: atomics or subgroup operations here
// cost the path tracer registers on NVIDIA, bench/README.md).
#define PATH_PARK(o, d, beta, prev_pdf, prev_delta, prev_p, rng) if (PARK_DEPTH != 0u) { \
    uint parked_pixel = gl_GlobalInvocationID.y * b_frame.f.width + gl_GlobalInvocationID.x; \
    b_parked.p[parked_pixel] = ParkedPath(o, rng, d, prev_delta ? 1u : 0u, beta, prev_pdf, prev_p, 0u); \
    b_parked_flags.f[parked_pixel] = 1u; }
#endif

#endif
