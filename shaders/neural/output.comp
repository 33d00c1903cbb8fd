#version 460
// The learned denoiser's output (training/model.py, end of `step`): the network's log radiance
// blended with the reprojected history by the mask times a learned weight, kept for the next frame,
// and re-modulated by the first hit's albedo plus its emission.
#include "common/image_coords.glsl"
#include "neural/record.glsl"
#include "neural/tensor.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, std430) readonly buffer Record { float v[]; } b_record;
layout(set = 0, binding = 1, std430) readonly buffer Features { uvec2 v[]; } b_features;
layout(set = 0, binding = 2, std430) readonly buffer Net { uvec2 v[]; } b_net;
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D u_output;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D u_radiance;

layout(push_constant) uniform Params {
    uint width;
    uint height;
} params;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = uvec2(params.width, params.height);
    if (!pixel_in_bounds(pixel, ivec2(size))) {
        return;
    }
    uint at = tensor_index(pixel, params.width, FEATURE_GROUPS, 0u);
    vec4 f2 = unpack_channels(b_features.v[at + 2u]);
    vec4 f3 = unpack_channels(b_features.v[at + 3u]);
    vec3 warped = vec3(f2.w, f3.xy);
    float mask = f3.z;
    vec4 o = unpack_channels(b_net.v[tensor_index(pixel, params.width, 1u, 0u)]);
    float blend = mask / (1.0 + exp(-o.w));
    vec3 log_out = max(o.rgb * (1.0 - blend) + warped * blend, vec3(0.0));
    log_out = unpack_channels(pack_channels(vec4(log_out, 0.0))).rgb;
    imageStore(u_output, pixel, vec4(log_out, 0.0));
    vec3 albedo = vec3(0.0);
    vec3 emission = vec3(0.0);
    for (uint i = 0u; i < 3u; ++i) {
        albedo[i] = b_record.v[record_index(RECORD_ALBEDO + i, pixel, size)];
        emission[i] = b_record.v[record_index(RECORD_EMISSION + i, pixel, size)];
    }
    imageStore(u_radiance, pixel, vec4((exp(log_out) - 1.0) * albedo + emission, 1.0));
}
