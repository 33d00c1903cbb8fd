#version 460
// 2x2 average pooling of a tensor (training/model.py, `pool`); odd edges repeat the last pixel.
#include "neural/tensor.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const uint CHANNELS = 32;

layout(set = 0, binding = 0, std430) readonly buffer In { uvec2 v[]; } b_in;
layout(set = 0, binding = 1, std430) writeonly buffer Out { uvec2 v[]; } b_out;

layout(push_constant) uniform Params {
    uint width;  // output size
    uint height;
    uint in_width;
    uint in_height;
} params;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uint c4 = gl_GlobalInvocationID.z;
    if (pixel.x >= int(params.width) || pixel.y >= int(params.height)) {
        return;
    }
    ivec2 last = ivec2(params.in_width, params.in_height) - 1;
    vec4 sum = vec4(0.0);
    for (int i = 0; i < 4; ++i) {
        ivec2 q = min(pixel * 2 + ivec2(i & 1, i >> 1), last);
        sum += unpack_channels(b_in.v[tensor_index(q, params.in_width, CHANNELS / 4u, c4)]);
    }
    b_out.v[tensor_index(pixel, params.width, CHANNELS / 4u, c4)] = pack_channels(0.25 * sum);
}
