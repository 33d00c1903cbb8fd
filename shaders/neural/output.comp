#version 460
// The learned denoiser's output (training/model.py, end of `step`): the network's log radiance
// blended with the reprojected history by the mask times a learned weight, kept for the next frame,
// and re-modulated by the first hits' albedo plus emission averaged over time (features.comp). The
// direct decoder's log radiance and blend weight are the output layer's channels
// 0-3; the kernel-predicting decoder's log radiance is the full scale's filtered radiance
// composited with the half scale's detail (kernel_detail.comp) by channel 25 of its head, the
// blend weight channel 26.
#include "common/image_coords.glsl"
#include "neural/tensor.glsl"
#include "neural/upsample.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const bool KERNEL = false;
layout(constant_id = 1) const uint NET_CHANNELS = 4;  // the output layer's channels, padded to 4

layout(set = 0, binding = 1, std430) readonly buffer Features { uvec2 v[]; } b_features;
layout(set = 0, binding = 2, std430) readonly buffer Net { uvec2 v[]; } b_net;
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D u_output;
layout(set = 0, binding = 4, rgba32f) uniform writeonly image2D u_radiance;
// The kernel decoder's full-scale filtered radiance and the half scale's detail (float32 rgb).
layout(set = 0, binding = 5, std430) readonly buffer Filtered { vec4 v[]; } b_filtered;
layout(set = 0, binding = 6, std430) readonly buffer Detail { vec4 v[]; } b_detail;
// The first hits' albedo and log(1 + emission) averaged over time (`antialias_surface`).
layout(set = 0, binding = 7, rgba32f) uniform readonly image2D u_albedo_mean;
layout(set = 0, binding = 8, rgba32f) uniform readonly image2D u_emission_mean;

layout(push_constant) uniform Params {
    uint width;
    uint height;
} params;

// The kernel decoder's log radiance at `pixel` (before rounding): filtered + sigmoid(a) * up(detail).
vec3 composited(ivec2 pixel, float a) {
    ivec2 size = ivec2(params.width, params.height);
    ivec2 coarse = (size + 1) / 2;
    ivec2 i0, i1;
    vec2 f;
    bilinear_taps(pixel, size, coarse, i0, i1, f);
    vec3 top = mix(b_detail.v[i0.y * coarse.x + i0.x].rgb, b_detail.v[i0.y * coarse.x + i1.x].rgb, f.x);
    vec3 bottom = mix(b_detail.v[i1.y * coarse.x + i0.x].rgb, b_detail.v[i1.y * coarse.x + i1.x].rgb, f.x);
    vec3 filtered = b_filtered.v[pixel.y * size.x + pixel.x].rgb;
    return filtered + mix(top, bottom, f.y) / (1.0 + exp(-a));
}

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
    vec3 predicted;
    float blend_logit;
    if (KERNEL) {
        // Channels 24-27: the last kernel tap, the compositing weight, the blend weight, padding.
        vec4 o = unpack_channels(b_net.v[tensor_index(pixel, params.width, NET_CHANNELS / 4u, 6u)]);
        predicted = unpack_channels(pack_channels(vec4(composited(pixel, o.y), 0.0))).rgb;
        blend_logit = o.z;
    } else {
        vec4 o = unpack_channels(b_net.v[tensor_index(pixel, params.width, NET_CHANNELS / 4u, 0u)]);
        predicted = o.rgb;
        blend_logit = o.w;
    }
    float blend = mask / (1.0 + exp(-blend_logit));
    vec3 log_out = max(predicted * (1.0 - blend) + warped * blend, vec3(0.0));
    log_out = unpack_channels(pack_channels(vec4(log_out, 0.0))).rgb;
    imageStore(u_output, pixel, vec4(log_out, 0.0));
    vec3 albedo = imageLoad(u_albedo_mean, pixel).rgb;
    vec3 emission = exp(imageLoad(u_emission_mean, pixel).rgb) - 1.0;
    imageStore(u_radiance, pixel, vec4((exp(log_out) - 1.0) * albedo + emission, 1.0));
}
