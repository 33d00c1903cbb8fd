#version 460
// The still-camera hand-off's per-pixel statistics (passes/src/denoise/handoff): the running second
// moment of this frame's radiance luminance over the frames accumulated (beside the accumulation's
// mean, which the accumulate pass keeps), then the squared luminance difference between the
// denoised and the accumulated image and the variance of the accumulated mean, which blend.comp
// averages over a neighbourhood.
#include "common/image_coords.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_radiance;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D u_accumulated;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D u_denoised;
layout(set = 0, binding = 3, r32f) uniform readonly image2D u_prev_moment;
layout(set = 0, binding = 4, r32f) uniform writeonly image2D u_cur_moment;
layout(set = 0, binding = 5, rg32f) uniform writeonly image2D u_stats;

layout(push_constant) uniform Params {
    // Frames averaged before this one (0: the accumulation, and the moment, start afresh).
    uint accumulated;
} params;

// What a pixel without finite statistics gets: no difference and an unbounded variance, so that the
// blend keeps the denoised value there.
const vec2 UNKNOWN = vec2(0.0, 3.0e38);

float luminance(vec3 c) {
    return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!pixel_in_bounds(pixel, imageSize(u_stats))) {
        return;
    }
    float l = luminance(imageLoad(u_radiance, pixel).rgb);
    float n = float(params.accumulated);
    float prev = imageLoad(u_prev_moment, pixel).r;
    // Last frame's moment is read only when it exists (it is undefined after a restart).
    float moment = params.accumulated == 0u ? l * l : prev + (l * l - prev) / (n + 1.0);
    imageStore(u_cur_moment, pixel, vec4(moment));
    if (params.accumulated == 0u) {
        imageStore(u_stats, pixel, vec4(UNKNOWN, 0.0, 0.0));
        return;
    }
    float mean = luminance(imageLoad(u_accumulated, pixel).rgb);
    float denoised = luminance(imageLoad(u_denoised, pixel).rgb);
    float difference = denoised - mean;
    // The frames' sample variance over n + 1 frames, divided by their number: the mean's variance.
    float variance = max(moment - mean * mean, 0.0) / n;
    vec2 stats = vec2(difference * difference, variance);
    bool finite = !(any(isnan(stats)) || any(isinf(stats)));
    imageStore(u_stats, pixel, vec4(finite ? stats : UNKNOWN, 0.0, 0.0));
}
