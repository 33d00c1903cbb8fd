#version 460
// The tensor-core twin of conv.comp: one 3x3 convolution (zero padding, fused bias and ReLU) as an
// implicit GEMM on NVIDIA cooperative matrices (GL_NV_cooperative_matrix, fp16 operands, fp32
// sums). Same inputs and output as conv.comp, so the two are interchangeable; optionally it also
// writes the output 2x2 average-pooled, and that pooled again (pool.comp's job, fused).
//
// A workgroup computes a 16 x TILE_H tile of output pixels and GROUP_TILES x 16 of the output
// channels (the z of the dispatch picks which). For each group of 16 input channels it copies into
// shared memory the tile and its one-pixel halo, as the packed halves they are (reading the first
// input upsampled, or the skip connection in place, as conv.comp does), and the nine taps'
// half-precision weights for its output channels (passes/src/denoise/neural/network.rs packs
// them), uvec4 by uvec4; the next group's reads are issued into registers before this group's
// products run, so their latency hides behind them. Each tap multiplies (16 pixels x 16 channels)
// by (16 channels x 16 outputs) matrices, the first read straight out of the staged tile, shifted
// by the tap's offset. Each subgroup owns ROWS rows of the tile and walks the taps column by
// column: the ROWS + 2 staged rows a column's taps read are loaded once for all of them, and each
// tap's weights once for all its rows (ROWS = 2: 30 matrix loads for 36 products, against 27 for
// 18 with one row a subgroup). The sums go through shared memory once more (in the weights' place)
// for the bias, the ReLU and the pooling, and out as packed halves. Rows in shared memory are
// padded by 16 bytes so that a matrix's rows fall in different banks.
#extension GL_NV_cooperative_matrix : require
#extension GL_KHR_memory_scope_semantics : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_EXT_shader_explicit_arithmetic_types_float16 : require
#include "neural/tensor.glsl"

layout(local_size_x = 256, local_size_x_id = 9) in;  // 32 invocations per subgroup

layout(constant_id = 0) const uint IN0_CHANNELS = 16;
layout(constant_id = 1) const uint IN1_CHANNELS = 0;
layout(constant_id = 2) const uint OUT_CHANNELS = 16;
layout(constant_id = 4) const bool IN0_UPSAMPLED = false;
layout(constant_id = 5) const bool RELU = true;
layout(constant_id = 6) const uint ROWS = 1;  // tile rows per subgroup: 1 to 4
layout(constant_id = 7) const uint POOL_LEVELS = 0;  // also write the output 2x2 pooled (1), then again (2)
layout(constant_id = 8) const uint GROUP_TILES = 4;  // 16-channel output tiles per workgroup

const uint THREADS = gl_WorkGroupSize.x;
const uint SUBGROUPS = THREADS / 32u;
const uint TILE_W = 16;
const uint TILE_H = SUBGROUPS * ROWS;
const uint MAX_ROWS = 4;
const uint HALO_W = TILE_W + 2u;
const uint HALO_PIXELS = HALO_W * (TILE_H + 2u);
const uint CHANNELS = IN0_CHANNELS + IN1_CHANNELS;
const uint CHUNKS = (CHANNELS + 15u) / 16u;
const uint OUT4 = OUT_CHANNELS / 4u;
const uint ALL_TILES = (OUT_CHANNELS + 15u) / 16u;
const uint N_TILES = ALL_TILES < GROUP_TILES ? ALL_TILES : GROUP_TILES;  // this workgroup's
const uint MAX_N_TILES = 4;  // up to 64 output channels
const uint OUT_PADDED = ALL_TILES * 16u;
const uint PIXEL_UVEC2S = 6u;             // a staged pixel: 16 channels, then 16 bytes of padding
const uint ROW_UVEC4S = OUT_PADDED / 8u;  // a row of a chunk's weights in the buffer
const uint GROUP_ROW_UVEC4S = N_TILES * 2u;  // the part of a row this workgroup stages
const uint MATRIX_ROW = GROUP_ROW_UVEC4S + 1u;  // uvec4s per row of weights and per pixel of outputs
const uint WEIGHT_UVEC4S = 9u * 16u * ROW_UVEC4S;
const uint GROUP_WEIGHT_UVEC4S = 9u * 16u * GROUP_ROW_UVEC4S;
const uint STAGED_WEIGHT_UVEC4S = 9u * 16u * MATRIX_ROW;
const uint OUT_UVEC4S = TILE_W * TILE_H * MATRIX_ROW;
const uint INPUT_ITEMS = HALO_PIXELS * 4u;
// What each invocation copies per chunk.
const uint INPUT_LOADS = (INPUT_ITEMS + THREADS - 1u) / THREADS;
const uint WEIGHT_LOADS = (GROUP_WEIGHT_UVEC4S + THREADS - 1u) / THREADS;

