#version 460
// The tensor-core twin of conv.comp: one 3x3 convolution (zero padding, fused bias and ReLU) as an
// implicit GEMM on NVIDIA cooperative matrices (GL_NV_cooperative_matrix, fp16 operands, fp32
// sums). Same inputs and output as conv.comp, so the two are interchangeable; optionally it also
// writes the output 2x2 average-pooled, and that pooled again (pool.comp's job, fused).
//
// A workgroup of eight subgroups computes a tile of 128 output pixels and GROUP_TILES x 16 of the
// output channels (the z of the dispatch picks which); each subgroup owns 16 of the pixels. For
// each group of 16 input channels (a chunk) it copies into shared memory the tile and its
// one-pixel halo, as the packed halves they are (reading the first input upsampled, or the skip
// connection in place, as conv.comp does), and the taps' half-precision weights for its output
// channels (passes/src/denoise/neural/network.rs packs them), uvec4 by uvec4; the next chunk's
// reads are issued into registers before this chunk's products run, so their latency hides behind
// them. Each tap multiplies (16 pixels x 16 channels) by (16 channels x 16 outputs) matrices, the
// first read straight out of the staged tile, shifted by the tap's offset. The sums go through
// shared memory once more (in the weights' place) for the bias, the ReLU and the pooling, and out
// as packed halves. Pixels in shared memory are padded by 16 bytes so that a matrix's rows fall
// in different banks.
//
// Two tile layouts:
// - plain: a 16 x 8 tile, subgroup s owning its row s.
// - FOLD (a decoder layer, whose first input is the level below upsampled by nearest neighbour):
//   a 32 x 4 tile, subgroup s owning the 16 pixels of row s / 2 whose x has the parity of s. A 3x3
//   convolution of a nearest-upsampled image is, for the output pixels of one parity class (x and
//   y parities), a 2x2 convolution of the image before upsampling with the 3x3 weights summed per
//   source pixel ("folded"): so the first input's chunks are staged at its own resolution (18 x 4
//   pixels) and take four taps instead of nine, the class's folded weights (network.rs packs the
//   four classes' after the nine taps). The skip connection's chunks take the nine taps on the
//   full-resolution tile, staged with even columns first then odd ones, so that a subgroup's
//   pixels, two apart in the image, are consecutive in shared memory. At odd sizes the fold is not
//   exact at the last column and row (the pixel past them lies in the image before upsampling), so
//   a workgroup whose tile holds them stages every chunk at full resolution with the nine taps.
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
layout(constant_id = 7) const uint POOL_LEVELS = 0;  // also write the output 2x2 pooled (1), then again (2)
layout(constant_id = 8) const uint GROUP_TILES = 4;  // 16-channel output tiles per workgroup
// The fold layout (IN0_UPSAMPLED layers only; IN0_CHANNELS a multiple of 16).
layout(constant_id = 10) const bool FOLD = false;

const uint THREADS = gl_WorkGroupSize.x;
const uint SUBGROUPS = THREADS / 32u;
const uint TILE_W = FOLD ? 32u : 16u;
const uint TILE_H = FOLD ? SUBGROUPS / 2u : SUBGROUPS;
const uint TILE_PIXELS = TILE_W * TILE_H;
const uint HALO_W = TILE_W + 2u;
const uint HALO_PIXELS = HALO_W * (TILE_H + 2u);
// The first input before upsampling under a FOLD tile, with its halo.
const uint LOW_W = TILE_W / 2u + 2u;
const uint LOW_PIXELS = LOW_W * (TILE_H / 2u + 2u);
const uint STAGED_PIXELS = HALO_PIXELS > LOW_PIXELS ? HALO_PIXELS : LOW_PIXELS;
const uint CHANNELS = IN0_CHANNELS + IN1_CHANNELS;
const uint CHUNKS = (CHANNELS + 15u) / 16u;
// Chunks of the first input that have folded weights.
const uint FOLD_CHUNKS = FOLD ? IN0_CHANNELS / 16u : 0u;
const uint TAPS = 9u;
// The folded weights: 4 parity classes x 4 taps.
const uint FOLDED = 16u;
const uint MAX_MATRICES = FOLD ? FOLDED : TAPS;
const uint OUT4 = OUT_CHANNELS / 4u;
const uint ALL_TILES = (OUT_CHANNELS + 15u) / 16u;
const uint N_TILES = ALL_TILES < GROUP_TILES ? ALL_TILES : GROUP_TILES;  // this workgroup's
const uint MAX_N_TILES = 4;  // up to 64 output channels
const uint OUT_PADDED = ALL_TILES * 16u;
const uint PIXEL_UVEC2S = 6u;             // a staged pixel: 16 channels, then 16 bytes of padding
const uint ROW_UVEC4S = OUT_PADDED / 8u;  // a row of a chunk's weights in the buffer
const uint MATRIX_UVEC4S = 16u * ROW_UVEC4S;  // one tap's weights in the buffer
const uint GROUP_ROW_UVEC4S = N_TILES * 2u;  // the part of a row this workgroup stages
const uint MATRIX_ROW = GROUP_ROW_UVEC4S + 1u;  // uvec4s per row of weights and per pixel of outputs
const uint STAGED_WEIGHT_UVEC4S = MAX_MATRICES * 16u * MATRIX_ROW;
const uint OUT_UVEC4S = TILE_PIXELS * MATRIX_ROW;
// What each invocation copies per chunk, at most.
const uint INPUT_LOADS = (STAGED_PIXELS * 4u + THREADS - 1u) / THREADS;
const uint WEIGHT_LOADS = (MAX_MATRICES * 16u * GROUP_ROW_UVEC4S + THREADS - 1u) / THREADS;

