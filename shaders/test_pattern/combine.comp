#version 460
// out = in + (row sum of red) in alpha, with a constant offset: checks that both inputs arrive.
#include "common/image_coords.glsl"

layout(local_size_x_id = 0, local_size_y = 8) in;
layout(constant_id = 1) const bool ADD_OFFSET = true;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_in;
layout(set = 0, binding = 1) readonly buffer RowSums {
    float values[];
} b_sums;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D u_out;

layout(push_constant) uniform Params {
    float offset;
} params;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_out);
    if (!pixel_in_bounds(pixel, size)) {
        return;
    }
    vec4 c = imageLoad(u_in, pixel);
    float offset = ADD_OFFSET ? params.offset : 0.0;
    imageStore(u_out, pixel, vec4(c.rgb + offset, b_sums.values[pixel.y]));
}
