// Deterministic random numbers: a pure function of (pixel, frame index, seed, draw number).
#ifndef LUCID_RNG_GLSL
#define LUCID_RNG_GLSL

uint pcg_hash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// The generator state for one pixel of one frame.
uint rng_init(uvec2 pixel, uint frame, uint seed) {
    return pcg_hash(pixel.x ^ pcg_hash(pixel.y ^ pcg_hash(frame ^ pcg_hash(seed))));
}

// A uniform float in [0, 1) with 24 bits of precision.
float rng_next(inout uint state) {
    state = state * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    word = (word >> 22u) ^ word;
    return float(word >> 8u) * (1.0 / 16777216.0);
}

// A uniform float in [0, 1) from a hash of the state that leaves the stream as it is: a number a
// sampling decision can use without shifting every draw after it (so that paths that do not
// need it keep their random numbers).
float rng_side(uint state) {
    return float(pcg_hash(pcg_hash(state ^ 0x9e3779b9u)) >> 8u) * (1.0 / 16777216.0);
}

vec2 rng_next2(inout uint state) {
    float a = rng_next(state);
    return vec2(a, rng_next(state));
}

#endif
