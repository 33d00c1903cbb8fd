#version 460
// The first iteration of the SVGF a-trous filter (see svgf/atrous.glsl), whose output also
// becomes the colour history the next frame reprojects.
#include "common/math.glsl"
#include "common/image_coords.glsl"
#include "svgf/common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba16f) uniform readonly image2D u_in;
layout(set = 0, binding = 1, r32f) uniform readonly image2D u_depth;
layout(set = 0, binding = 2, rgba16f) uniform readonly image2D u_normal_roughness;
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D u_out;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D u_history;

layout(push_constant) uniform Params {
    int step;
    float sigma_z;
    float sigma_n;
    float sigma_l;
} params;

#include "svgf/depth_slope.glsl"
#include "svgf/atrous.glsl"

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_out);
    if (!pixel_in_bounds(pixel, size)) {
        return;
    }
    vec4 filtered = svgf_atrous(pixel, size);
    imageStore(u_out, pixel, filtered);
    imageStore(u_history, pixel, vec4(filtered.rgb, 0.0));
}
