#version 460
// The input of the spatial-only filter: demodulated illumination and its luminance moments with
// no history (the variance pass then estimates variance spatially).
#include "common/math.glsl"
#include "common/image_coords.glsl"
#include "svgf/common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_radiance;
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D u_albedo;
layout(set = 0, binding = 2, rgba16f) uniform readonly image2D u_emission;
layout(set = 0, binding = 3, rgba32f) uniform writeonly image2D u_color;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D u_moments;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!pixel_in_bounds(pixel, imageSize(u_color))) {
        return;
    }
    vec3 illum = svgf_demodulate(imageLoad(u_radiance, pixel).rgb, imageLoad(u_emission, pixel).rgb,
                                 imageLoad(u_albedo, pixel).rgb);
    float l = luminance(illum);
    imageStore(u_color, pixel, vec4(illum, 0.0));
    imageStore(u_moments, pixel, vec4(l, l * l, 0.0, 0.0));
}
