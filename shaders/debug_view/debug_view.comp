#version 460
// Maps an intermediate image to displayable linear RGB: normals to 0.5 + 0.5 n, depth to a grey
// ramp, motion vectors to 0.5 + motion / 16 (red: x, green: y), SVGF's temporal gradients to the
// share of history they drop (red), anything else copied. A source smaller than the output (the
// gradients have one texel per stratum) is stretched over it.
#include "common/image_coords.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D u_source;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D u_out;

layout(push_constant) uniform Params {
    uint mode;   // 0 copy, 1 normal, 2 depth, 3 motion, 4 gradient
    float scale; // depth: distance shown as white
} params;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (!pixel_in_bounds(pixel, imageSize(u_out))) {
        return;
    }
    ivec2 source = pixel * textureSize(u_source, 0) / imageSize(u_out);
    vec4 v = texelFetch(u_source, source, 0);
    vec3 c = v.rgb;
    if (params.mode == 1u) {
        c = 0.5 + 0.5 * v.xyz;
    } else if (params.mode == 2u) {
        c = vec3(v.x > 0.0 ? 1.0 - clamp(v.x / params.scale, 0.0, 1.0) : 0.0);
    } else if (params.mode == 3u) {
        c = vec3(0.5 + v.xy / 16.0, 0.5);
    } else if (params.mode == 4u) {
        // As the temporal pass weighs its history (svgf/temporal.comp).
        c = vec3(v.y > 1e-6 ? clamp(abs(v.x) / v.y, 0.0, 1.0) : 0.0, 0.0, 0.0);
    }
    imageStore(u_out, pixel, vec4(c, 1.0));
}
