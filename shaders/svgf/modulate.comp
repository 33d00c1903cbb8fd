#version 460
// Re-modulation after filtering: radiance = illumination * albedo + directly seen emission, both
// averaged over the light transport's jittered first hits (svgf/temporal.comp, or accumulated).
#include "common/image_coords.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D u_illumination;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D u_albedo;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D u_emission;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D u_out;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!pixel_in_bounds(pixel, imageSize(u_out))) {
        return;
    }
    vec3 illumination = imageLoad(u_illumination, pixel).rgb;
    vec3 albedo = imageLoad(u_albedo, pixel).rgb;
    vec3 emission = imageLoad(u_emission, pixel).rgb;
    imageStore(u_out, pixel, vec4(illumination * albedo + emission, 1.0));
}