layout(set = 0, binding = 0, std430) readonly buffer In0 { uvec2 v[]; } b_in0;
layout(set = 0, binding = 1, std430) readonly buffer In1 { uvec2 v[]; } b_in1;
// Biases (and conv.comp's weights): float32, the bias of layer at params.bias_offset.
layout(set = 0, binding = 2, std430) readonly buffer Weights { vec4 v[]; } b_weights;
layout(set = 0, binding = 3, std430) writeonly buffer Out { uvec2 v[]; } b_out;
// Half-precision weights, eight per uvec4: per chunk and tap a row-major 16 x OUT_PADDED matrix
// (input channel by output channel, zero past the layer's channels); with FOLD, the first input's
// chunks have the 16 folded matrices after their nine taps.
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

// 16 channels of each staged pixel (four packed in a uvec2), pixel-major: the haloed tile (with
// FOLD, each row's even columns, then its odd ones), or with FOLD the first input's pixels under it.
shared uvec2 s_input[STAGED_PIXELS * PIXEL_UVEC2S];
// The chunk's weights as packed halves (per matrix, 16 rows of MATRIX_ROW), then the tile's
// outputs (per subgroup its 16 pixels, MATRIX_ROW per pixel).
shared uvec4 s_matrix[STAGED_WEIGHT_UVEC4S > OUT_UVEC4S ? STAGED_WEIGHT_UVEC4S : OUT_UVEC4S];

// This invocation's share of the next chunk, on its way from memory to shared memory.
uvec2 r_input[INPUT_LOADS];
uvec4 r_weights[WEIGHT_LOADS];

#define Half16 fcoopmatNV<16, gl_ScopeSubgroup, 16, 16>
#define Float16x16 fcoopmatNV<32, gl_ScopeSubgroup, 16, 16>

ivec2 tile_origin() {
    return ivec2(gl_WorkGroupID.xy) * ivec2(TILE_W, TILE_H);
}

// Whether this workgroup's first-input chunks take the folded weights: a FOLD layer's tile that
// holds neither an odd-sized image's last column nor its last row.
bool folded_group() {
    ivec2 end = tile_origin() + ivec2(TILE_W, TILE_H);
    return FOLD && (params.width % 2u == 0u || end.x < int(params.width))
        && (params.height % 2u == 0u || end.y < int(params.height));
}

// Whether `chunk` is staged at the first input's own resolution, with the folded weights.
bool low_chunk(uint chunk, bool folded) {
    return folded && chunk < FOLD_CHUNKS;
}

// The tile's pixel of shared-memory index `p` (subgroup p / 16 owns 16 consecutive indices).
ivec2 tile_pixel(uint p) {
    uint s = p / 16u;
    uint j = p % 16u;
    return FOLD ? ivec2(2u * j + (s & 1u), s >> 1u) : ivec2(j, s);
}

// The shared-memory index of the tile's pixel `local` (the inverse of tile_pixel).
uint tile_index(ivec2 local) {
    return FOLD ? (uint(local.y) * 2u + uint(local.x & 1)) * 16u + uint(local.x >> 1)
                : uint(local.y) * TILE_W + uint(local.x);
}

