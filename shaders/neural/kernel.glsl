// One scale's filter of the kernel-predicting decoder (training/kernel_model.py, `apply_kernel`):
// the log radiance of that scale filtered by the per-pixel 5x5 kernel whose weights are the
// softmax of the first 25 channels of the head's output (taps row-major, borders replicated),
// float32; with LINEAR_MIX the same kernel also filters the radiance itself (exp(log) - 1). The
// includer defines the head's output and the radiance it filters (prototypes below):
// kernel_filter.comp at half and quarter resolution, output.comp at full resolution.
#ifndef LUCID_NEURAL_KERNEL_GLSL
#define LUCID_NEURAL_KERNEL_GLSL

// Whether the decoder also filters in linear space (the weights' `linear_mix`).
layout(constant_id = 8) const bool LINEAR_MIX = false;

const int KERNEL_RADIUS = 2;
const uint KERNEL_TAPS = 25u;

// Channels 4 * c4 .. 4 * c4 + 3 of the head's output at `pixel`.
vec4 kernel_logits(ivec2 pixel, uint c4);

// The log radiance the kernels filter at `pixel`.
vec3 kernel_radiance(ivec2 pixel);

// A scale's filtered radiance at a pixel: the mean of the log radiance and, with LINEAR_MIX, of
// the radiance (else 0).
struct KernelMeans {
    vec3 log_mean;
    vec3 linear_mean;
};

// The filtered radiance at `pixel` of a scale of `size`.
KernelMeans apply_kernel(ivec2 pixel, ivec2 size) {
    float logits[KERNEL_TAPS];
    float largest = -1e30;
    for (uint c4 = 0u; c4 < (KERNEL_TAPS + 3u) / 4u; ++c4) {
        vec4 v = kernel_logits(pixel, c4);
        for (uint k = 0u; k < 4u && c4 * 4u + k < KERNEL_TAPS; ++k) {
            logits[c4 * 4u + k] = v[k];
            largest = max(largest, v[k]);
        }
    }
    vec3 sum = vec3(0.0);
    vec3 linear_sum = vec3(0.0);
    float weight_sum = 0.0;
    for (uint t = 0u; t < KERNEL_TAPS; ++t) {
        ivec2 offset = ivec2(int(t % 5u) - KERNEL_RADIUS, int(t / 5u) - KERNEL_RADIUS);
        ivec2 q = clamp(pixel + offset, ivec2(0), size - 1);
        float w = exp(logits[t] - largest);
        vec3 r = kernel_radiance(q);
        sum += w * r;
        if (LINEAR_MIX) {
            linear_sum += w * (exp(r) - 1.0);
        }
        weight_sum += w;
    }
    return KernelMeans(sum / weight_sum, linear_sum / weight_sum);
}

#endif
