#version 460
// Gathers the learned denoiser's per-pixel inputs (inputs.glsl) into a record (record.glsl): what
// `lucid dataset` stores and image denoisers take their albedo and normal from. Inference reads
// the inputs where it uses them (features.comp); this pass runs only where a record is read back.
#include "common/image_coords.glsl"
#define INPUTS_BINDING 0
#include "neural/inputs.glsl"
#include "neural/record.glsl"

layout(local_size_x = 32, local_size_y = 2) in;

layout(set = 0, binding = 6, std430) writeonly buffer Record { float v[]; } b_record;
// The G-buffer's ids: object (x), material, primitive, hit flag.
layout(set = 0, binding = 7, rgba32ui) uniform readonly uimage2D u_ids;

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
    vec4 nr = input_normal_roughness(pixel);
    put3(RECORD_DEMODULATED, pixel, s, input_demodulated(pixel));
    put3(RECORD_ALBEDO, pixel, s, input_albedo(pixel));
    put3(RECORD_EMISSION, pixel, s, input_emission(pixel));
    put3(RECORD_NORMAL, pixel, s, nr.xyz);
    put(RECORD_ROUGHNESS, pixel, s, nr.w);
    put(RECORD_DEPTH, pixel, s, input_depth(pixel));
    put3(RECORD_MOTION, pixel, s, input_motion(pixel));
    put(RECORD_OBJECT, pixel, s, float(imageLoad(u_ids, pixel).x & OBJECT_BITS));
}
