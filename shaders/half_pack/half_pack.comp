#version 460
// The learned denoiser's half-precision packing (neural/tensor.glsl, `pack_channels`) applied to a
// buffer of floats, one vec4 an invocation, and the round trip through it that the denoiser uses to
// round values to half precision in place: tests check that both round as training does.
#include "neural/tensor.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 0, std430) readonly buffer Values { vec4 v[]; } b_values;
layout(set = 0, binding = 1, std430) writeonly buffer Packed { uvec2 v[]; } b_packed;
layout(set = 0, binding = 2, std430) writeonly buffer Rounded { vec4 v[]; } b_rounded;

layout(push_constant) uniform Params {
    uint count;  // vec4s in b_values
} params;

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index < params.count) {
        vec4 value = b_values.v[index];
        b_packed.v[index] = pack_channels(value);
        b_rounded.v[index] = unpack_channels(pack_channels(value));
    }
}
