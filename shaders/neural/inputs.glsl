// The learned denoiser's per-pixel inputs, read from the light transport's surface images and the
// G-buffer where they are used (features.comp) or gathered into a record (record.comp, what
// `lucid dataset` stores): the channels of a record (record.glsl), one function per group. The
// includer defines INPUTS_BINDING, the first of the six consecutive bindings of set 0.
#ifndef LUCID_NEURAL_INPUTS_GLSL
#define LUCID_NEURAL_INPUTS_GLSL

layout(set = 0, binding = INPUTS_BINDING, rgba32f) uniform readonly image2D u_demodulated;
layout(set = 0, binding = INPUTS_BINDING + 1, rgba32f) uniform readonly image2D u_albedo;
layout(set = 0, binding = INPUTS_BINDING + 2, rgba32f) uniform readonly image2D u_emission;
layout(set = 0, binding = INPUTS_BINDING + 3, rgba16f) uniform readonly image2D u_normal_roughness;
layout(set = 0, binding = INPUTS_BINDING + 4, r32f) uniform readonly image2D u_depth;
layout(set = 0, binding = INPUTS_BINDING + 5, rgba16f) uniform readonly image2D u_motion;

// The largest half float: the demodulated radiance and the emission are clamped to it.
const float INPUT_MAX = 65504.0;

// The demodulated radiance (RECORD_DEMODULATED).
vec3 input_demodulated(ivec2 pixel) {
    return min(imageLoad(u_demodulated, pixel).rgb, vec3(INPUT_MAX));
}

// The first hit's albedo (RECORD_ALBEDO).
vec3 input_albedo(ivec2 pixel) {
    return imageLoad(u_albedo, pixel).rgb;
}

// The radiance the first hit emits towards the camera (RECORD_EMISSION).
vec3 input_emission(ivec2 pixel) {
    return min(imageLoad(u_emission, pixel).rgb, vec3(INPUT_MAX));
}

// The G-buffer normal (xyz, RECORD_NORMAL) and roughness (w, RECORD_ROUGHNESS).
vec4 input_normal_roughness(ivec2 pixel) {
    return imageLoad(u_normal_roughness, pixel);
}

// The view-space depth, 0 for the sky (RECORD_DEPTH).
float input_depth(ivec2 pixel) {
    return imageLoad(u_depth, pixel).x;
}

// The offset to last frame's pixel (xy) and last frame's depth of the point (z) (RECORD_MOTION).
vec3 input_motion(ivec2 pixel) {
    return imageLoad(u_motion, pixel).xyz;
}

#endif
