#version 460
// The spatial-only filter's moments: luminance and its square of the demodulated illumination,
// with no history (the variance pass then estimates variance spatially).
#include "common/math.glsl"
#include "common/image_coords.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_illumination;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D u_moments;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!pixel_in_bounds(pixel, imageSize(u_moments))) {
        return;
    }
    float l = luminance(imageLoad(u_illumination, pixel).rgb);
    imageStore(u_moments, pixel, vec4(l, l * l, 0.0, 0.0));
}