layout(set = 0, binding = 0, std430) readonly buffer In0 { uvec2 v[]; } b_in0;
layout(set = 0, binding = 1, std430) readonly buffer In1 { uvec2 v[]; } b_in1;
// Biases (and conv.comp's weights): float32, the bias of layer at params.bias_offset.
layout(set = 0, binding = 2, std430) readonly buffer Weights { vec4 v[]; } b_weights;
layout(set = 0, binding = 3, std430) writeonly buffer Out { uvec2 v[]; } b_out;
// Half-precision weights, eight per uvec4: per chunk and tap a row-major 16 x OUT_PADDED matrix
// (input channel by output channel, zero past the layer's channels).
layout(set = 0, binding = 4, std430) readonly buffer HalfWeights { uvec4 v[]; } b_half_weights;
layout(set = 0, binding = 5, std430) writeonly buffer Pooled { uvec2 v[]; } b_pooled;
layout(set = 0, binding = 6, std430) writeonly buffer PooledTwice { uvec2 v[]; } b_pooled_twice;

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
// The chunk's weights as packed halves (per tap, 16 rows of MATRIX_ROW), then the tile's outputs
// (pixel-major, MATRIX_ROW per pixel).
shared uvec4 s_matrix[STAGED_WEIGHT_UVEC4S > OUT_UVEC4S ? STAGED_WEIGHT_UVEC4S : OUT_UVEC4S];

// This invocation's share of the next chunk, on its way from memory to shared memory.
uvec2 r_input[INPUT_LOADS];
uvec4 r_weights[WEIGHT_LOADS];

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

// Reads this invocation's share of `chunk` (the haloed tile's channels and the weights) into
// registers.
void fetch(uint chunk, ivec2 tile_origin) {
    for (uint j = 0u; j < INPUT_LOADS; ++j) {
        uint i = gl_LocalInvocationIndex + j * gl_WorkGroupSize.x;
        if (i < INPUT_ITEMS) {
            uint p = i / 4u;
            ivec2 q = tile_origin + ivec2(p % HALO_W, p / HALO_W) - 1;
            r_input[j] = input_channels(q, chunk * 4u + i % 4u);
        }
    }
    uint first = params.half_offset + chunk * WEIGHT_UVEC4S + gl_WorkGroupID.z * GROUP_ROW_UVEC4S;
    for (uint j = 0u; j < WEIGHT_LOADS; ++j) {
        uint i = gl_LocalInvocationIndex + j * gl_WorkGroupSize.x;
        if (i < GROUP_WEIGHT_UVEC4S) {
            uint row = i / GROUP_ROW_UVEC4S;
            r_weights[j] = b_half_weights.v[first + row * ROW_UVEC4S + i % GROUP_ROW_UVEC4S];
        }
    }
}

// Writes what `fetch` read into shared memory.
void stage() {
    for (uint j = 0u; j < INPUT_LOADS; ++j) {
        uint i = gl_LocalInvocationIndex + j * gl_WorkGroupSize.x;
        if (i < INPUT_ITEMS) {
            s_input[(i / 4u) * PIXEL_UVEC2S + i % 4u] = r_input[j];
        }
    }
    for (uint j = 0u; j < WEIGHT_LOADS; ++j) {
        uint i = gl_LocalInvocationIndex + j * gl_WorkGroupSize.x;
        if (i < GROUP_WEIGHT_UVEC4S) {
            s_matrix[(i / GROUP_ROW_UVEC4S) * MATRIX_ROW + i % GROUP_ROW_UVEC4S] = r_weights[j];
        }
    }
}

