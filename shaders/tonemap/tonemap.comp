#version 460
// Exposure (stops), a filmic operator (clamp, ACES fit, AgX) and the sRGB transfer function,
// matching lucid_engine::capture::PngEncoding exactly.
#include "common/image_coords.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_hdr;
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D u_ldr;

layout(push_constant) uniform Params {
    float exposure;
    uint curve;   // 0 clamp, 1 ACES, 2 AgX
    uint swap_rb; // 1: store B, G, R, A (for copies into BGRA images)
} params;

const vec3 AGX_INSET_ROWS[3] = vec3[3](
    vec3(0.842479062253094, 0.0784335999999992, 0.0792237451477643),
    vec3(0.0423282422610123, 0.878468636469772, 0.0791661274605434),
    vec3(0.0423756549057051, 0.0784336, 0.879142973793104));
const vec3 AGX_OUTSET_ROWS[3] = vec3[3](
    vec3(1.19687900512017, -0.0980208811401368, -0.0990297440797205),
    vec3(-0.0528968517574562, 1.15190312990417, -0.0989611768448433),
    vec3(-0.0529716355144438, -0.0980434501171241, 1.15107367264116));
const float AGX_MIN_EV = -12.47393;
const float AGX_MAX_EV = 4.026069;

vec3 mul_rows(const vec3 rows[3], vec3 v) {
    return vec3(dot(rows[0], v), dot(rows[1], v), dot(rows[2], v));
}

vec3 aces(vec3 x) {
    return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
}

vec3 agx_sigmoid(vec3 x) {
    vec3 x2 = x * x;
    vec3 x4 = x2 * x2;
    return 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.00232;
}

vec3 agx(vec3 rgb) {
    vec3 ev = clamp(log2(max(mul_rows(AGX_INSET_ROWS, rgb), vec3(1e-10))), AGX_MIN_EV, AGX_MAX_EV);
    vec3 encoded = agx_sigmoid((ev - AGX_MIN_EV) / (AGX_MAX_EV - AGX_MIN_EV));
    return pow(clamp(mul_rows(AGX_OUTSET_ROWS, encoded), 0.0, 1.0), vec3(2.2));
}

vec3 srgb_encode(vec3 c) {
    bvec3 low = lessThanEqual(c, vec3(0.0031308));
    return mix(1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, 12.92 * c, low);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!pixel_in_bounds(pixel, imageSize(u_ldr))) {
        return;
    }
    vec3 c = imageLoad(u_hdr, pixel).rgb * exp2(params.exposure);
    c = clamp(mix(c, vec3(0.0), isnan(c)), 0.0, 1.0e30);
    if (params.curve == 1u) {
        c = aces(c);
    } else if (params.curve == 2u) {
        c = agx(c);
    }
    vec3 encoded = srgb_encode(clamp(c, 0.0, 1.0));
    imageStore(u_ldr, pixel, vec4(params.swap_rb == 1u ? encoded.bgr : encoded, 1.0));
}
