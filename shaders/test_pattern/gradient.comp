#version 460
// Writes a test pattern: red = x / width, green = y / height, blue = checkerboard, scaled by `gain`.
#include "common/image_coords.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform writeonly image2D u_out;

layout(push_constant) uniform Params {
    float gain;
    uint checker;
} params;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(u_out);
    if (!pixel_in_bounds(pixel, size)) {
        return;
    }
    vec2 uv = vec2(pixel) / vec2(size);
    float check = float(((pixel.x / int(params.checker)) + (pixel.y / int(params.checker))) & 1);
    imageStore(u_out, pixel, vec4(uv * params.gain, check * params.gain, 1.0));
}
