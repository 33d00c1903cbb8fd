// Shared helpers of the SVGF passes: demodulation, the history surface record and edge-stopping
// terms. Requires common/math.glsl.
#ifndef LUCID_SVGF_COMMON_GLSL
#define LUCID_SVGF_COMMON_GLSL

#include "common/half_round.glsl"

// The object id the G-buffer writes where the sky is seen.
const uint SVGF_SKY = 0xffffffffu;

// What the a-trous iterations read and write (rgba16f): illumination clamped to half precision's
// range, and the standard deviation rather than the variance, whose small values half precision
// would flush to zero; rounded to nearest (common/half_round.glsl), since the store's own
// conversion may truncate, which would darken the image a little at every iteration.
vec4 svgf_pack_filtered(vec3 illumination, float variance) {
    return round_to_half(vec4(min(illumination, vec3(60000.0)), sqrt(max(variance, 0.0))));
}

// The variance of a texel written by svgf_pack_filtered.
float svgf_filtered_variance(vec4 texel) {
    return texel.a * texel.a;
}

// Octahedral encoding of a unit vector into [-1, 1]^2.
vec2 svgf_oct_encode(vec3 n) {
    n /= abs(n.x) + abs(n.y) + abs(n.z);
    vec2 e = n.xy;
    if (n.z < 0.0) {
        e = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    }
    return e;
}

vec3 svgf_oct_decode(vec2 e) {
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) {
        n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    }
    return normalize(n);
}

// What the history keeps of a pixel's surface: view depth, normal, object id, and the luminance of
// the frame's raw radiance (the gradient pass compares replayed samples against it).
struct SvgfSurface {
    float depth;
    vec3 normal;
    uint object_id;
    float radiance_luminance;
};

uvec4 svgf_pack_surface(SvgfSurface s) {
    return uvec4(floatBitsToUint(s.depth), packSnorm2x16(svgf_oct_encode(s.normal)), s.object_id,
                 floatBitsToUint(s.radiance_luminance));
}

SvgfSurface svgf_unpack_surface(uvec4 v) {
    SvgfSurface s;
    s.depth = uintBitsToFloat(v.x);
    s.normal = svgf_oct_decode(unpackSnorm2x16(v.y));
    s.object_id = v.z;
    s.radiance_luminance = uintBitsToFloat(v.w);
    return s;
}

// The edge-stopping weight of SVGF between a centre pixel and a tap `dist` pixels away, from view
// depth (with its slope), normal and luminance (with the standard deviation of the centre).
float svgf_edge_weight(float z_p, float z_q, float slope, float dist, vec3 n_p, vec3 n_q,
                       float l_p, float l_q, float sigma_l_std, float sigma_z, float sigma_n) {
    float wz = abs(z_p - z_q) / (sigma_z * slope * dist + 1e-3 * z_p + 1e-6);
    float wl = abs(l_p - l_q) / (sigma_l_std + 1e-8);
    float wn = pow(max(dot(n_p, n_q), 0.0), sigma_n);
    return exp(-wz - wl) * wn;
}

#endif
