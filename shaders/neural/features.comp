#version 460
// The learned denoiser's 24 input channels (training/model.py, `features`): log radiance, albedo,
// normal, roughness, log depth, last frame's output reprojected by the motion vectors where the
// surface is the same (`warp_history`), the reprojection mask, then the running mean of the noisy
// radiance (`accumulate`, reprojected with the same taps): log(1 + mean), its history length /
// N_MAX and log(1 + the standard deviation of luminance), then the running mean of the radiance
// range-compressed against fireflies (`compress`): log(1 + its mean expanded back) and the
// standard deviation of its luminance; where the history is shorter than the weights file's
// `spatial_variance_frames`, both deviations are this frame's over the pixel's 3x3 neighbourhood
// (`neighbourhood_variance`). Also writes this frame's surface (depth, normal), running
// means and second moments for the next frame, and the first hits' albedo and log(1 + emission)
// averaged over time with those of the same taps that saw the same object (`antialias_surface`;
// the object id kept in the emission's alpha; the emission supersampled at emitters' edges weighs
// more as it moves, edge_emission.glsl), which output.comp re-modulates by.
// Reads the frame's inputs from the light transport's and the G-buffer's images (inputs.glsl).
// With POOLED_LEVELS (the kernel-predicting decoder's coarser scales, 2 to 4;
// training/kernel_model.py, `KernelOutput`), also the demodulated radiance (negative values
// clamped) 2x2 average-pooled up to three times, in linear space, then log(1 + x) rounded to half
// precision, as kernel_filter.comp filters it at the half, quarter (and eighth) scales; odd edges
// repeat the last pixel of each level, as pool.comp does. With a fourth level, the eighth's linear
// means too, which radiance_pool.comp pools to the sixteenth.
#include "common/image_coords.glsl"
#include "common/math.glsl"
#define INPUTS_BINDING 16
#include "neural/inputs.glsl"
#include "edge_emission/edge_emission.glsl"
#include "neural/tensor.glsl"

// An 8x8 tile of pixels a workgroup: its 4x4 pixels of half, 2x2 of quarter and one of eighth
// resolution are pooled from it alone.
layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const uint POOLED_LEVELS = 0;

// The last frame's output: its log radiance as packed halves (`pack_channels`), exact.
layout(set = 0, binding = 0, rg32ui) uniform readonly uimage2D u_prev_output;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D u_prev_surface;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D u_surface;
layout(set = 0, binding = 3, std430) writeonly buffer Features { uvec2 v[]; } b_features;
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D u_prev_accum;
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2D u_accum;
layout(set = 0, binding = 6, r32f) uniform readonly image2D u_prev_moment;
layout(set = 0, binding = 7, r32f) uniform writeonly image2D u_moment;
layout(set = 0, binding = 8, rgba32f) uniform readonly image2D u_prev_robust;
layout(set = 0, binding = 9, rgba32f) uniform writeonly image2D u_robust;
layout(set = 0, binding = 10, rgba32f) uniform readonly image2D u_prev_albedo_mean;
layout(set = 0, binding = 11, rgba32f) uniform writeonly image2D u_albedo_mean;
layout(set = 0, binding = 12, rgba32f) uniform readonly image2D u_prev_emission_mean;
layout(set = 0, binding = 13, rgba32f) uniform writeonly image2D u_emission_mean;
// The pooled log radiance (POOLED_LEVELS), rgb of a vec4 a pixel of half, quarter and eighth
// resolution, and the eighth's linear means (POOLED_LEVELS 4).
layout(set = 0, binding = 14, std430) writeonly buffer RadianceHalf { vec4 v[]; } b_radiance_half;
layout(set = 0, binding = 15, std430) writeonly buffer RadianceQuarter {
    vec4 v[];
} b_radiance_quarter;
layout(set = 0, binding = 23, std430) writeonly buffer RadianceEighth { vec4 v[]; } b_radiance_eighth;
layout(set = 0, binding = 24, std430) writeonly buffer RadianceEighthLinear {
    vec4 v[];
} b_radiance_eighth_linear;
// The G-buffer's ids: object (x), material, primitive, hit flag.
layout(set = 0, binding = 22, rgba32ui) uniform readonly uimage2D u_ids;

