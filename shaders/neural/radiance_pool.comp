#version 460
// The kernel-predicting decoder's radiance at its sixteenth scale (training/kernel_model.py,
// `KernelOutput`): the eighth's linear means (features.comp) 2x2 average-pooled, odd edges
// repeating the last pixel as pool.comp does, then log(1 + x) rounded to half precision, as
// kernel_filter.comp filters it.
#include "neural/tensor.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, std430) readonly buffer In { vec4 v[]; } b_in;
layout(set = 0, binding = 1, std430) writeonly buffer Out { vec4 v[]; } b_out;

layout(push_constant) uniform Params {
    uint width;  // output size
    uint height;
    uint in_width;
    uint in_height;
} params;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(params.width) || pixel.y >= int(params.height)) {
        return;
    }
    ivec2 last = ivec2(params.in_width, params.in_height) - 1;
    vec3 mean = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        ivec2 q = min(pixel * 2 + ivec2(i & 1, i >> 1), last);
        mean += 0.25 * b_in.v[q.y * int(params.in_width) + q.x].rgb;
    }
    b_out.v[pixel.y * int(params.width) + pixel.x] = log_pooled(mean);
}
