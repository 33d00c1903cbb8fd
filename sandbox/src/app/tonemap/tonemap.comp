#version 460
// Display transform: exposure, tone curve (clamp, ACES fit, AgX), sRGB encoding, 8-bit output.
// Matches lucid_engine::capture::PngEncoding so that PNG captures look like the window.

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D u_hdr;
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D u_out;

layout(push_constant) uniform Params {
    float exposure_scale;
    uint curve;     // 0 clamp, 1 ACES, 2 AgX
    uint swap_rb;   // 1: write BGRA order (the output is copied bit for bit into a BGRA image)
} params;

// The engine's row-major matrices, written row by row: GLSL reads them as columns, so they
// apply as `v * M`.
const mat3 AGX_INSET = mat3(
    0.842479062253094, 0.0784335999999992, 0.0792237451477643,
    0.0423282422610123, 0.878468636469772, 0.0791661274605434,
    0.0423756549057051, 0.0784336, 0.879142973793104);
const mat3 AGX_OUTSET = mat3(
    1.19687900512017, -0.0980208811401368, -0.0990297440797205,
    -0.0528968517574562, 1.15190312990417, -0.0989611768448433,
    -0.0529716355144438, -0.0980434501171241, 1.15107367264116);
const float AGX_MIN_EV = -12.47393;
const float AGX_MAX_EV = 4.026069;

vec3 aces(vec3 x) {
    return (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
}

vec3 agx_sigmoid(vec3 x) {
    vec3 x2 = x * x;
    vec3 x4 = x2 * x2;
    return 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2
        + 0.1191 * x - 0.00232;
}

vec3 agx(vec3 rgb) {
    vec3 ev = clamp(log2(max(rgb * AGX_INSET, vec3(1e-10))), AGX_MIN_EV, AGX_MAX_EV);
    vec3 encoded = agx_sigmoid((ev - AGX_MIN_EV) / (AGX_MAX_EV - AGX_MIN_EV));
    return pow(clamp(encoded * AGX_OUTSET, 0.0, 1.0), vec3(2.2));
}

vec3 srgb_encode(vec3 c) {
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_out);
    if (pixel.x >= size.x || pixel.y >= size.y) {
        return;
    }
    vec3 scene = texelFetch(u_hdr, pixel, 0).rgb;
    scene = clamp(mix(scene, vec3(0.0), isnan(scene)), 0.0, 1.0e30) * params.exposure_scale;
    vec3 display = params.curve == 1u ? aces(scene) : params.curve == 2u ? agx(scene) : scene;
    vec3 encoded = srgb_encode(clamp(display, 0.0, 1.0));
    imageStore(u_out, pixel, params.swap_rb == 1u ? vec4(encoded.bgr, 1.0) : vec4(encoded, 1.0));
}
