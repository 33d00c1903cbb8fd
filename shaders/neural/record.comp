#version 460
// Gathers the learned denoiser's per-pixel inputs (record.glsl) from the light transport's
// surface images and the G-buffer.
#include "common/image_coords.glsl"
#include "neural/record.glsl"

layout(local_size_x = 32, local_size_y = 2) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_demodulated;
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D u_albedo;
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D u_emission;
layout(set = 0, binding = 3, rgba16f) uniform readonly image2D u_normal_roughness;
layout(set = 0, binding = 4, r32f) uniform readonly image2D u_depth;
layout(set = 0, binding = 5, rgba16f) uniform readonly image2D u_motion;
layout(set = 0, binding = 6, std430) writeonly buffer Record { float v[]; } b_record;

void put(uint channel, ivec2 pixel, uvec2 size, float value) {
    b_record.v[record_index(channel, pixel, size)] = value;
}

void put3(uint channel, ivec2 pixel, uvec2 size, vec3 value) {
    for (uint i = 0u; i < 3u; ++i) {
        put(channel + i, pixel, size, value[i]);
    }
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_depth);
    if (!pixel_in_bounds(pixel, size)) {
        return;
    }
    uvec2 s = uvec2(size);
    vec4 nr = imageLoad(u_normal_roughness, pixel);
    put3(RECORD_DEMODULATED, pixel, s, min(imageLoad(u_demodulated, pixel).rgb, vec3(65504.0)));
    put3(RECORD_ALBEDO, pixel, s, imageLoad(u_albedo, pixel).rgb);
    put3(RECORD_EMISSION, pixel, s, min(imageLoad(u_emission, pixel).rgb, vec3(65504.0)));
    put3(RECORD_NORMAL, pixel, s, nr.xyz);
    put(RECORD_ROUGHNESS, pixel, s, nr.w);
    put(RECORD_DEPTH, pixel, s, imageLoad(u_depth, pixel).x);
    put3(RECORD_MOTION, pixel, s, imageLoad(u_motion, pixel).xyz);
}
