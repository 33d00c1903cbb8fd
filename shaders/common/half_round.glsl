// Rounding to half precision that survives an rgba16f image store. Vulkan leaves the rounding of a
// store's conversion to half precision to the implementation: lavapipe's and NVIDIA's truncate,
// which lowers every stored value by half a unit in the last place on average, and NVIDIA's
// compiler folds a packHalf2x16/unpackHalf2x16 round trip before such a store into the store's own
// conversion (tests/tests/half_rounding.rs). `round_to_half` rounds to nearest, ties to even, with
// exact float operations that no compiler takes for a conversion, so the store after it is exact.
#ifndef LUCID_COMMON_HALF_ROUND_GLSL
#define LUCID_COMMON_HALF_ROUND_GLSL

// The smallest magnitude that rounds to infinity in half precision: halfway from the largest
// finite half (65504) to 65536.
const float HALF_OVERFLOW = 65520.0;

// `x` rounded to the nearest half-precision value, ties to even (infinity from HALF_OVERFLOW up,
// NaN kept), as a float.
float round_to_half(float x) {
    if (isnan(x)) {
        return x;
    }
    if (abs(x) >= HALF_OVERFLOW) {
        return sign(x) * uintBitsToFloat(0x7f800000u);
    }
    int exponent;
    frexp(x, exponent);
    // Halves carry 11 significant bits, down to the subnormals' fixed step of 2^-24.
    int step = max(exponent - 11, -24);
    return ldexp(roundEven(ldexp(x, -step)), step);
}

vec4 round_to_half(vec4 v) {
    return vec4(round_to_half(v.x), round_to_half(v.y), round_to_half(v.z), round_to_half(v.w));
}

#endif
