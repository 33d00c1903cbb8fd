#version 460
// The kernel-predicting decoder's compositing of scales (training/kernel_model.py, `combine`:
// fine + a * (up(coarse) - up(pool(fine))), with `up` bilinear and linear) at the coarsest scale,
// as the difference it adds to the next finer one, upsampled: at this (quarter) scale,
//   detail = filtered - pool(finer filtered).
// output.comp composites the half scale with it and the full scale with the half's. Float32.

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, std430) readonly buffer Filtered { vec4 v[]; } b_filtered;
layout(set = 0, binding = 1, std430) readonly buffer Finer { vec4 v[]; } b_finer;
layout(set = 0, binding = 2, std430) writeonly buffer Out { vec4 v[]; } b_out;

layout(push_constant) uniform Params {
    uint width;  // this scale's size
    uint height;
    uint finer_width;
    uint finer_height;
} params;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(params.width, params.height);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec3 detail = b_filtered.v[pixel.y * size.x + pixel.x].rgb;
    ivec2 finer = ivec2(params.finer_width, params.finer_height);
    vec3 pooled = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        ivec2 q = min(pixel * 2 + ivec2(i & 1, i >> 1), finer - 1);
        pooled += b_finer.v[q.y * finer.x + q.x].rgb;
    }
    b_out.v[pixel.y * size.x + pixel.x] = vec4(detail - 0.25 * pooled, 0.0);
}