// The first group of four output channels this workgroup computes.
uint o4_first() {
    return gl_WorkGroupID.z * N_TILES * 4u;
}

// How many groups of four output channels this workgroup computes.
uint group_out4() {
    return min(N_TILES * 4u, OUT4 - o4_first());
}

// Output channels 4*o4..4*o4+3 (o4 counted from o4_first()) of the tile's pixel `p` in s_matrix,
// packed.
uint staged_at(uint p, uint o4) {
    return p * MATRIX_ROW + o4 / 2u;
}

uvec2 staged_output(uint p, uint o4) {
    uint at = staged_at(p, o4);
    uint c = (o4 % 2u) * 2u;
    return uvec2(s_matrix[at][c], s_matrix[at][c + 1u]);
}

// The tile's outputs after bias and ReLU, written out (and, rounded to half precision, back into
// s_matrix for the pooling).
void finish_outputs(ivec2 tile_origin) {
    uint bias = params.bias_offset + o4_first();
    uint group = group_out4();
    for (uint i = gl_LocalInvocationIndex; i < TILE_W * TILE_H * group; i += gl_WorkGroupSize.x) {
        uint p = i / group;
        uint o4 = i % group;
        vec4 v = unpack_channels(staged_output(p, o4)) + b_weights.v[bias + o4];
        v = RELU ? max(v, vec4(0.0)) : v;
        uvec2 packed = pack_channels(v);
        ivec2 pixel = tile_origin + ivec2(p % TILE_W, p / TILE_W);
        if (pixel.x < int(params.width) && pixel.y < int(params.height)) {
            b_out.v[tensor_index(pixel, params.width, OUT4, o4_first() + o4)] = packed;
        }
        if (POOL_LEVELS > 0u) {
            uint at = staged_at(p, o4);
            uint c = (o4 % 2u) * 2u;
            s_matrix[at][c] = packed.x;
            s_matrix[at][c + 1u] = packed.y;
        }
    }
}

// 2x2 averages of the tile's outputs (the image's last row and column repeat at odd sizes, as in
// pool.comp): the tile origin is even, so every pooled pixel's sources are in this tile. With a
// second level, the pooled tile is kept (packed, pixel-major) in s_input for it.
void write_pooled(ivec2 tile_origin) {
    uvec2 pooled_size = (uvec2(params.width, params.height) + 1u) / 2u;
    ivec2 last = ivec2(params.width, params.height) - 1;
    const uint PIXELS = (TILE_W / 2u) * (TILE_H / 2u);
    uint group = group_out4();
    for (uint i = gl_LocalInvocationIndex; i < PIXELS * group; i += gl_WorkGroupSize.x) {
        uint p = i / group;
        uint o4 = i % group;
        ivec2 pooled = tile_origin / 2 + ivec2(p % (TILE_W / 2u), p / (TILE_W / 2u));
        if (pooled.x >= int(pooled_size.x) || pooled.y >= int(pooled_size.y)) {
            continue;
        }
        vec4 sum = vec4(0.0);
        for (int d = 0; d < 4; ++d) {
            ivec2 local = min(pooled * 2 + ivec2(d & 1, d >> 1), last) - tile_origin;
            sum += unpack_channels(staged_output(uint(local.y) * TILE_W + uint(local.x), o4));
        }
        uvec2 packed = pack_channels(0.25 * sum);
        b_pooled.v[tensor_index(pooled, pooled_size.x, OUT4, o4_first() + o4)] = packed;
        if (POOL_LEVELS > 1u) {
            s_input[p * N_TILES * 4u + o4] = packed;
        }
    }
}

