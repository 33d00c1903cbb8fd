// The path tracer's parked paths (parking/parking.glsl): with PARK_DEPTH set, a path still alive
// after PARK_DEPTH segments goes to its pixel's record in b_parked and long_paths.comp continues it.
// Requires parking/parking.glsl.
#ifndef LUCID_LONG_PATHS_GLSL
#define LUCID_LONG_PATHS_GLSL

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

#ifdef PARKING_CONTINUE
layout(set = 0, binding = 23, std430) readonly buffer Parked { ParkedPath p[]; } b_parked;
#else
layout(set = 0, binding = 23, std430) writeonly buffer Parked { ParkedPath p[]; } b_parked;

// Parks the path of this invocation's pixel (a plain store: atomics or subgroup operations here
// cost the path tracer registers on NVIDIA, bench/README.md).
#define PATH_PARK(o, d, beta, prev_pdf, prev_delta, prev_p, rng) if (PARK_DEPTH != 0u) { \
    uint parked_pixel = parking_pixel(); \
    b_parked.p[parked_pixel] = ParkedPath(o, rng, d, prev_delta ? 1u : 0u, beta, prev_pdf, prev_p, 0u); \
    b_parked_flags.f[parked_pixel] = 1u; }
#endif

#endif
