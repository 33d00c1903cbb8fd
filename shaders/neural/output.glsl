// The learned denoiser's output (training/model.py, end of `step`): the network's log radiance
// blended with the reprojected history by the mask times a learned weight, kept for the next frame,
// and re-modulated by the first hits' albedo plus emission averaged over time (features.comp). The
// direct decoder's log radiance and blend weight are the output layer's channels 0-3. The
// kernel-predicting decoder's (KERNEL; training/kernel_model.py, `KernelOutput`) are computed here
// from its heads' outputs: the full scale's log radiance (the input features' channels 0-2)
// filtered by its kernels (kernel.glsl), composited (`combine`) with the half scale's detail,
//   half detail = half filtered + sigmoid(half a) * up(quarter detail) - pool(full filtered),
// by channel 25 of the full scale's head (a), its blend weight channel 26. A workgroup filters the
// full scale over its tile and the margin that the half scale's detail under the tile pools (in
// shared memory, float32), then that detail, then composites; the half scale's filtered radiance
// and the quarter's detail come from kernel_filter.comp. With LINEAR_MIX (kernel.glsl) all of this
// runs in linear space too (the coarser scales' buffers hold both results a pixel), and the
// head's channel 27 (m) mixes the two: log + sigmoid(m) * (log(1 + max(linear, 0)) - log).
// With ATROUS_GATE (output_atrous.comp) the pass writes the output's illumination, exp(log) - 1,
// and the sigmoid of the output layer's last channel (GATE_CHANNEL, the gate) instead of the
// re-modulated radiance: atrous_step.glsl filters the illumination further, and its last step
// blends it in by the gate and re-modulates (training/model.py, `atrous`). The includer defines
// the version.
#include "common/image_coords.glsl"
#include "neural/tensor.glsl"
#include "neural/kernel.glsl"
#include "neural/upsample.glsl"

// A tile of TILE x TILE pixels a workgroup.
const int TILE = 16;
layout(local_size_x = TILE, local_size_y = TILE) in;

layout(constant_id = 0) const bool KERNEL = false;
layout(constant_id = 1) const uint NET_CHANNELS = 4;  // the output layer's channels, padded to 4
layout(constant_id = 2) const uint HALF_CHANNELS = 28;  // the half scale's head's, padded to 4

layout(set = 0, binding = 1, std430) readonly buffer Features { uvec2 v[]; } b_features;
layout(set = 0, binding = 2, std430) readonly buffer Net { uvec2 v[]; } b_net;
// The output's log radiance for the next frame, as packed halves: an rgba16f image store may
// truncate instead of rounding (passes/src/denoise/neural/mod.rs).
layout(set = 0, binding = 3, rg32ui) uniform writeonly uimage2D u_output;
#ifdef ATROUS_GATE
// The output's illumination (rgb) and its gate (a).
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D u_illumination;
layout(constant_id = 3) const uint GATE_CHANNEL = 4;  // the output layer's channel of the gate
#else
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D u_radiance;
#endif
// The kernel decoder's half scale: its head's output, its filtered radiance; the quarter scale's
// detail (float32 rgb).
layout(set = 0, binding = 5, std430) readonly buffer HalfLogits { uvec2 v[]; } b_half_logits;
layout(set = 0, binding = 6, std430) readonly buffer HalfFiltered { vec4 v[]; } b_half_filtered;
layout(set = 0, binding = 7, std430) readonly buffer QuarterDetail { vec4 v[]; } b_quarter_detail;
// The first hits' albedo and log(1 + emission) averaged over time (`antialias_surface`).
layout(set = 0, binding = 8, rgba32f) uniform readonly image2D u_albedo_mean;
layout(set = 0, binding = 9, rgba32f) uniform readonly image2D u_emission_mean;

layout(push_constant) uniform Params {
    uint width;
    uint height;
} params;

const uint BLEND_CHANNEL = 25u;  // a, the weight of the coarser scale's detail