// The haloed tile's column staged at position `k` of its row.
int halo_column(uint k) {
    const uint EVEN = (HALO_W + 1u) / 2u;
    return FOLD ? int(k < EVEN ? 2u * k : 2u * (k - EVEN) + 1u) : int(k);
}

// The staged position of the haloed tile's column `c`.
uint halo_position(uint c) {
    const uint EVEN = (HALO_W + 1u) / 2u;
    return FOLD ? (c & 1u) * EVEN + (c >> 1u) : c;
}

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

// Channels 4*c4..4*c4+3 of the first input before upsampling at `q`, packed (zero outside it).
uvec2 low_channels(ivec2 q, uint c4) {
    if (any(lessThan(q, ivec2(0))) || q.x >= int(params.in0_width) || q.y >= int(params.in0_height)) {
        return uvec2(0u);
    }
    return b_in0.v[tensor_index(q, params.in0_width, IN0_CHANNELS / 4u, c4)];
}

// Where `chunk`'s weights start in b_half_weights, and how many matrices it stages.
uint chunk_weights(uint chunk, bool low, out uint matrices) {
    matrices = low ? FOLDED : TAPS;
    uint before = chunk < FOLD_CHUNKS ? chunk * (TAPS + FOLDED)
                                      : FOLD_CHUNKS * (TAPS + FOLDED) + (chunk - FOLD_CHUNKS) * TAPS;
    return params.half_offset + (before + (low ? TAPS : 0u)) * MATRIX_UVEC4S;
}

// Reads this invocation's share of `chunk` (the staged pixels' channels and the weights) into
// registers.
void fetch(uint chunk, bool folded) {
    ivec2 origin = tile_origin();
    bool low = low_chunk(chunk, folded);
    uint items = (low ? LOW_PIXELS : HALO_PIXELS) * 4u;
    for (uint j = 0u; j < INPUT_LOADS; ++j) {
        uint i = gl_LocalInvocationIndex + j * THREADS;
        if (i < items) {
            uint p = i / 4u;
            uint c4 = chunk * 4u + i % 4u;
            if (low) {
                r_input[j] = low_channels(origin / 2 + ivec2(p % LOW_W, p / LOW_W) - 1, c4);
            } else {
                ivec2 q = origin + ivec2(halo_column(p % HALO_W), p / HALO_W) - 1;
                r_input[j] = input_channels(q, c4);
            }
        }
    }
    uint matrices;
    uint first = chunk_weights(chunk, low, matrices) + gl_WorkGroupID.z * GROUP_ROW_UVEC4S;
    for (uint j = 0u; j < WEIGHT_LOADS; ++j) {
        uint i = gl_LocalInvocationIndex + j * THREADS;
        if (i < matrices * 16u * GROUP_ROW_UVEC4S) {
            uint row = i / GROUP_ROW_UVEC4S;
            r_weights[j] = b_half_weights.v[first + row * ROW_UVEC4S + i % GROUP_ROW_UVEC4S];
        }
    }
}

