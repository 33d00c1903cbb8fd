// Rounding to half precision that survives an rgba16f image store. Vulkan leaves the rounding of a
// store's conversion to half precision to the implementation: lavapipe's and NVIDIA's truncate,
// which lowers every stored value by half a unit in the last place on average, and NVIDIA's
// compiler folds a packHalf2x16/unpackHalf2x16 round trip before such a store into the store's own
// conversion (tests/tests/half_rounding.rs). `round_to_half` rounds to nearest, ties to even, with
// exact float operations that no compiler takes for a conversion, so the store after it is exact.
#ifndef LUCID_COMMON_HALF_ROUND_GLSL
#define LUCID_COMMON_HALF_ROUND_GLSL

// The largest finite half.
const float HALF_MAX = 65504.0;

// `x` rounded to the nearest half-precision value, ties to even (infinity from halfway between
// HALF_MAX and 65536 up, NaN kept), as a float. The step between halves around `x` is a power of
// two read off its exponent bits (2^(e - 10) for an exponent e of at least -14, the subnormals'
// 2^-24 below), so scaling by it and back is exact and only `roundEven` rounds: a few integer
// operations (on an H200 SVGF's a-trous steps take 1% longer than without rounding, 17% with
// `frexp` and `ldexp`).
float round_to_half(float x) {
    uint exponent = max((floatBitsToUint(x) >> 23) & 0xffu, 113u);
    uint step = exponent - 10u;
    float rounded = roundEven(x * uintBitsToFloat((254u - step) << 23)) * uintBitsToFloat(step << 23);
    return abs(rounded) > HALF_MAX ? rounded * uintBitsToFloat(0x7f800000u) : rounded;
}

vec4 round_to_half(vec4 v) {
    return vec4(round_to_half(v.x), round_to_half(v.y), round_to_half(v.z), round_to_half(v.w));
}

#endif
