// Bilinear upsampling as PyTorch's F.interpolate(mode="bilinear", align_corners=False) to a given
// size: the two source rows and columns of a pixel and its weights towards the second ones.
#ifndef LUCID_NEURAL_UPSAMPLE_GLSL
#define LUCID_NEURAL_UPSAMPLE_GLSL

// The taps of `pixel` of an image of `size` in a source image of `source` pixels: rows and columns
// `i0` and `i1`, weights `f` towards `i1`.
void bilinear_taps(ivec2 pixel, ivec2 size, ivec2 source, out ivec2 i0, out ivec2 i1, out vec2 f) {
    vec2 scale = vec2(source) / vec2(size);
    vec2 src = max((vec2(pixel) + 0.5) * scale - 0.5, vec2(0.0));
    i0 = ivec2(src);
    i1 = min(i0 + 1, source - 1);
    f = src - vec2(i0);
}

// The value at the taps' weights `f` of the four taps: `c01` at row i0 and column i1, and so on.
vec3 bilinear_mix(vec3 c00, vec3 c01, vec3 c10, vec3 c11, vec2 f) {
    return mix(mix(c00, c01, f.x), mix(c10, c11, f.x), f.y);
}

#endif