// Writes what `fetch` read for `chunk` into shared memory.
void stage(uint chunk, bool folded) {
    bool low = low_chunk(chunk, folded);
    uint items = (low ? LOW_PIXELS : HALO_PIXELS) * 4u;
    for (uint j = 0u; j < INPUT_LOADS; ++j) {
        uint i = gl_LocalInvocationIndex + j * THREADS;
        if (i < items) {
            s_input[(i / 4u) * PIXEL_UVEC2S + i % 4u] = r_input[j];
        }
    }
    uint matrices = low ? FOLDED : TAPS;
    for (uint j = 0u; j < WEIGHT_LOADS; ++j) {
        uint i = gl_LocalInvocationIndex + j * THREADS;
        if (i < matrices * 16u * GROUP_ROW_UVEC4S) {
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

// Output channels 4*o4..4*o4+3 (o4 counted from o4_first()) of the tile's pixel of index `p` in
// s_matrix, packed.
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
void finish_outputs(ivec2 origin) {
    uint bias = params.bias_offset + o4_first();
    uint group = group_out4();
    for (uint i = gl_LocalInvocationIndex; i < TILE_PIXELS * group; i += THREADS) {
        uint p = i / group;
        uint o4 = i % group;
        vec4 v = unpack_channels(staged_output(p, o4)) + b_weights.v[bias + o4];
        v = RELU ? max(v, vec4(0.0)) : v;
        uvec2 packed = pack_channels(v);
        ivec2 pixel = origin + tile_pixel(p);
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
void write_pooled(ivec2 origin) {
    uvec2 pooled_size = (uvec2(params.width, params.height) + 1u) / 2u;
    ivec2 last = ivec2(params.width, params.height) - 1;
    const uint PIXELS = (TILE_W / 2u) * (TILE_H / 2u);
    uint group = group_out4();
    for (uint i = gl_LocalInvocationIndex; i < PIXELS * group; i += THREADS) {
        uint p = i / group;
        uint o4 = i % group;
        ivec2 pooled = origin / 2 + ivec2(p % (TILE_W / 2u), p / (TILE_W / 2u));
        if (pooled.x >= int(pooled_size.x) || pooled.y >= int(pooled_size.y)) {
            continue;
        }
        vec4 sum = vec4(0.0);
        for (int d = 0; d < 4; ++d) {
            ivec2 local = min(pooled * 2 + ivec2(d & 1, d >> 1), last) - origin;
            sum += unpack_channels(staged_output(tile_index(local), o4));
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
void write_pooled_twice(ivec2 origin) {
    uvec2 pooled_size = (uvec2(params.width, params.height) + 1u) / 2u;
    uvec2 twice_size = (pooled_size + 1u) / 2u;
    ivec2 last = ivec2(pooled_size) - 1;
    ivec2 pooled_origin = origin / 2;
    const uint PIXELS = (TILE_W / 4u) * (TILE_H / 4u);
    uint group = group_out4();
    for (uint i = gl_LocalInvocationIndex; i < PIXELS * group; i += THREADS) {
        uint p = i / group;
        uint o4 = i % group;
        ivec2 twice = origin / 4 + ivec2(p % (TILE_W / 4u), p / (TILE_W / 4u));
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

// Adds the products of the staged pixel rows starting at `first` (this subgroup's 16 pixels, one
// staged pixel apart) with staged weight matrix `matrix` to the sums.
void multiply(uint first, uint matrix, inout Float16x16 sums[MAX_N_TILES]) {
    Half16 a;
    coopMatLoadNV(a, s_input, first * PIXEL_UVEC2S, PIXEL_UVEC2S, false);
    for (uint n = 0u; n < N_TILES; ++n) {
        Half16 b;
        coopMatLoadNV(b, s_matrix, matrix * 16u * MATRIX_ROW + n * 2u, MATRIX_ROW, false);
        sums[n] = coopMatMulAddNV(a, b, sums[n]);
    }
}

void main() {
    ivec2 origin = tile_origin();
    bool folded = folded_group();
    uint s = gl_SubgroupID;
    // The subgroup's row of the tile and, with FOLD, the x parity of its pixels.
    uint row = FOLD ? s >> 1u : s;
    uint parity = FOLD ? s & 1u : 0u;
    Float16x16 sums[MAX_N_TILES];
    for (uint n = 0u; n < N_TILES; ++n) {
        sums[n] = Float16x16(0.0);
    }
    fetch(0u, folded);
    for (uint chunk = 0u; chunk < CHUNKS; ++chunk) {
        stage(chunk, folded);
        barrier();
        // The next chunk's reads are under way while this one's products run.
        if (chunk + 1u < CHUNKS) {
            fetch(chunk + 1u, folded);
        }
        if (low_chunk(chunk, folded)) {
            // The 2x2 taps of the class (row parity, x parity): the pixels before upsampling at
            // offsets parity + t - 1 from this subgroup's (row / 2, j) in each direction.
            uint row_parity = row & 1u;
            for (uint t = 0u; t < 4u; ++t) {
                uint low_row = (row >> 1u) + row_parity + t / 2u;
                uint matrix = (row_parity * 2u + parity) * 4u + t;
                multiply(low_row * LOW_W + parity + t % 2u, matrix, sums);
            }
        } else {
            for (uint tap = 0u; tap < TAPS; ++tap) {
                uint dx = tap % 3u;
                uint dy = tap / 3u;
                multiply((row + dy) * HALO_W + halo_position(parity + dx), tap, sums);
            }
        }
        barrier();
    }
    for (uint n = 0u; n < N_TILES; ++n) {
        coopMatStoreNV(Half16(sums[n]), s_matrix, s * 16u * MATRIX_ROW + n * 2u, MATRIX_ROW, false);
    }
    barrier();
    finish_outputs(origin);
    if (POOL_LEVELS > 0u) {
        barrier();
        write_pooled(origin);
    }
    if (POOL_LEVELS > 1u) {
        barrier();
        write_pooled_twice(origin);
    }
}
