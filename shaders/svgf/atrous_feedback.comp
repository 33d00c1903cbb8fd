#version 460
// The first iteration of the SVGF a-trous filter (see svgf/atrous.glsl), whose output also
// becomes the colour history the next frame reprojects.
#include "common/math.glsl"
#include "common/image_coords.glsl"
#include "svgf/common.glsl"

layout(set = 0, binding = 0) uniform sampler2D u_in;
layout(set = 0, binding = 1, r32f) uniform readonly image2D u_depth;
layout(set = 0, binding = 2, rgba16f) uniform readonly image2D u_normal_roughness;
layout(set = 0, binding = 3, r32f) uniform readonly image2D u_depth_slope;
layout(set = 0, binding = 4, rgba16f) uniform writeonly image2D u_out;
layout(set = 0, binding = 5, rgba32f) uniform writeonly image2D u_history;

layout(push_constant) uniform Params {
    int step;
    float sigma_z;
    float sigma_n;
    float sigma_l;
} params;

#include "svgf/atrous.glsl"

void main() {
    ivec2 pixel;
    vec4 filtered;
    if (svgf_atrous(pixel, filtered)) {
        imageStore(u_out, pixel, filtered);
        imageStore(u_history, pixel, vec4(filtered.rgb, 0.0));
    }
}
