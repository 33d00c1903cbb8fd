#version 460
// The tensor-core twin of conv.comp: one 3x3 convolution (zero padding, fused bias and ReLU) as an
// implicit GEMM on NVIDIA cooperative matrices (GL_NV_cooperative_matrix, fp16 operands, fp32
// sums). Same inputs and output as conv.comp, so the two are interchangeable; optionally it also
// writes the output 2x2 average-pooled (pool.comp's job, fused).
//
// A workgroup computes a 16 x TILE_H tile of output pixels, all output channels. For each group of
// 16 input channels it copies into shared memory the tile and its one-pixel halo, as the packed
// halves they are (reading the first input upsampled, or the skip connection in place, as
// conv.comp does), and the nine taps' half-precision weights (passes/src/neural/network.rs packs
// them); then each tap multiplies (16 pixels x 16 channels) by (16 channels x 16 outputs)
// matrices, the first read straight out of the staged tile, shifted by the tap's offset. Each of
// the four subgroups owns ROWS rows of the tile. The sums go through shared memory once more (in
// the weights' place) for the bias, the ReLU and the pooling, and out as packed halves. Rows in
// shared memory are padded by 16 bytes so that a matrix's rows fall in different banks.
#extension GL_NV_cooperative_matrix : require
#extension GL_KHR_memory_scope_semantics : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#include "neural/tensor.glsl"

layout(local_size_x = 128) in;

layout(constant_id = 0) const uint IN0_CHANNELS = 16;
layout(constant_id = 1) const uint IN1_CHANNELS = 0;
layout(constant_id = 2) const uint OUT_CHANNELS = 16;
layout(constant_id = 4) const bool IN0_UPSAMPLED = false;
layout(constant_id = 5) const bool RELU = true;
layout(constant_id = 6) const uint ROWS = 2;  // tile rows per subgroup: 1 to 4
layout(constant_id = 7) const bool POOLED = false;

const uint TILE_W = 16;
const uint TILE_H = 4u * ROWS;
const uint MAX_ROWS = 4;
const uint HALO_W = TILE_W + 2u;
const uint HALO_PIXELS = HALO_W * (TILE_H + 2u);
const uint CHANNELS = IN0_CHANNELS + IN1_CHANNELS;
const uint CHUNKS = (CHANNELS + 15u) / 16u;
const uint OUT4 = OUT_CHANNELS / 4u;
const uint N_TILES = (OUT_CHANNELS + 15u) / 16u;
const uint MAX_N_TILES = 4;  // up to 64 output channels
const uint OUT_PADDED = N_TILES * 16u;
const uint PIXEL_UVEC2S = 6u;             // a staged pixel: 16 channels, then 16 bytes of padding
const uint OUT_STRIDE = OUT_PADDED + 8u;  // halves per row of weights and per pixel of outputs
const uint WEIGHT_HALVES = 9u * 16u * OUT_STRIDE;
const uint OUT_HALVES = TILE_W * TILE_H * OUT_STRIDE;

layout(set = 0, binding = 0, std430) readonly buffer In0 { uvec2 v[]; } b_in0;
layout(set = 0, binding = 1, std430) readonly buffer In1 { uvec2 v[]; } b_in1;
// Biases (and conv.comp's weights): float32, the bias of layer at params.bias_offset.
layout(set = 0, binding = 2, std430) readonly buffer Weights { vec4 v[]; } b_weights;
layout(set = 0, binding = 3, std430) writeonly buffer Out { uvec2 v[]; } b_out;
// Half-precision weights, eight per uvec4: per chunk and tap a row-major 16 x OUT_PADDED matrix
// (input channel by output channel, zero past the layer's channels).
layout(set = 0, binding = 4, std430) readonly buffer HalfWeights { uvec4 v[]; } b_half_weights;
layout(set = 0, binding = 5, std430) writeonly buffer Pooled { uvec2 v[]; } b_pooled;

