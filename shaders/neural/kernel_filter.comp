#version 460
// One scale of the kernel-predicting decoder (training/kernel_model.py, `apply_kernel`): the log
// radiance of that scale filtered by the per-pixel 5x5 kernel whose weights are the softmax of the
// first 25 channels of the head's output (taps row-major, borders replicated). The full scale reads
// the log radiance from the input features (channels 0-2), the coarser ones the radiance
// features.comp pooled. Writes float32 rgb.
#include "neural/tensor.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(constant_id = 0) const uint LOGIT_CHANNELS = 28;  // the head's output channels, padded to 4
layout(constant_id = 1) const bool FROM_FEATURES = true;

const int RADIUS = 2;
const uint TAPS = 25u;

layout(set = 0, binding = 0, std430) readonly buffer Logits { uvec2 v[]; } b_logits;
layout(set = 0, binding = 1, std430) readonly buffer Features { uvec2 v[]; } b_features;
layout(set = 0, binding = 2, std430) readonly buffer Radiance { vec4 v[]; } b_radiance;
layout(set = 0, binding = 3, std430) writeonly buffer Out { vec4 v[]; } b_out;

layout(push_constant) uniform Params {
    uint width;  // this scale's size
    uint height;
} params;

vec3 log_radiance(ivec2 q) {
    if (FROM_FEATURES) {
        return unpack_channels(b_features.v[tensor_index(q, params.width, FEATURE_GROUPS, 0u)]).rgb;
    }
    return b_radiance.v[q.y * int(params.width) + q.x].rgb;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = ivec2(params.width, params.height);
    if (any(greaterThanEqual(pixel, size))) {
        return;
    }
    uint at = tensor_index(pixel, params.width, LOGIT_CHANNELS / 4u, 0u);
    float logits[TAPS];
    float largest = -1e30;
    for (uint c4 = 0u; c4 < (TAPS + 3u) / 4u; ++c4) {
        vec4 v = unpack_channels(b_logits.v[at + c4]);
        for (uint k = 0u; k < 4u && c4 * 4u + k < TAPS; ++k) {
            logits[c4 * 4u + k] = v[k];
            largest = max(largest, v[k]);
        }
    }
    vec3 sum = vec3(0.0);
    float weight_sum = 0.0;
    for (uint t = 0u; t < TAPS; ++t) {
        ivec2 q = clamp(pixel + ivec2(int(t % 5u) - RADIUS, int(t / 5u) - RADIUS), ivec2(0), size - 1);
        float w = exp(logits[t] - largest);
        sum += w * log_radiance(q);
        weight_sum += w;
    }
    b_out.v[pixel.y * size.x + pixel.x] = vec4(sum / weight_sum, 0.0);
}