// The pooled tile pooled once more (its origin is a multiple of 4 in the image: every source is in
// this tile again).
void write_pooled_twice(ivec2 tile_origin) {
    uvec2 pooled_size = (uvec2(params.width, params.height) + 1u) / 2u;
    uvec2 twice_size = (pooled_size + 1u) / 2u;
    ivec2 last = ivec2(pooled_size) - 1;
    ivec2 pooled_origin = tile_origin / 2;
    const uint PIXELS = (TILE_W / 4u) * (TILE_H / 4u);
    uint group = group_out4();
    for (uint i = gl_LocalInvocationIndex; i < PIXELS * group; i += gl_WorkGroupSize.x) {
        uint p = i / group;
        uint o4 = i % group;
        ivec2 twice = tile_origin / 4 + ivec2(p % (TILE_W / 4u), p / (TILE_W / 4u));
        if (twice.x >= int(twice_size.x) || twice.y >= int(twice_size.y)) {
            continue;
        }
        vec4 sum = vec4(0.0);
        for (int d = 0; d < 4; ++d) {
            ivec2 local = min(twice * 2 + ivec2(d & 1, d >> 1), last) - pooled_origin;
            sum += unpack_channels(s_input[(uint(local.y) * (TILE_W / 2u) + uint(local.x)) * N_TILES * 4u + o4]);
        }
        b_pooled_twice.v[tensor_index(twice, twice_size.x, OUT4, o4_first() + o4)] = pack_channels(0.25 * sum);
    }
}

// Adds tap (dx, dy)'s products for this subgroup's rows to `acc`, `a` holding the staged tile's
// rows from this subgroup's first row (shifted by dx), so row m's tap reads a[m + dy].
void tap_products(uint dx, uint dy, Half16 a[MAX_ROWS + 2u], inout Float16x16 acc[MAX_ROWS][MAX_N_TILES]) {
    uint tap = dy * 3u + dx;
    for (uint n = 0u; n < N_TILES; ++n) {
        Half16 b;
        coopMatLoadNV(b, s_matrix, tap * 16u * MATRIX_ROW + n * 2u, MATRIX_ROW, false);
        for (uint m = 0u; m < ROWS; ++m) {
            acc[m][n] = coopMatMulAddNV(a[m + dy], b, acc[m][n]);
        }
    }
}

// Adds the three taps of column offset dx: the ROWS + 2 shifted rows they read are loaded once,
// each serving every tap and row that reads it.
void column_products(uint dx, uint first_row, inout Float16x16 acc[MAX_ROWS][MAX_N_TILES]) {
    Half16 a[MAX_ROWS + 2u];
    for (uint r = 0u; r < ROWS + 2u; ++r) {
        uint halo_pixel = (first_row + r) * HALO_W + dx;
        coopMatLoadNV(a[r], s_input, halo_pixel * PIXEL_UVEC2S, PIXEL_UVEC2S, false);
    }
    // Written out: as a loop the driver does not unroll it (2.42 ms against 2.30 at 1080p).
    tap_products(dx, 0u, a, acc);
    tap_products(dx, 1u, a, acc);
    tap_products(dx, 2u, a, acc);
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
    fetch(0u, tile_origin);
    for (uint chunk = 0u; chunk < CHUNKS; ++chunk) {
        stage();
        barrier();
        // The next chunk's reads are under way while this one's products run.
        if (chunk + 1u < CHUNKS) {
            fetch(chunk + 1u, tile_origin);
        }
        column_products(0u, first_row, sums);
        column_products(1u, first_row, sums);
        column_products(2u, first_row, sums);
        barrier();
    }
    for (uint m = 0u; m < ROWS; ++m) {
        for (uint n = 0u; n < N_TILES; ++n) {
            uint at = (first_row + m) * TILE_W * MATRIX_ROW + n * 2u;
            coopMatStoreNV(Half16(sums[m][n]), s_matrix, at, MATRIX_ROW, false);
        }
    }
    barrier();
    finish_outputs(tile_origin);
    if (POOL_LEVELS > 0u) {
        barrier();
        write_pooled(tile_origin);
    }
    if (POOL_LEVELS > 1u) {
        barrier();
        write_pooled_twice(tile_origin);
    }
}
