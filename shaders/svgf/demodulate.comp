#version 460
// Demodulation of accumulated radiance for the spatial filter: (radiance - emission) / albedo,
// with the first hit's emission and albedo accumulated over the same frames.
#include "common/math.glsl"
#include "common/image_coords.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_radiance;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D u_albedo;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D u_emission;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D u_illumination;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!pixel_in_bounds(pixel, imageSize(u_illumination))) {
        return;
    }
    vec3 radiance = imageLoad(u_radiance, pixel).rgb;
    vec3 albedo = imageLoad(u_albedo, pixel).rgb;
    vec3 emission = imageLoad(u_emission, pixel).rgb;
    imageStore(u_illumination, pixel, vec4(demodulate(radiance, emission, albedo), 0.0));
}
