#version 460
// One a-trous iteration over the stratum gradients: a 3x3 box with taps `step` strata apart,
// summing the luminance differences and their normalisers, so that the ratio the temporal pass
// takes is a regional share of changed shading rather than one noisy sample.

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_in;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D u_out;

layout(push_constant) uniform Params {
    int step;
} params;

void main() {
    ivec2 cell = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_out);
    if (any(greaterThanEqual(cell, size))) {
        return;
    }
    vec2 sum = vec2(0.0);
    float count = 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = cell + ivec2(dx, dy) * params.step;
            if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size))) {
                sum += imageLoad(u_in, q).xy;
                count += 1.0;
            }
        }
    }
    imageStore(u_out, cell, vec4(sum / count, 0.0, 0.0));
}