layout(push_constant) uniform Params {
    uint width;          // output (and second input) size
    uint height;
    uint in0_width;      // first input size (half the output's when upsampled, rounded up)
    uint in0_height;
    uint bias_offset;    // this layer's bias, in vec4s of b_weights
    uint half_offset;    // this layer's weights, in uvec4s of b_half_weights
} params;

// 16 channels of each pixel of the haloed tile (four packed in a uvec2), pixel-major.
shared uvec2 s_input[HALO_PIXELS * PIXEL_UVEC2S];
// The chunk's weights (per tap, 16 rows of OUT_STRIDE), then the tile's outputs (pixel-major).
shared float16_t s_half[WEIGHT_HALVES > OUT_HALVES ? WEIGHT_HALVES : OUT_HALVES];

#define Half16 fcoopmatNV<16, gl_ScopeSubgroup, 16, 16>
#define Float16x16 fcoopmatNV<32, gl_ScopeSubgroup, 16, 16>

// Channels 4*c4..4*c4+3 of the input concatenation at `q`, packed (zero outside the image and past
// the last channel).
uvec2 input_channels(ivec2 q, uint c4) {
    if (any(lessThan(q, ivec2(0))) || q.x >= int(params.width) || q.y >= int(params.height)
        || c4 * 4u >= CHANNELS) {
        return uvec2(0u);
    }
    if (c4 < IN0_CHANNELS / 4u) {
        ivec2 q0 = IN0_UPSAMPLED ? min(q >> 1, ivec2(params.in0_width, params.in0_height) - 1) : q;
        return b_in0.v[tensor_index(q0, params.in0_width, IN0_CHANNELS / 4u, c4)];
    }
    return b_in1.v[tensor_index(q, params.width, IN1_CHANNELS / 4u, c4 - IN0_CHANNELS / 4u)];
}

void stage(uint chunk, ivec2 tile_origin) {
    for (uint i = gl_LocalInvocationIndex; i < HALO_PIXELS * 4u; i += gl_WorkGroupSize.x) {
        uint p = i / 4u;
        ivec2 q = tile_origin + ivec2(p % HALO_W, p / HALO_W) - 1;
        s_input[p * PIXEL_UVEC2S + i % 4u] = input_channels(q, chunk * 4u + i % 4u);
    }
    const uint ROW_UVEC4S = OUT_PADDED / 8u;
    uint first = params.half_offset + chunk * 9u * 16u * ROW_UVEC4S;
    for (uint i = gl_LocalInvocationIndex; i < 9u * 16u * ROW_UVEC4S; i += gl_WorkGroupSize.x) {
        uvec4 w = b_half_weights.v[first + i];
        uint at = (i / ROW_UVEC4S) * OUT_STRIDE + (i % ROW_UVEC4S) * 8u;
        for (uint k = 0u; k < 4u; ++k) {
            f16vec2 pair = unpackFloat2x16(w[k]);
            s_half[at + 2u * k] = pair.x;
            s_half[at + 2u * k + 1u] = pair.y;
        }
    }
}

// The tile's outputs after bias and ReLU, written out (and, rounded to half precision, back into
// s_half for the pooling).
void finish_outputs(ivec2 tile_origin) {
    uint bias = params.bias_offset;
    for (uint i = gl_LocalInvocationIndex; i < TILE_W * TILE_H * OUT4; i += gl_WorkGroupSize.x) {
        uint p = i / OUT4;
        uint o4 = i % OUT4;
        uint at = p * OUT_STRIDE + o4 * 4u;
        vec4 v = vec4(s_half[at], s_half[at + 1u], s_half[at + 2u], s_half[at + 3u]);
        v += b_weights.v[bias + o4];
        v = RELU ? max(v, vec4(0.0)) : v;
        uvec2 packed = pack_channels(v);
        ivec2 pixel = tile_origin + ivec2(p % TILE_W, p / TILE_W);
        if (pixel.x < int(params.width) && pixel.y < int(params.height)) {
            b_out.v[tensor_index(pixel, params.width, OUT4, o4)] = packed;
        }
        if (POOLED) {
            vec4 rounded = unpack_channels(packed);
            for (uint k = 0u; k < 4u; ++k) {
                s_half[at + k] = float16_t(rounded[k]);
            }
        }
    }
}

