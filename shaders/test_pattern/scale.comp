#version 460
// out = in * factor: a link in chains of transients (used to test memory aliasing).
#include "common/image_coords.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_in;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D u_out;

layout(push_constant) uniform Params {
    float factor;
} params;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!pixel_in_bounds(pixel, imageSize(u_out))) {
        return;
    }
    imageStore(u_out, pixel, imageLoad(u_in, pixel) * params.factor);
}
