#version 460
// The kernel-predicting decoder's compositing of scales (training/kernel_model.py, `combine`:
// fine + a * (up(coarse) - up(pool(fine))), with `up` bilinear and linear), one scale at a time, as
// the difference the next finer scale adds upsampled: at this (coarse) scale,
//   detail = filtered [+ sigmoid(a) * up(coarser detail)] - pool(finer filtered),
// where the bracket (this scale's own compositing with the one below, HAS_COARSER) uses channel 25
// of this scale's head. Float32 throughout.
#include "neural/tensor.glsl"
#include "neural/upsample.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const uint LOGIT_CHANNELS = 28;
layout(constant_id = 1) const bool HAS_COARSER = false;

const uint BLEND_CHANNEL = 25u;

layout(set = 0, binding = 0, std430) readonly buffer Filtered { vec4 v[]; } b_filtered;
layout(set = 0, binding = 1, std430) readonly buffer Finer { vec4 v[]; } b_finer;
layout(set = 0, binding = 2, std430) readonly buffer Coarser { vec4 v[]; } b_coarser;
layout(set = 0, binding = 3, std430) readonly buffer Logits { uvec2 v[]; } b_logits;
layout(set = 0, binding = 4, std430) writeonly buffer Out { vec4 v[]; } b_out;

layout(push_constant) uniform Params {
    uint width;  // this scale's size
    uint height;
    uint finer_width;
    uint finer_height;
    uint coarser_width;
    uint coarser_height;
} params;

// The coarser detail bilinearly upsampled to `pixel` of this scale.
vec3 upsampled(ivec2 pixel) {
    ivec2 coarse = ivec2(params.coarser_width, params.coarser_height);
    ivec2 i0, i1;
    vec2 f;
    bilinear_taps(pixel, ivec2(params.width, params.height), coarse, i0, i1, f);
    vec3 top = mix(b_coarser.v[i0.y * coarse.x + i0.x].rgb, b_coarser.v[i0.y * coarse.x + i1.x].rgb, f.x);
    vec3 bottom = mix(b_coarser.v[i1.y * coarse.x + i0.x].rgb, b_coarser.v[i1.y * coarse.x + i1.x].rgb, f.x);
    return mix(top, bottom, f.y);
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(params.width, params.height);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec3 detail = b_filtered.v[pixel.y * size.x + pixel.x].rgb;
    if (HAS_COARSER) {
        uint at = tensor_index(pixel, params.width, LOGIT_CHANNELS / 4u, BLEND_CHANNEL / 4u);
        float a = unpack_channels(b_logits.v[at])[BLEND_CHANNEL % 4u];
        detail += upsampled(pixel) / (1.0 + exp(-a));
    }
    ivec2 finer = ivec2(params.finer_width, params.finer_height);
    vec3 pooled = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        ivec2 q = min(pixel * 2 + ivec2(i & 1, i >> 1), finer - 1);
        pooled += b_finer.v[q.y * finer.x + q.x].rgb;
    }
    b_out.v[pixel.y * size.x + pixel.x] = vec4(detail - 0.25 * pooled, 0.0);
}