// 2x2 averages of the tile's outputs (the image's last row and column repeat at odd sizes, as in
// pool.comp): the tile origin is even, so every pooled pixel's sources are in this tile.
void write_pooled(ivec2 tile_origin) {
    uvec2 pooled_size = (uvec2(params.width, params.height) + 1u) / 2u;
    ivec2 last = ivec2(params.width, params.height) - 1;
    const uint PIXELS = (TILE_W / 2u) * (TILE_H / 2u);
    for (uint i = gl_LocalInvocationIndex; i < PIXELS * OUT4; i += gl_WorkGroupSize.x) {
        uint p = i / OUT4;
        uint o4 = i % OUT4;
        ivec2 pooled = tile_origin / 2 + ivec2(p % (TILE_W / 2u), p / (TILE_W / 2u));
        if (pooled.x >= int(pooled_size.x) || pooled.y >= int(pooled_size.y)) {
            continue;
        }
        vec4 sum = vec4(0.0);
        for (int d = 0; d < 4; ++d) {
            ivec2 local = min(pooled * 2 + ivec2(d & 1, d >> 1), last) - tile_origin;
            uint at = (uint(local.y) * TILE_W + uint(local.x)) * OUT_STRIDE + o4 * 4u;
            sum += vec4(s_half[at], s_half[at + 1u], s_half[at + 2u], s_half[at + 3u]);
        }
        b_pooled.v[tensor_index(pooled, pooled_size.x, OUT4, o4)] = pack_channels(0.25 * sum);
    }
}

void main() {
    ivec2 tile_origin = ivec2(gl_WorkGroupID.xy) * ivec2(TILE_W, TILE_H);
    uint first_row = gl_SubgroupID * ROWS;
    Float16x16 sums[MAX_ROWS][MAX_N_TILES];
    for (uint m = 0u; m < ROWS; ++m) {
        for (uint n = 0u; n < N_TILES; ++n) {
            sums[m][n] = Float16x16(0.0);
        }
    }
    for (uint chunk = 0u; chunk < CHUNKS; ++chunk) {
        stage(chunk, tile_origin);
        barrier();
        for (uint tap = 0u; tap < 9u; ++tap) {
            uint dx = tap % 3u;
            uint dy = tap / 3u;
            Half16 a[MAX_ROWS];
            for (uint m = 0u; m < ROWS; ++m) {
                uint halo_pixel = (first_row + m + dy) * HALO_W + dx;
                coopMatLoadNV(a[m], s_input, halo_pixel * PIXEL_UVEC2S, PIXEL_UVEC2S, false);
            }
            for (uint n = 0u; n < N_TILES; ++n) {
                Half16 b;
                coopMatLoadNV(b, s_half, tap * 16u * OUT_STRIDE + n * 16u, OUT_STRIDE, false);
                for (uint m = 0u; m < ROWS; ++m) {
                    sums[m][n] = coopMatMulAddNV(a[m], b, sums[m][n]);
                }
            }
        }
        barrier();
    }
    for (uint m = 0u; m < ROWS; ++m) {
        for (uint n = 0u; n < N_TILES; ++n) {
            uint at = (first_row + m) * TILE_W * OUT_STRIDE + n * 16u;
            coopMatStoreNV(Half16(sums[m][n]), s_half, at, OUT_STRIDE, false);
        }
    }
    barrier();
    finish_outputs(tile_origin);
    if (POOLED) {
        barrier();
        write_pooled(tile_origin);
    }
}
