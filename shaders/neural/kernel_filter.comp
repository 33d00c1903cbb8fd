#version 460
// The kernel-predicting decoder's coarser scales (kernel.glsl; training/kernel_model.py,
// `KernelOutput`): the log radiance features.comp pooled to this scale, filtered by this scale's
// head, float32 rgb. The full scale is filtered where output.comp composites it.
// Scales are composited coarse to fine (`combine`: fine + a * (up(coarse) - up(pool(fine))), `up`
// bilinear and linear, `a` the sigmoid of the finer head's channel 25), as differences:
//   detail = filtered [+ sigmoid(a) * up(coarser detail) (COARSER)] - pool(finer filtered) (DETAIL),
// which the next finer scale upsamples (output.comp for the half scale's). With LINEAR_MIX every
// pixel of the output (and of the finer and coarser scales' buffers) holds two vec4s, the log
// space's result and then the linear space's, each composited alike.
#include "neural/tensor.glsl"
#include "neural/kernel.glsl"
#include "neural/upsample.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const uint LOGIT_CHANNELS = 28;  // the head's output channels, padded to 4
layout(constant_id = 1) const bool DETAIL = false;
layout(constant_id = 2) const bool COARSER = false;

// The head's channel that weighs the next coarser scale.
const uint BLEND_CHANNEL = 25u;

layout(set = 0, binding = 0, std430) readonly buffer Logits { uvec2 v[]; } b_logits;
layout(set = 0, binding = 1, std430) readonly buffer Radiance { vec4 v[]; } b_radiance;
layout(set = 0, binding = 2, std430) writeonly buffer Out { vec4 v[]; } b_out;
// The next finer scale's filtered radiance (DETAIL).
layout(set = 0, binding = 3, std430) readonly buffer Finer { vec4 v[]; } b_finer;
// The next coarser scale's detail (COARSER).
layout(set = 0, binding = 4, std430) readonly buffer Coarser { vec4 v[]; } b_coarser;

layout(push_constant) uniform Params {
    uint width;  // this scale's size
    uint height;
    uint finer_width;
    uint finer_height;
    uint coarser_width;
    uint coarser_height;
} params;

vec4 kernel_logits(ivec2 pixel, uint c4) {
    return unpack_channels(b_logits.v[tensor_index(pixel, params.width, LOGIT_CHANNELS / 4u, c4)]);
}

vec3 kernel_radiance(ivec2 q) {
    return b_radiance.v[q.y * int(params.width) + q.x].rgb;
}

// The vec4s a pixel of the output, finer and coarser buffers holds.
const int RESULTS = LINEAR_MIX ? 2 : 1;

// Where result `k` (0 log, 1 linear) of `pixel` lies in a buffer of rows `width` wide.
int result_index(ivec2 pixel, int width, int k) {
    return (pixel.y * width + pixel.x) * RESULTS + k;
}

// The next coarser scale's detail (result `k`) bilinearly upsampled to `pixel` of this scale.
vec3 upsampled_coarser(ivec2 pixel, ivec2 size, int k) {
    ivec2 coarse = ivec2(params.coarser_width, params.coarser_height);
    ivec2 i0, i1;
    vec2 f;
    bilinear_taps(pixel, size, coarse, i0, i1, f);
    return bilinear_mix(b_coarser.v[result_index(i0, coarse.x, k)].rgb,
                        b_coarser.v[result_index(ivec2(i1.x, i0.y), coarse.x, k)].rgb,
                        b_coarser.v[result_index(ivec2(i0.x, i1.y), coarse.x, k)].rgb,
                        b_coarser.v[result_index(i1, coarse.x, k)].rgb, f);
}

// Result `k` of this scale: `filtered` with the coarser detail composited (COARSER) and the finer
// scale's pooled result taken away (DETAIL).
vec3 composited(ivec2 pixel, ivec2 size, vec3 filtered, int k) {
    if (COARSER) {
        float a = kernel_logits(pixel, BLEND_CHANNEL / 4u)[BLEND_CHANNEL % 4u];
        filtered += upsampled_coarser(pixel, size, k) / (1.0 + exp(-a));
    }
    if (DETAIL) {
        ivec2 finer = ivec2(params.finer_width, params.finer_height);
        vec3 pooled = vec3(0.0);
        for (int i = 0; i < 4; ++i) {
            ivec2 q = min(pixel * 2 + ivec2(i & 1, i >> 1), finer - 1);
            pooled += b_finer.v[result_index(q, finer.x, k)].rgb;
        }
        filtered -= 0.25 * pooled;
    }
    return filtered;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(params.width, params.height);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    KernelMeans means = apply_kernel(pixel, size);
    b_out.v[result_index(pixel, size.x, 0)] = vec4(composited(pixel, size, means.log_mean, 0), 0.0);
    if (LINEAR_MIX) {
        b_out.v[result_index(pixel, size.x, 1)] = vec4(composited(pixel, size, means.linear_mean, 1), 0.0);
    }
}
