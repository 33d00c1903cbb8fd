// Activations of the learned denoiser: half-precision tensors, pixel-major with the channels of a
// pixel contiguous (NHWC), four channels packed in a uvec2 (packHalf2x16, so no 16-bit storage
// feature is needed). Mirrors training/model.py.
#ifndef LUCID_NEURAL_TENSOR_GLSL
#define LUCID_NEURAL_TENSOR_GLSL

// The network's input features (FEATURES in training/model.py and weights.rs) in groups of four.
const uint FEATURE_GROUPS = 6u;

// The index of channels 4*c4..4*c4+3 of `pixel` in a tensor `width` wide with `channels4` groups.
uint tensor_index(ivec2 pixel, uint width, uint channels4, uint c4) {
    return (uint(pixel.y) * width + uint(pixel.x)) * channels4 + c4;
}

vec4 unpack_channels(uvec2 v) {
    return vec4(unpackHalf2x16(v.x), unpackHalf2x16(v.y));
}

uvec2 pack_channels(vec4 v) {
    return uvec2(packHalf2x16(v.xy), packHalf2x16(v.zw));
}

// The kernel decoder's radiance at a coarser scale as kernel_filter.comp reads it: log(1 + `mean`)
// rounded to half precision (`pack_channels`), alpha 0.
vec4 log_pooled(vec3 mean) {
    return vec4(unpack_channels(pack_channels(vec4(log(vec3(1.0) + mean), 0.0))).rgb, 0.0);
}

#endif
