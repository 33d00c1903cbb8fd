#version 460
// Progressive averaging: cur = prev + (new - prev) / (n + 1), where n frames are already averaged
// (n = 0 restarts from the new frame).
#include "common/image_coords.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_new;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D u_prev;
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D u_cur;

layout(push_constant) uniform Params {
    uint accumulated;
} params;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!pixel_in_bounds(pixel, imageSize(u_cur))) {
        return;
    }
    vec4 fresh = imageLoad(u_new, pixel);
    vec4 result = fresh;
    if (params.accumulated > 0u) {
        vec4 prev = imageLoad(u_prev, pixel);
        result = prev + (fresh - prev) / float(params.accumulated + 1u);
    }
    imageStore(u_cur, pixel, result);
}