layout(push_constant) uniform Params {
    uint width;
    uint height;
    uint history_valid;  // 0 on the first frame and after a reset: nothing is reprojected
    // The least weight of this frame's emission in its average, per pixel of motion (the weights
    // file's, passes/src/denoise/neural/weights.rs).
    float emission_motion;
    // The most frames the running means average before they become exponential moving averages
    // (the weights file's `history_frames`, at most N_MAX).
    float history_frames;
    // The history lengths below which the variance inputs are spatial (the weights file's
    // `spatial_variance_frames`; 0: never).
    float spatial_variance_frames;
} params;

const float DEPTH_TOLERANCE = 0.05;
const float NORMAL_COS = 0.9;
const float MIN_WEIGHT = 0.01;
// What the network's input divides the history length by: the longest history a weights file may
// ask the running means to average (HISTORY_FRAMES in passes/src/denoise/neural/weights.rs).
const float N_MAX = 32.0;
// The least weight of this frame's albedo and emission in their averages over time.
const float SURFACE_ALPHA = 0.1;
// The bits of an object id the emission's history keeps (exact in a float; the sky's is all ones).
const uint OBJECT_BITS = 0xffffffu;
// The smallest 1 - luminance that `expand` divides by.
const float EXPAND_MIN = 1e-3;

// Range compression against fireflies (`compress`): the luminance stays below 1.
vec3 compress(vec3 rgb) {
    return rgb / (1.0 + luminance(rgb));
}

// The inverse of `compress` (`expand`).
vec3 expand(vec3 rgb) {
    return rgb / max(1.0 - luminance(rgb), EXPAND_MIN);
}

// The object the pixel's first hit belongs to, as the emission's history keeps it (alpha).
float surface_object(ivec2 pixel) {
    return float(imageLoad(u_ids, pixel).x & OBJECT_BITS);
}

uvec2 size() {
    return uvec2(params.width, params.height);
}

shared vec3 s_radiance[8][8];
shared vec3 s_radiance_half[4][4];
shared vec3 s_radiance_quarter[2][2];
// log(1 + emission) over the workgroup's tile and a one-pixel margin (the 3x3 neighbourhoods that
// clamp the emission's history), each pixel's computed once (unset outside the image).
shared vec3 s_log_emission[10][10];
// This frame's luminance (x) and compressed luminance (y) of the demodulated radiance over the same
// tile and margin (the 3x3 neighbourhoods of `neighbourhood_variance`), where the weights file asks
// for spatial variances (unset outside the image).
shared vec2 s_luminance[10][10];

// The pixel at the shared arrays' [0][0]: one pixel up and left of the workgroup's tile.
ivec2 margin_origin() {
    return ivec2(gl_WorkGroupID.xy) * 8 - 1;
}

// The position of `q`, within one pixel of the workgroup's tile, in the shared arrays.
ivec2 margin_index(ivec2 q) {
    return q - margin_origin();
}

// Fills s_log_emission and, with spatial variances, s_luminance. Every invocation of the workgroup
// calls it (barrier).
void load_neighbourhood() {
    ivec2 origin = margin_origin();
    for (uint i = gl_LocalInvocationIndex; i < 100u; i += 64u) {
        ivec2 r = ivec2(i % 10u, i / 10u);
        ivec2 q = origin + r;
        if (inside_image(q, ivec2(size()))) {
            s_log_emission[r.y][r.x] = log(vec3(1.0) + input_emission(q));
            if (params.spatial_variance_frames > 0.0) {
                vec3 radiance = max(input_demodulated(q), vec3(0.0));
                s_luminance[r.y][r.x] = vec2(luminance(radiance), luminance(compress(radiance)));
            }
        }
    }
    barrier();
}

