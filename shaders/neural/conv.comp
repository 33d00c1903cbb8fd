#version 460
// One 3x3 convolution of the learned denoiser (zero padding, fused bias and ReLU), reading one
// tensor (optionally at half resolution, upsampled by nearest neighbour) and optionally a second
// one concatenated after it (the U-Net's skip connection, read in place: no copy). Each
// invocation computes OUT_PER_THREAD output channels of PIXELS horizontally adjacent pixels, so
// that every weight it loads serves each of them; z selects the channel group. Each pixel's sums
// run in the same order as with one pixel an invocation.
// Weights: vec4s over four consecutive output channels, at ((tap * CIN + ci) * OUT / 4 + o4),
// then the bias (passes/src/neural/weights.rs packs them).
#include "neural/tensor.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const uint IN0_CHANNELS = 16;
layout(constant_id = 1) const uint IN1_CHANNELS = 0;
layout(constant_id = 2) const uint OUT_CHANNELS = 16;
layout(constant_id = 3) const uint OUT_PER_THREAD = 16;
layout(constant_id = 4) const bool IN0_UPSAMPLED = false;
layout(constant_id = 5) const bool RELU = true;
layout(constant_id = 6) const uint PIXELS = 2;

const uint OUT4 = OUT_PER_THREAD / 4;

layout(set = 0, binding = 0, std430) readonly buffer In0 { uvec2 v[]; } b_in0;
layout(set = 0, binding = 1, std430) readonly buffer In1 { uvec2 v[]; } b_in1;
layout(set = 0, binding = 2, std430) readonly buffer Weights { vec4 v[]; } b_weights;
layout(set = 0, binding = 3, std430) writeonly buffer Out { uvec2 v[]; } b_out;

layout(push_constant) uniform Params {
    uint width;          // output (and second input) size
    uint height;
    uint in0_width;      // first input size (half the output's when upsampled, rounded up)
    uint in0_height;
    uint weight_offset;  // this layer's first vec4 in b_weights
} params;

void main() {
    ivec2 first = ivec2(gl_GlobalInvocationID.x * PIXELS, gl_GlobalInvocationID.y);
    ivec2 size = ivec2(params.width, params.height);
    if (any(greaterThanEqual(first, size))) {
        return;
    }
    const uint cin = IN0_CHANNELS + IN1_CHANNELS;
    const uint out4_all = OUT_CHANNELS / 4u;
    uint group = gl_GlobalInvocationID.z * OUT4;
    vec4 acc[OUT4 * PIXELS];
    uint bias = params.weight_offset + 9u * cin * out4_all + group;
    for (uint o = 0u; o < OUT4; ++o) {
        vec4 b = b_weights.v[bias + o];
        for (uint i = 0u; i < PIXELS; ++i) {
            acc[o * PIXELS + i] = b;
        }
    }
    ivec2 in0_last = ivec2(params.in0_width, params.in0_height) - 1;
    for (int tap = 0; tap < 9; ++tap) {
        ivec2 offset = ivec2(tap % 3 - 1, tap / 3 - 1);
        uint w_tap = params.weight_offset + uint(tap) * cin * out4_all + group;
        // Which of the pixels read this tap (zero padding outside the image), and where.
        bool reads[PIXELS];
        uint at0[PIXELS];
        uint at1[PIXELS];
        for (uint i = 0u; i < PIXELS; ++i) {
            ivec2 q = first + ivec2(i, 0) + offset;
            reads[i] = all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size))
                && first.x + int(i) < size.x;
            ivec2 q0 = IN0_UPSAMPLED ? min(q >> 1, in0_last) : q;
            at0[i] = reads[i] ? tensor_index(q0, params.in0_width, IN0_CHANNELS / 4u, 0u) : 0u;
            at1[i] = reads[i] ? tensor_index(q, params.width, IN1_CHANNELS / 4u, 0u) : 0u;
        }
        for (uint c4 = 0u; c4 < IN0_CHANNELS / 4u; ++c4) {
            vec4 x[PIXELS];
            for (uint i = 0u; i < PIXELS; ++i) {
                x[i] = reads[i] ? unpack_channels(b_in0.v[at0[i] + c4]) : vec4(0.0);
            }
            for (uint k = 0u; k < 4u; ++k) {
                uint w = w_tap + (c4 * 4u + k) * out4_all;
                for (uint o = 0u; o < OUT4; ++o) {
                    vec4 weight = b_weights.v[w + o];
                    for (uint i = 0u; i < PIXELS; ++i) {
                        if (reads[i]) {
                            acc[o * PIXELS + i] += x[i][k] * weight;
                        }
                    }
                }
            }
        }
        if (IN1_CHANNELS > 0u) {
            for (uint c4 = 0u; c4 < IN1_CHANNELS / 4u; ++c4) {
                vec4 x[PIXELS];
                for (uint i = 0u; i < PIXELS; ++i) {
                    x[i] = reads[i] ? unpack_channels(b_in1.v[at1[i] + c4]) : vec4(0.0);
                }
                for (uint k = 0u; k < 4u; ++k) {
                    uint w = w_tap + (IN0_CHANNELS + c4 * 4u + k) * out4_all;
                    for (uint o = 0u; o < OUT4; ++o) {
                        vec4 weight = b_weights.v[w + o];
                        for (uint i = 0u; i < PIXELS; ++i) {
                            if (reads[i]) {
                                acc[o * PIXELS + i] += x[i][k] * weight;
                            }
                        }
                    }
                }
            }
        }
    }
    for (uint i = 0u; i < PIXELS; ++i) {
        ivec2 pixel = first + ivec2(i, 0);
        if (pixel.x < size.x) {
            uint at = tensor_index(pixel, params.width, out4_all, group);
            for (uint o = 0u; o < OUT4; ++o) {
                vec4 v = acc[o * PIXELS + i];
                b_out.v[at + o] = pack_channels(RELU ? max(v, vec4(0.0)) : v);
            }
        }
    }
}
