#version 460
// SVGF temporal accumulation: takes this frame's demodulated illumination, reprojects last frame's
// integrated illumination and luminance moments with the G-buffer's motion vectors (bilinear taps
// validated by depth, normal and object id, else a 3x3 search, else a disocclusion), and blends
// them with an exponential moving average whose weight the temporal gradient raises where the
// shading changed (A-SVGF). The first hit's albedo and emission, which the light-transport pass
// wrote for its jittered samples, are averaged the same way: re-modulating with these means keeps
// emitter and texture edges antialiased and steady under sub-pixel motion (the emission the edge
// pass supersampled weighs more as it moves, edge_emission.glsl). A firefly is clamped before it
// enters the colour and the moments: where the pixel has history, the sample may be at most
// `firefly_headroom` times as bright as the brightest history pixel of the same surface in the
// 3x3 neighbourhood last frame (that history is the first a-trous iteration's output, so smooth),
// or that many times as bright as the second brightest of this frame's neighbouring samples on
// the same object (light that appeared since last frame lights the neighbours too; fireflies are
// alone, or two together). Without history, only the latter bound applies. Also writes this
// frame's surface record for the next frame.
#include "common/math.glsl"
#include "common/image_coords.glsl"
#include "svgf/common.glsl"
#include "edge_emission/edge_emission.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_radiance;
layout(set = 0, binding = 1, r32f) uniform readonly image2D u_depth;
layout(set = 0, binding = 2, rgba16f) uniform readonly image2D u_normal_roughness;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D u_illumination;
layout(set = 0, binding = 5, rgba32ui) uniform readonly uimage2D u_ids;
layout(set = 0, binding = 6, rgba16f) uniform readonly image2D u_motion;
layout(set = 0, binding = 7, rgba32f) uniform readonly image2D u_gradient;
layout(set = 0, binding = 8, rgba32f) uniform readonly image2D u_prev_color;
layout(set = 0, binding = 9, rgba32f) uniform readonly image2D u_prev_moments;
layout(set = 0, binding = 10, rgba32ui) uniform readonly uimage2D u_prev_surface;
layout(set = 0, binding = 11, rgba32f) uniform writeonly image2D u_color;
layout(set = 0, binding = 12, rgba32f) uniform writeonly image2D u_moments;
layout(set = 0, binding = 13, rgba32ui) uniform writeonly uimage2D u_surface;
layout(set = 0, binding = 14, rgba32f) uniform readonly image2D u_albedo;
layout(set = 0, binding = 15, rgba32f) uniform readonly image2D u_emission;
layout(set = 0, binding = 16, rgba32f) uniform readonly image2D u_prev_albedo;
layout(set = 0, binding = 17, rgba32f) uniform readonly image2D u_prev_emission;
layout(set = 0, binding = 18, rgba32f) uniform writeonly image2D u_albedo_out;
layout(set = 0, binding = 19, rgba32f) uniform writeonly image2D u_emission_out;

#include "svgf/depth_slope.glsl"

layout(push_constant) uniform Params {
    float alpha;          // colour blend weight of a long history
    float moments_alpha;  // moments blend weight of a long history
    uint history_valid;   // 0 after a reset: every pixel is a disocclusion
    uint stratum;         // side of a gradient stratum in pixels
    float max_history;    // cap of the history length
    float surface_alpha;  // albedo and emission blend weight of a long history
    float firefly_headroom;  // how far above its neighbours a sample may go; 0: no firefly clamp
    float pad;
} params;

// The history length from which a sample is bounded by the history around it: from the second
// frame a pixel sees its surface on (in a pixel's first frame, only its neighbours bound it).
const float FIREFLY_MIN_HISTORY = 1.0;

// Whether last frame's pixel `q` saw the surface this pixel sees now.
bool tap_valid(ivec2 q, ivec2 size, uint object_id, vec3 normal, float expected_depth, float tolerance) {
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) {
        return false;
    }
    SvgfSurface s = svgf_unpack_surface(imageLoad(u_prev_surface, q));
    if (s.object_id != object_id) {
        return false;
    }
    if (object_id == SVGF_SKY) {
        return true;
    }
    return abs(s.depth - expected_depth) <= tolerance && dot(s.normal, normal) > 0.9;
}

// The brightest luminance of last frame's colour history among the 3x3 pixels around `centre` that
// saw this pixel's surface (0 where none did).
float history_peak(ivec2 centre, ivec2 size, uint object_id, vec3 normal, float expected_depth, float tolerance) {
    float peak = 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = centre + ivec2(dx, dy);
            if (tap_valid(q, size, object_id, normal, expected_depth, tolerance)) {
                peak = max(peak, luminance(imageLoad(u_prev_color, q).rgb));
            }
        }
    }
    return peak;
}

