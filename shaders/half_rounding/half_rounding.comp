#version 460
// The ways shaders round to half precision, applied to a buffer of floats, one vec4 an invocation:
// the learned denoiser's packing (neural/tensor.glsl, `pack_channels`), the round trip through it
// that rounds in place, and common/half_round.glsl's `round_to_half` stored in an rgba16f image
// (IMAGE_WIDTH texels a row), as SVGF stores its a-trous steps. Tests check that each rounds to
// nearest, ties to even, as training does.
#include "common/half_round.glsl"
#include "neural/tensor.glsl"

layout(local_size_x = 64) in;

layout(constant_id = 0) const uint IMAGE_WIDTH = 256u;

layout(set = 0, binding = 0, std430) readonly buffer Values { vec4 v[]; } b_values;
layout(set = 0, binding = 1, std430) writeonly buffer Packed { uvec2 v[]; } b_packed;
layout(set = 0, binding = 2, std430) writeonly buffer Rounded { vec4 v[]; } b_rounded;
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D u_stored;

layout(push_constant) uniform Params {
    uint count;  // vec4s in b_values
} params;

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index < params.count) {
        vec4 value = b_values.v[index];
        b_packed.v[index] = pack_channels(value);
        b_rounded.v[index] = unpack_channels(pack_channels(value));
        imageStore(u_stored, ivec2(index % IMAGE_WIDTH, index / IMAGE_WIDTH), round_to_half(value));
    }
}
