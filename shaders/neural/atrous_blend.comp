#version 460
// The end of the learned denoiser's gated filter (training/model.py, `step`): the output's
// illumination blended with its a-trous filtered self by the gate, then re-modulated by the first
// hits' albedo plus emission averaged over time (features.comp), as output.comp does without it.
#include "common/image_coords.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// The output's illumination (rgb) and its gate (a), from output_atrous.comp.
layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_illumination;
// The illumination after the last a-trous step (rgb).
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D u_filtered;
// The first hits' albedo and log(1 + emission) averaged over time (`antialias_surface`).
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D u_albedo_mean;
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D u_emission_mean;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D u_radiance;

layout(push_constant) uniform Params {
    uint width;
    uint height;
} params;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!pixel_in_bounds(pixel, ivec2(params.width, params.height))) {
        return;
    }
    vec4 illumination = imageLoad(u_illumination, pixel);
    vec3 filtered = imageLoad(u_filtered, pixel).rgb;
    vec3 blended = mix(illumination.rgb, filtered, illumination.a);
    vec3 albedo = imageLoad(u_albedo_mean, pixel).rgb;
    vec3 emission = exp(imageLoad(u_emission_mean, pixel).rgb) - 1.0;
    imageStore(u_radiance, pixel, vec4(blended * albedo + emission, 1.0));
}
