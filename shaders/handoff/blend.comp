#version 460
// The still-camera hand-off (passes/src/denoise/handoff): per pixel, the mix of the denoised and the
// accumulated image of least expected error. The accumulated mean's error is this pixel's variance
// (moment.comp's statistics); the denoised image's (its bias, which more samples do not remove) is
// the squared difference between the two images beyond SIGNIFICANCE times the variance, over a 5x5
// neighbourhood. The accumulated image weighs bias^2 / (bias^2 + variance): the image moves to the
// accumulation where it has converged, and keeps the denoised value where it has not (fireflies).
#include "common/image_coords.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_accumulated;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D u_denoised;
layout(set = 0, binding = 2, rg32f) uniform readonly image2D u_stats;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D u_output;

layout(push_constant) uniform Params {
    // Frames averaged before this one (at least FIRST_FRAMES).
    uint accumulated;
} params;

// The accumulated frames after which the hand-off starts (Handoff::first_frames in handoff/mod.rs).
layout(constant_id = 0) const uint FIRST_FRAMES = 32u;
// How many times the accumulation's variance the squared difference must exceed before any of it
// counts as the denoised image's error (Handoff::significance).
layout(constant_id = 1) const float SIGNIFICANCE = 8.0;

// Half the side of the neighbourhood the statistics are averaged over.
const int RADIUS = 2;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_output);
    if (!pixel_in_bounds(pixel, size)) {
        return;
    }
    vec2 sum = vec2(0.0);
    float count = 0.0;
    for (int dy = -RADIUS; dy <= RADIUS; ++dy) {
        for (int dx = -RADIUS; dx <= RADIUS; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (inside_image(q, size)) {
                sum += imageLoad(u_stats, q).rg;
                count += 1.0;
            }
        }
    }
    // The variance estimated from few frames is itself uncertain (and path tracing's heavy tail
    // makes it low more often than high): it counts (N + 1) / (N - 1) times over N frames.
    float n = float(params.accumulated);
    float inflation = (n + 2.0) / n;
    // The denoised image's squared error is smooth: estimated over the neighbourhood. The
    // accumulated mean's is this pixel's own (a firefly's variance is its own alone).
    float bias2 = max(sum.x - SIGNIFICANCE * inflation * sum.y, 0.0) / count;
    float variance = inflation * imageLoad(u_stats, pixel).g;
    float total = bias2 + variance;
    float w = total > 0.0 ? bias2 / total : 1.0;
    // Fades in from FIRST_FRAMES to twice that many accumulated frames (handoff/mod.rs).
    w *= clamp((n + 1.0) / float(FIRST_FRAMES) - 1.0, 0.0, 1.0);
    vec4 denoised = imageLoad(u_denoised, pixel);
    vec4 accumulated = imageLoad(u_accumulated, pixel);
    imageStore(u_output, pixel, vec4(mix(denoised.rgb, accumulated.rgb, w), denoised.a));
}