// The second brightest luminance of this frame's illumination among the 8 neighbours of `pixel`
// that see object `object_id`: new light brightens several, while two fireflies side by side,
// which a single bright neighbour would let through, are no more than one each.
float second_brightest_neighbour(ivec2 pixel, ivec2 size, uint object_id) {
    float peak = 0.0;
    float second = 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if ((dx != 0 || dy != 0) && pixel_in_bounds(q, size) && imageLoad(u_ids, q).x == object_id) {
                float l = luminance(imageLoad(u_illumination, q).rgb);
                second = max(second, min(peak, l));
                peak = max(peak, l);
            }
        }
    }
    return second;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_color);
    if (!pixel_in_bounds(pixel, size)) {
        return;
    }
    vec3 radiance = imageLoad(u_radiance, pixel).rgb;
    vec3 illum = imageLoad(u_illumination, pixel).rgb;
    float lum = luminance(illum);
    SvgfSurface here;
    here.depth = imageLoad(u_depth, pixel).x;
    here.normal = imageLoad(u_normal_roughness, pixel).xyz;
    here.object_id = imageLoad(u_ids, pixel).x;
    here.radiance_luminance = luminance(radiance);
    imageStore(u_surface, pixel, svgf_pack_surface(here));

    vec3 motion = imageLoad(u_motion, pixel).xyz;
    float tolerance = 0.02 * motion.z + 2.0 * svgf_depth_slope(pixel, size);
    vec3 prev_color = vec3(0.0);
    vec3 prev_moments = vec3(0.0);
    vec3 prev_albedo = vec3(0.0);
    vec3 prev_emission = vec3(0.0);
    float weight_sum = 0.0;
    if (params.history_valid != 0u) {
        vec2 prev_pos = vec2(pixel) + motion.xy;
        ivec2 base = ivec2(floor(prev_pos));
        vec2 f = prev_pos - vec2(base);
        float w[4] = float[4]((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
        for (int i = 0; i < 4; ++i) {
            ivec2 q = base + ivec2(i & 1, i >> 1);
            if (tap_valid(q, size, here.object_id, here.normal, motion.z, tolerance)) {
                prev_color += w[i] * imageLoad(u_prev_color, q).rgb;
                prev_moments += w[i] * imageLoad(u_prev_moments, q).xyz;
                prev_albedo += w[i] * imageLoad(u_prev_albedo, q).rgb;
                prev_emission += w[i] * imageLoad(u_prev_emission, q).rgb;
                weight_sum += w[i];
            }
        }
        if (weight_sum < 0.01) {
            prev_color = vec3(0.0);
            prev_moments = vec3(0.0);
            prev_albedo = vec3(0.0);
            prev_emission = vec3(0.0);
            weight_sum = 0.0;
            ivec2 centre = ivec2(floor(prev_pos + 0.5));
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    ivec2 q = centre + ivec2(dx, dy);
                    if (tap_valid(q, size, here.object_id, here.normal, motion.z, tolerance + 0.02 * motion.z)) {
                        prev_color += imageLoad(u_prev_color, q).rgb;
                        prev_moments += imageLoad(u_prev_moments, q).xyz;
                        prev_albedo += imageLoad(u_prev_albedo, q).rgb;
                        prev_emission += imageLoad(u_prev_emission, q).rgb;
                        weight_sum += 1.0;
                    }
                }
            }
        }
    }
    vec3 color = illum;
    vec2 moments = vec2(lum, lum * lum);
    vec3 albedo = imageLoad(u_albedo, pixel).rgb;
    vec4 traced_emission = imageLoad(u_emission, pixel);
    vec3 emission = traced_emission.rgb;
    float history = 1.0;
    if (weight_sum > 0.0) {
        prev_color /= weight_sum;
        prev_moments /= weight_sum;
        prev_albedo /= weight_sum;
        prev_emission /= weight_sum;
        // The temporal gradient's share of shading that changed since last frame drops that
        // share of the history (A-SVGF).
        vec2 g = imageLoad(u_gradient, pixel / int(params.stratum)).xy;
        float lambda = g.y > 1e-6 ? clamp(abs(g.x) / g.y, 0.0, 1.0) : 0.0;
        float n = prev_moments.z * (1.0 - lambda);
        float a = mix(max(params.alpha, 1.0 / (n + 1.0)), 1.0, lambda);
        float am = mix(max(params.moments_alpha, 1.0 / (n + 1.0)), 1.0, lambda);
        // The pixel's own history is among its neighbours': most samples are too dim to need the
        // search for the bound. The bound is on the sample, not on the blended colour, which would
        // let a sample as much brighter through as the blend weight is small.
        if (params.firefly_headroom > 0.0 && n >= FIREFLY_MIN_HISTORY &&
            lum > params.firefly_headroom * luminance(prev_color)) {
            ivec2 centre = ivec2(floor(vec2(pixel) + motion.xy + 0.5));
            float largest = params.firefly_headroom *
                            history_peak(centre, size, here.object_id, here.normal, motion.z,
                                         tolerance + 0.02 * motion.z);
            if (lum > largest) {
                float neighbours = second_brightest_neighbour(pixel, size, here.object_id);
                largest = max(largest, params.firefly_headroom * neighbours);
            }
            if (lum > largest) {
                illum *= largest / lum;
                lum = largest;
                moments = vec2(lum, lum * lum);
            }
        }
        color = mix(prev_color, illum, a);
        float a_surface = mix(max(params.surface_alpha, 1.0 / (n + 1.0)), 1.0, lambda);
        albedo = mix(prev_albedo, albedo, a_surface);
        float a_emission = max(a_surface, edge_emission_weight(traced_emission, motion.xy));
        emission = mix(prev_emission, emission, a_emission);
        moments = mix(prev_moments.xy, moments, am);
        history = min(n + 1.0, params.max_history);
    } else if (params.firefly_headroom > 0.0) {
        // No history: the sample may be at most `firefly_headroom` times as bright as the
        // second brightest of its neighbours.
        float largest =
            params.firefly_headroom * second_brightest_neighbour(pixel, size, here.object_id);
        if (lum > largest) {
            color *= largest / lum;
            moments = vec2(largest, largest * largest);
        }
    }
    imageStore(u_color, pixel, vec4(color, 0.0));
    imageStore(u_moments, pixel, vec4(moments, history, 0.0));
    imageStore(u_albedo_out, pixel, vec4(albedo, 1.0));
    imageStore(u_emission_out, pixel, vec4(emission, 1.0));
}
