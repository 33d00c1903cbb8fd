#version 460
// The kernel-predicting decoder's coarser radiance (training/kernel_model.py, `KernelOutput`): the
// demodulated radiance (negative values clamped) 2x2 average-pooled LEVEL times from the record, in
// linear space, then log(1 + x) rounded to half precision, as the filter at that scale reads it.
// Odd edges repeat the last pixel of each level, as pool.comp does.
#include "neural/record.glsl"
#include "neural/tensor.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const uint LEVEL = 1;  // 1: half resolution, 2: quarter

layout(set = 0, binding = 0, std430) readonly buffer Record { float v[]; } b_record;
layout(set = 0, binding = 1, std430) writeonly buffer Out { vec4 v[]; } b_out;

layout(push_constant) uniform Params {
    uint width;  // the record's size
    uint height;
} params;

ivec2 level_size(uint level) {
    ivec2 size = ivec2(params.width, params.height);
    for (uint i = 0u; i < level; ++i) {
        size = (size + 1) / 2;
    }
    return size;
}

vec3 radiance(ivec2 pixel) {
    uvec2 size = uvec2(params.width, params.height);
    vec3 rgb;
    for (uint c = 0u; c < 3u; ++c) {
        rgb[c] = b_record.v[record_index(RECORD_DEMODULATED + c, pixel, size)];
    }
    return max(rgb, vec3(0.0));
}

// The mean of the 2x2 pixels of level 1 under `pixel` of level 1 (that is, of level 0).
vec3 level1(ivec2 pixel) {
    ivec2 last = level_size(0u) - 1;
    vec3 sum = vec3(0.0);
    for (int i = 0; i < 4; ++i) {
        sum += radiance(min(pixel * 2 + ivec2(i & 1, i >> 1), last));
    }
    return 0.25 * sum;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = level_size(LEVEL);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    vec3 mean;
    if (LEVEL == 1u) {
        mean = level1(pixel);
    } else {
        ivec2 last = level_size(1u) - 1;
        mean = vec3(0.0);
        for (int i = 0; i < 4; ++i) {
            mean += 0.25 * level1(min(pixel * 2 + ivec2(i & 1, i >> 1), last));
        }
    }
    vec3 log_mean = unpack_channels(pack_channels(vec4(log(vec3(1.0) + mean), 0.0))).rgb;
    b_out.v[pixel.y * size.x + pixel.x] = vec4(log_mean, 0.0);
}
