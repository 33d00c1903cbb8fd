#version 460
// SVGF variance estimate: the temporal luminance moments give variance = E[l^2] - E[l]^2. Where
// the history is shorter than 4 frames (disocclusions, the first frame, the per-frame filter) the
// moments and the illumination are instead averaged over a 7x7 neighbourhood with depth and normal
// edge stopping. Writes illumination (rgb) and the standard deviation (a) in half precision
// (svgf_pack_filtered), and every pixel's depth slope (svgf/depth_slope.glsl) for the a-trous
// iterations, whose tiles hold pixels a step apart rather than a pixel's neighbours.
#include "common/math.glsl"
#include "common/image_coords.glsl"
#include "svgf/common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_color;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D u_moments;
layout(set = 0, binding = 2, r32f) uniform readonly image2D u_depth;
layout(set = 0, binding = 3, rgba16f) uniform readonly image2D u_normal_roughness;
layout(set = 0, binding = 4, rgba16f) uniform writeonly image2D u_out;
layout(set = 0, binding = 5, r32f) uniform writeonly image2D u_depth_slope;

#include "svgf/depth_slope.glsl"

layout(push_constant) uniform Params {
    float sigma_z;
    float sigma_n;
} params;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_out);
    if (!pixel_in_bounds(pixel, size)) {
        return;
    }
    vec3 color = imageLoad(u_color, pixel).rgb;
    vec3 moments = imageLoad(u_moments, pixel).xyz;
    float history = moments.z;
    float z = imageLoad(u_depth, pixel).x;
    float slope = svgf_depth_slope(pixel, size);
    imageStore(u_depth_slope, pixel, vec4(slope));
    if (history >= 4.0 || z <= 0.0) {
        float variance = max(moments.y - moments.x * moments.x, 0.0);
        imageStore(u_out, pixel, svgf_pack_filtered(color, variance));
        return;
    }
    vec3 n = imageLoad(u_normal_roughness, pixel).xyz;
    vec3 color_sum = vec3(0.0);
    vec2 moment_sum = vec2(0.0);
    float weight_sum = 0.0;
    for (int dy = -3; dy <= 3; ++dy) {
        for (int dx = -3; dx <= 3; ++dx) {
            ivec2 q = pixel + ivec2(dx, dy);
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) {
                continue;
            }
            float zq = imageLoad(u_depth, q).x;
            if (zq <= 0.0) {
                continue;
            }
            vec3 nq = imageLoad(u_normal_roughness, q).xyz;
            float w = svgf_edge_weight(z, zq, slope, length(vec2(dx, dy)), n, nq, 0.0, 0.0, 1.0,
                                       params.sigma_z, params.sigma_n);
            color_sum += w * imageLoad(u_color, q).rgb;
            moment_sum += w * imageLoad(u_moments, q).xy;
            weight_sum += w;
        }
    }
    color_sum /= weight_sum;
    moment_sum /= weight_sum;
    float variance = max(moment_sum.y - moment_sum.x * moment_sum.x, 0.0);
    // Few frames of history underestimate variance: boost it as the SVGF reference does.
    variance *= history > 0.0 ? 4.0 / history : 1.0;
    imageStore(u_out, pixel, svgf_pack_filtered(color_sum, variance));
}