// The half scale's pixels whose detail the tile's bilinear taps read: from one before the tile's
// first (tile / 2 - 1) on; and the full scale's pixels they pool.
const int HALF_REGION = TILE / 2 + 2;
const int FULL_REGION = 2 * HALF_REGION;
// Index 0 the log space's, 1 the linear space's (LINEAR_MIX).
shared vec3 s_filtered[2][FULL_REGION][FULL_REGION];
shared vec3 s_half_detail[2][HALF_REGION][HALF_REGION];

// The vec4s a pixel of the half scale's filtered radiance and the quarter's detail holds.
const int RESULTS = LINEAR_MIX ? 2 : 1;

vec4 kernel_logits(ivec2 pixel, uint c4) {
    return unpack_channels(b_net.v[tensor_index(pixel, params.width, NET_CHANNELS / 4u, c4)]);
}

vec3 kernel_radiance(ivec2 q) {
    return unpack_channels(b_features.v[tensor_index(q, params.width, FEATURE_GROUPS, 0u)]).rgb;
}

// Where result `k` (0 log, 1 linear) of `pixel` lies in a coarser scale's buffer `width` wide.
int result_index(ivec2 pixel, int width, int k) {
    return (pixel.y * width + pixel.x) * RESULTS + k;
}

// The quarter scale's detail (result `k`) bilinearly upsampled to `pixel` of the half scale.
vec3 upsampled_quarter(ivec2 pixel, ivec2 half_size, int k) {
    ivec2 coarse = (half_size + 1) / 2;
    ivec2 i0, i1;
    vec2 f;
    bilinear_taps(pixel, half_size, coarse, i0, i1, f);
    vec3 c00 = b_quarter_detail.v[result_index(i0, coarse.x, k)].rgb;
    vec3 c01 = b_quarter_detail.v[result_index(ivec2(i1.x, i0.y), coarse.x, k)].rgb;
    vec3 c10 = b_quarter_detail.v[result_index(ivec2(i0.x, i1.y), coarse.x, k)].rgb;
    vec3 c11 = b_quarter_detail.v[result_index(i1, coarse.x, k)].rgb;
    return bilinear_mix(c00, c01, c10, c11, f);
}

// Fills s_filtered (the full scale filtered) and then s_half_detail over the workgroup's regions,
// from `full_origin` and `half_origin`. Every invocation of the workgroup calls it (barriers).
void filter_tile(ivec2 full_origin, ivec2 half_origin) {
    ivec2 size = ivec2(params.width, params.height);
    ivec2 half_size = (size + 1) / 2;
    uint local = gl_LocalInvocationIndex;
    for (uint i = local; i < uint(FULL_REGION * FULL_REGION); i += uint(TILE * TILE)) {
        ivec2 r = ivec2(i % uint(FULL_REGION), i / uint(FULL_REGION));
        ivec2 q = full_origin + r;
        if (all(greaterThanEqual(q, ivec2(0))) && pixel_in_bounds(q, size)) {
            KernelMeans means = apply_kernel(q, size);
            s_filtered[0][r.y][r.x] = means.log_mean;
            if (LINEAR_MIX) {
                s_filtered[1][r.y][r.x] = means.linear_mean;
            }
        }
    }
    barrier();
    if (local < uint(HALF_REGION * HALF_REGION)) {
        ivec2 r = ivec2(local % uint(HALF_REGION), local / uint(HALF_REGION));
        ivec2 h = half_origin + r;
        if (all(greaterThanEqual(h, ivec2(0))) && pixel_in_bounds(h, half_size)) {
            uint at = tensor_index(h, uint(half_size.x), HALF_CHANNELS / 4u, BLEND_CHANNEL / 4u);
            float a = unpack_channels(b_half_logits.v[at])[BLEND_CHANNEL % 4u];
            for (int k = 0; k < RESULTS; ++k) {
                vec3 detail = b_half_filtered.v[result_index(h, half_size.x, k)].rgb;
                detail += upsampled_quarter(h, half_size, k) / (1.0 + exp(-a));
                vec3 pooled = vec3(0.0);
                for (int i = 0; i < 4; ++i) {
                    ivec2 q = min(h * 2 + ivec2(i & 1, i >> 1), size - 1) - full_origin;
                    pooled += s_filtered[k][q.y][q.x];
                }
                s_half_detail[k][r.y][r.x] = detail - 0.25 * pooled;
            }
        }
    }
    barrier();
}

