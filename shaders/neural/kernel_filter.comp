#version 460
// The kernel-predicting decoder's half and quarter scales (kernel.glsl): the log radiance
// features.comp pooled to this scale, filtered by this scale's head, float32 rgb. The full scale is
// filtered where output.comp composites it. At the coarsest scale (DETAIL), writes the difference
// it adds to the next finer scale (training/kernel_model.py, `combine`: fine + a * (up(coarse) -
// up(pool(fine))), with `up` bilinear and linear), upsampled in output.comp:
//   detail = filtered - pool(finer filtered).
#include "neural/tensor.glsl"
#include "neural/kernel.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const uint LOGIT_CHANNELS = 28;  // the head's output channels, padded to 4
layout(constant_id = 1) const bool DETAIL = false;

layout(set = 0, binding = 0, std430) readonly buffer Logits { uvec2 v[]; } b_logits;
layout(set = 0, binding = 1, std430) readonly buffer Radiance { vec4 v[]; } b_radiance;
layout(set = 0, binding = 2, std430) writeonly buffer Out { vec4 v[]; } b_out;
// The next finer scale's filtered radiance (DETAIL).
layout(set = 0, binding = 3, std430) readonly buffer Finer { vec4 v[]; } b_finer;

layout(push_constant) uniform Params {
    uint width;  // this scale's size
    uint height;
    uint finer_width;
    uint finer_height;
} params;

vec4 kernel_logits(ivec2 pixel, uint c4) {
    return unpack_channels(b_logits.v[tensor_index(pixel, params.width, LOGIT_CHANNELS / 4u, c4)]);
}

vec3 kernel_radiance(ivec2 q) {
    return b_radiance.v[q.y * int(params.width) + q.x].rgb;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(params.width, params.height);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec3 filtered = apply_kernel(pixel, size);
    if (DETAIL) {
        ivec2 finer = ivec2(params.finer_width, params.finer_height);
        vec3 pooled = vec3(0.0);
        for (int i = 0; i < 4; ++i) {
            ivec2 q = min(pixel * 2 + ivec2(i & 1, i >> 1), finer - 1);
            pooled += b_finer.v[q.y * finer.x + q.x].rgb;
        }
        filtered -= 0.25 * pooled;
    }
    b_out.v[pixel.y * size.x + pixel.x] = vec4(filtered, 0.0);
}
