#version 460
// cur = prev + increment: a history that must survive across frames.
#include "common/image_coords.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_prev;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D u_cur;

layout(push_constant) uniform Params {
    float increment;
} params;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!pixel_in_bounds(pixel, imageSize(u_cur))) {
        return;
    }
    imageStore(u_cur, pixel, imageLoad(u_prev, pixel) + vec4(params.increment));
}