// Result `k` of the kernel decoder at `pixel` (before rounding): filtered + sigmoid(a) * up(half
// detail), from the workgroup's regions.
vec3 composited(ivec2 pixel, float a, ivec2 full_origin, ivec2 half_origin, int k) {
    ivec2 size = ivec2(params.width, params.height);
    ivec2 i0, i1;
    vec2 f;
    bilinear_taps(pixel, size, (size + 1) / 2, i0, i1, f);
    i0 -= half_origin;
    i1 -= half_origin;
    vec3 up = bilinear_mix(s_half_detail[k][i0.y][i0.x], s_half_detail[k][i0.y][i1.x],
                           s_half_detail[k][i1.y][i0.x], s_half_detail[k][i1.y][i1.x], f);
    ivec2 r = pixel - full_origin;
    return s_filtered[k][r.y][r.x] + up / (1.0 + exp(-a));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = uvec2(params.width, params.height);
    ivec2 half_origin = ivec2(gl_WorkGroupID.xy) * (TILE / 2) - 1;
    ivec2 full_origin = half_origin * 2;
    if (KERNEL) {
        filter_tile(full_origin, half_origin);
    }
    if (!pixel_in_bounds(pixel, ivec2(size))) {
        return;
    }
    uint at = tensor_index(pixel, params.width, FEATURE_GROUPS, 0u);
    vec4 f2 = unpack_channels(b_features.v[at + 2u]);
    vec4 f3 = unpack_channels(b_features.v[at + 3u]);
    vec3 warped = vec3(f2.w, f3.xy);
    float mask = f3.z;
    vec3 predicted;
    float blend_logit;
    if (KERNEL) {
        // Channels 24-27: the last kernel tap, the compositing weight, the blend weight, the linear
        // mix (LINEAR_MIX; else the gate with ATROUS_GATE, or padding).
        vec4 o = kernel_logits(pixel, 6u);
        vec3 radiance = composited(pixel, o.y, full_origin, half_origin, 0);
        if (LINEAR_MIX) {
            vec3 linear = composited(pixel, o.y, full_origin, half_origin, 1);
            float m = 1.0 / (1.0 + exp(-o.w));
            radiance += m * (log(vec3(1.0) + max(linear, vec3(0.0))) - radiance);
        }
        predicted = unpack_channels(pack_channels(vec4(radiance, 0.0))).rgb;
        blend_logit = o.z;
    } else {
        vec4 o = kernel_logits(pixel, 0u);
        predicted = o.rgb;
        blend_logit = o.w;
    }
    float blend = mask / (1.0 + exp(-blend_logit));
    vec3 log_out = max(predicted * (1.0 - blend) + warped * blend, vec3(0.0));
    uvec2 packed_out = pack_channels(vec4(log_out, 0.0));
    log_out = unpack_channels(packed_out).rgb;
    imageStore(u_output, pixel, uvec4(packed_out, 0u, 0u));
#ifdef ATROUS_GATE
    float gate_logit = kernel_logits(pixel, GATE_CHANNEL / 4u)[GATE_CHANNEL % 4u];
    imageStore(u_illumination, pixel, vec4(exp(log_out) - 1.0, 1.0 / (1.0 + exp(-gate_logit))));
#else
    vec3 albedo = imageLoad(u_albedo_mean, pixel).rgb;
    vec3 emission = exp(imageLoad(u_emission_mean, pixel).rgb) - 1.0;
    imageStore(u_radiance, pixel, vec4((exp(log_out) - 1.0) * albedo + emission, 1.0));
#endif
}