// log(1 + emission) of `q`, within one pixel of the invocation's pixel and inside the image.
vec3 log_emission(ivec2 q) {
    ivec2 r = margin_index(q);
    return s_log_emission[r.y][r.x];
}

// The variance of this frame's luminance (x) and compressed luminance (y) over the 3x3
// neighbourhood of `pixel`, its pixels inside the image (training/model.py,
// `neighbourhood_variance`).
vec2 neighbourhood_variance(ivec2 pixel) {
    vec2 sum = vec2(0.0);
    vec2 square = vec2(0.0);
    float count = 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (inside_image(q, ivec2(size()))) {
                ivec2 r = margin_index(q);
                vec2 v = s_luminance[r.y][r.x];
                sum += v;
                square += v * v;
                count += 1.0;
            }
        }
    }
    vec2 mean = sum / count;
    return max(square / count - mean * mean, vec2(0.0));
}

// Writes the workgroup's pixels of `radiance` (this invocation's, clamped to 0) 2x2 average-pooled
// POOLED_LEVELS times, at most three. Every invocation of the workgroup calls it (barriers).
void pool_radiance(vec3 radiance) {
    uvec2 local = gl_LocalInvocationID.xy;
    s_radiance[local.y][local.x] = radiance;
    barrier();
    ivec2 tile = ivec2(gl_WorkGroupID.xy);
    ivec2 last = ivec2(size()) - 1;
    ivec2 half_size = (ivec2(size()) + 1) / 2;
    ivec2 half_pixel = tile * 4 + ivec2(local);
    if (all(lessThan(local, uvec2(4u))) && pixel_in_bounds(half_pixel, half_size)) {
        vec3 sum = vec3(0.0);
        for (int i = 0; i < 4; ++i) {
            ivec2 q = min(half_pixel * 2 + ivec2(i & 1, i >> 1), last) - tile * 8;
            sum += s_radiance[q.y][q.x];
        }
        vec3 mean = 0.25 * sum;
        s_radiance_half[local.y][local.x] = mean;
        b_radiance_half.v[half_pixel.y * half_size.x + half_pixel.x] = log_pooled(mean);
    }
    barrier();
    ivec2 quarter_size = (half_size + 1) / 2;
    ivec2 quarter_pixel = tile * 2 + ivec2(local);
    if (all(lessThan(local, uvec2(2u))) && pixel_in_bounds(quarter_pixel, quarter_size)) {
        vec3 mean = vec3(0.0);
        for (int i = 0; i < 4; ++i) {
            ivec2 q = min(quarter_pixel * 2 + ivec2(i & 1, i >> 1), half_size - 1) - tile * 4;
            mean += 0.25 * s_radiance_half[q.y][q.x];
        }
        s_radiance_quarter[local.y][local.x] = mean;
        b_radiance_quarter.v[quarter_pixel.y * quarter_size.x + quarter_pixel.x] = log_pooled(mean);
    }
    if (POOLED_LEVELS < 3u) {
        return;
    }
    barrier();
    ivec2 eighth_size = (quarter_size + 1) / 2;
    if (gl_LocalInvocationIndex == 0u && pixel_in_bounds(tile, eighth_size)) {
        vec3 mean = vec3(0.0);
        for (int i = 0; i < 4; ++i) {
            ivec2 q = min(tile * 2 + ivec2(i & 1, i >> 1), quarter_size - 1) - tile * 2;
            mean += 0.25 * s_radiance_quarter[q.y][q.x];
        }
        b_radiance_eighth.v[tile.y * eighth_size.x + tile.x] = log_pooled(mean);
        if (POOLED_LEVELS > 3u) {
            b_radiance_eighth_linear.v[tile.y * eighth_size.x + tile.x] = vec4(mean, 0.0);
        }
    }
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = pixel_in_bounds(pixel, ivec2(size()));
    vec3 demodulated = inside ? max(input_demodulated(pixel), vec3(0.0)) : vec3(0.0);
    if (POOLED_LEVELS > 0u) {
        pool_radiance(demodulated);
    }
    load_neighbourhood();
    if (!inside) {
        return;
    }
    vec4 normal_roughness = input_normal_roughness(pixel);
    vec3 normal = normal_roughness.xyz;
    float depth = input_depth(pixel);
    vec3 motion = input_motion(pixel);
    imageStore(u_surface, pixel, vec4(depth, normal));

    // The output history, the running means with the length and the second moments, warped together.
    vec3 warped = vec3(0.0);
    vec4 warped_accum = vec4(0.0);
    float warped_moment = 0.0;
    vec4 warped_robust = vec4(0.0);
    vec3 warped_albedo = vec3(0.0);
    vec3 warped_emission = vec3(0.0);
    float weight_sum = 0.0;
    float surface_weight = 0.0;
    float emission_weight = 0.0;
    float object_id = surface_object(pixel);
    // The emission supersampled at an emitter's edge covers the pixel whichever object its centre
    // sees, so its history is taken from the taps of either side.
    vec4 traced_emission = imageLoad(u_emission, pixel);
    bool edge = supersampled(traced_emission);
    if (params.history_valid != 0u) {
        vec2 prev_pos = vec2(pixel) + motion.xy;
        vec2 base = floor(prev_pos);
        vec2 f = prev_pos - base;
        bool here_sky = depth <= 0.0;
        for (int i = 0; i < 4; ++i) {
            ivec2 d = ivec2(i & 1, i >> 1);
            vec2 q = base + vec2(d);
            float w = (d.x == 1 ? f.x : 1.0 - f.x) * (d.y == 1 ? f.y : 1.0 - f.y);
            if (q.x < 0.0 || q.y < 0.0 || q.x >= float(params.width) || q.y >= float(params.height)) {
                continue;
            }
            vec4 s = imageLoad(u_prev_surface, ivec2(q));
            bool q_sky = s.x <= 0.0;
            bool same = abs(s.x - motion.z) <= DEPTH_TOLERANCE * motion.z && dot(s.yzw, normal) > NORMAL_COS;
            bool valid = here_sky ? q_sky : (!q_sky && same);
            if (valid) {
                warped += w * unpack_channels(imageLoad(u_prev_output, ivec2(q)).xy).rgb;
                warped_accum += w * imageLoad(u_prev_accum, ivec2(q));
                warped_moment += w * imageLoad(u_prev_moment, ivec2(q)).r;
                warped_robust += w * imageLoad(u_prev_robust, ivec2(q));
                weight_sum += w;
                // The albedo and emission only from taps of the same object, as SVGF's: a light's
                // edge is never mixed with the ceiling beside it.
                vec4 e = imageLoad(u_prev_emission_mean, ivec2(q));
                if (e.a == object_id) {
                    warped_albedo += w * imageLoad(u_prev_albedo_mean, ivec2(q)).rgb;
                    surface_weight += w;
                }
                if (e.a == object_id || edge) {
                    warped_emission += w * e.rgb;
                    emission_weight += w;
                }
            }
        }
    }
    float mask = 0.0;
    if (weight_sum >= MIN_WEIGHT) {
        float norm = max(weight_sum, 1e-8);
        warped /= norm;
        warped_accum /= norm;
        warped_moment /= norm;
        warped_robust /= norm;
        mask = 1.0;
    } else {
        warped = vec3(0.0);
    }
    // The running means (`accumulate`): this frame's values where nothing is reprojected.
    float lum = luminance(demodulated);
    vec3 squeezed = compress(demodulated);
    float squeezed_lum = luminance(squeezed);
    float n = 1.0;
    vec3 mean = demodulated;
    float moment = lum * lum;
    vec4 robust = vec4(squeezed, squeezed_lum * squeezed_lum);
    if (mask > 0.0) {
        n = min(warped_accum.a + 1.0, params.history_frames);
        float alpha = 1.0 / n;
        mean = warped_accum.rgb + (demodulated - warped_accum.rgb) * alpha;
        moment = warped_moment + (lum * lum - warped_moment) * alpha;
        robust = warped_robust + (robust - warped_robust) * alpha;
    }
    imageStore(u_accum, pixel, vec4(mean, n));
    imageStore(u_moment, pixel, vec4(moment, 0.0, 0.0, 0.0));
    imageStore(u_robust, pixel, robust);

    // The first hits' albedo and log(1 + emission) averaged over time (`antialias_surface`) where
    // taps of the same object were reprojected (for an emission supersampled at an emitter's edge,
    // taps of either object): the emission's weight at least the motion in pixels times
    // emission_motion (0 unless the weights file says otherwise) and, supersampled, at least the
    // motion in pixels (edge_emission.glsl), its history clamped to the range of this frame's over
    // the 3x3 neighbourhood.
    vec3 albedo = input_albedo(pixel);
    vec3 albedo_mean = albedo;
    vec3 emission = log_emission(pixel);
    vec3 emission_mean = emission;
    float alpha_surface = max(1.0 / n, SURFACE_ALPHA);
    if (surface_weight >= MIN_WEIGHT) {
        warped_albedo /= surface_weight;
        albedo_mean = warped_albedo + (albedo - warped_albedo) * alpha_surface;
    }
    if (emission_weight >= MIN_WEIGHT) {
        warped_emission /= emission_weight;
        float alpha_emission = max(alpha_surface, min(length(motion.xy) * params.emission_motion, 1.0));
        alpha_emission = max(alpha_emission, edge_emission_weight(traced_emission, motion.xy));
        // A pixel moving a pixel a frame or more keeps this frame's emission: no history to clamp.
        if (alpha_emission < 1.0) {
            vec3 low = emission;
            vec3 high = emission;
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    ivec2 q = pixel + ivec2(dx, dy);
                    if (inside_image(q, ivec2(size()))) {
                        vec3 e = log_emission(q);
                        low = min(low, e);
                        high = max(high, e);
                    }
                }
            }
            vec3 prev = clamp(warped_emission, low, high);
            emission_mean = prev + (emission - prev) * alpha_emission;
        }
    }
    imageStore(u_emission_mean, pixel, vec4(emission_mean, object_id));
    imageStore(u_albedo_mean, pixel, vec4(albedo_mean, 1.0));

    float mean_lum = luminance(mean);
    float variance = n > 1.0 ? max(moment - mean_lum * mean_lum, 0.0) : 0.0;
    float robust_lum = luminance(robust.rgb);
    float robust_variance = n > 1.0 ? max(robust.a - robust_lum * robust_lum, 0.0) : 0.0;
    if (n < params.spatial_variance_frames) {
        vec2 spatial = neighbourhood_variance(pixel);
        variance = spatial.x;
        robust_variance = spatial.y;
    }
    vec3 log_mean = log(vec3(1.0) + mean);
    float log_std = log(1.0 + sqrt(variance));
    vec3 log_robust = log(vec3(1.0) + expand(robust.rgb));

    float roughness = normal_roughness.w;
    vec3 log_radiance = log(vec3(1.0) + demodulated);
    float log_depth = log(1.0 + max(depth, 0.0));
    uint at = tensor_index(pixel, params.width, FEATURE_GROUPS, 0u);
    b_features.v[at + 0u] = pack_channels(vec4(log_radiance, albedo.r));
    b_features.v[at + 1u] = pack_channels(vec4(albedo.gb, normal.xy));
    b_features.v[at + 2u] = pack_channels(vec4(normal.z, roughness, log_depth, warped.r));
    b_features.v[at + 3u] = pack_channels(vec4(warped.gb, mask, log_mean.r));
    b_features.v[at + 4u] = pack_channels(vec4(log_mean.gb, n / N_MAX, log_std));
    b_features.v[at + 5u] = pack_channels(vec4(log_robust, sqrt(robust_variance)));
}
