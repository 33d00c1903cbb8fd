// An a-trous step of the learned denoiser's gated filter (training/model.py, `atrous`): the
// output's illumination filtered by the 5x5 B-spline kernel with its taps STEP pixels apart (the
// image's edge pixels repeated beyond it), each tap weighed by the agreement of the G-buffer
// normals, max(dot, 0)^128, and of the illumination's luminance, exp(-|l_q - l_p| / (SIGMA l_p +
// 1e-4)); a pixel whose taps all weigh nothing (the sky: no normal) keeps its value. The taps come
// from shared memory, the tile of common/atrous_tile.glsl (STEP a power of two), each cell holding
// its pixel's illumination and luminance in half precision (8 bytes: their relative error, 2^-11,
// is a two-hundredth of the luminance weight's scale, 0.1) and its unit normal in three float32
// arrays (12 bytes: the normals' weight, a 128th power, needs their precision); the sums are
// float32. With ATROUS_LAST (atrous_last.comp) the step is the last: it blends the output's
// illumination with its result by the gate and re-modulates it by the first hits' albedo plus
// emission averaged over time (features.comp), as output.comp does without the filter. The
// includer defines the version.
#include "common/image_coords.glsl"
#include "common/atrous_tile.glsl"

// The illumination to filter (rgb; the first step's alpha is the gate, not read).
layout(set = 0, binding = 0, rgba32f) uniform readonly image2D u_in;
// The G-buffer normal (xyz) and roughness (w, not read).
layout(set = 0, binding = 1, rgba16f) uniform readonly image2D u_normal_roughness;
#ifdef ATROUS_LAST
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D u_radiance;
// The output's illumination (rgb) and its gate (a), from output_atrous.comp.
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D u_illumination;
// The first hits' albedo and log(1 + emission) averaged over time (`antialias_surface`).
layout(set = 0, binding = 4, rgba32f) uniform readonly image2D u_albedo_mean;
layout(set = 0, binding = 5, rgba32f) uniform readonly image2D u_emission_mean;
#else
layout(set = 0, binding = 2, rgba32f) uniform writeonly image2D u_out;
#endif

layout(push_constant) uniform Params {
    uint width;
    uint height;
    uint step;  // the taps' spacing in pixels, a power of two
} params;

// The luminance's edge-stopping scale (`ATROUS_SIGMA` in training/model.py).
const float SIGMA = 0.1;
const float B_SPLINE[5] = float[5](1.0 / 16.0, 1.0 / 4.0, 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);

// Per cell: the illumination (rgb) and its luminance (a), as packHalf2x16 pairs; the unit
// normal's components.
shared uvec2 s_illumination[ATROUS_ROWS * ATROUS_COLUMNS];
shared float s_normal_x[ATROUS_ROWS * ATROUS_COLUMNS];
shared float s_normal_y[ATROUS_ROWS * ATROUS_COLUMNS];
shared float s_normal_z[ATROUS_ROWS * ATROUS_COLUMNS];

// A cell's illumination (rgb) and luminance (a).
vec4 cell_illumination(int at) {
    uvec2 packed = s_illumination[at];
    return vec4(unpackHalf2x16(packed.x), unpackHalf2x16(packed.y));
}

// A cell's unit normal.
vec3 cell_normal(int at) {
    return vec3(s_normal_x[at], s_normal_y[at], s_normal_z[at]);
}

// x^128, by squaring.
float pow128(float x) {
    for (int i = 0; i < 7; ++i) {
        x *= x;
    }
    return x;
}

// Reads the tile into shared memory, invocation (x, y) taking the cells (x + 16 i, y + 16 j);
// a cell beyond the image holds the image's nearest pixel.
void load_tile(AtrousTile tile, ivec2 size) {
    for (int row = int(gl_LocalInvocationID.y); row < ATROUS_ROWS; row += ATROUS_GROUP) {
        for (int column = int(gl_LocalInvocationID.x); column < tile.columns;
             column += ATROUS_GROUP) {
            ivec2 cell = ivec2(column, row);
            ivec2 q = clamp(atrous_cell_pixel(tile, cell), ivec2(0), size - 1);
            vec3 illumination = imageLoad(u_in, q).rgb;
            vec3 n = imageLoad(u_normal_roughness, q).xyz;
            float l = dot(illumination, vec3(0.2126, 0.7152, 0.0722));
            int at = atrous_cell_index(cell);
            s_illumination[at] = uvec2(packHalf2x16(illumination.rg),
                                       packHalf2x16(vec2(illumination.b, l)));
            n /= max(length(n), 1e-6);
            s_normal_x[at] = n.x;
            s_normal_y[at] = n.y;
            s_normal_z[at] = n.z;
        }
    }
}

void main() {
    ivec2 size = ivec2(params.width, params.height);
    AtrousTile tile = atrous_tile(int(params.step));
    ivec2 cell = atrous_own_cell(tile);
    ivec2 pixel = atrous_cell_pixel(tile, cell);
    load_tile(tile, size);
    barrier();
    if (!pixel_in_bounds(pixel, size)) {
        return;
    }
    vec4 centre = cell_illumination(atrous_cell_index(cell));
    vec3 normal = cell_normal(atrous_cell_index(cell));
    float scale = 1.0 / (SIGMA * centre.a + 1e-4);
    vec3 total = vec3(0.0);
    float weights = 0.0;
    for (int i = 0; i < 5; ++i) {
        for (int j = 0; j < 5; ++j) {
            int at = atrous_cell_index(cell + ivec2((j - 2) * tile.run, i - 2));
            vec4 tap = cell_illumination(at);
            float w_normal = pow128(max(dot(normal, cell_normal(at)), 0.0));
            float w_luminance = exp(-abs(tap.a - centre.a) * scale);
            float w = B_SPLINE[i] * B_SPLINE[j] * w_normal * w_luminance;
            total += w * tap.rgb;
            weights += w;
        }
    }
    // A pixel without weight keeps its value, as it was, not as the tile rounds it.
    vec3 filtered = weights > 1e-12 ? total / weights : imageLoad(u_in, pixel).rgb;
#ifdef ATROUS_LAST
    vec4 illumination = imageLoad(u_illumination, pixel);
    vec3 blended = mix(illumination.rgb, filtered, illumination.a);
    vec3 albedo = imageLoad(u_albedo_mean, pixel).rgb;
    vec3 emission = exp(imageLoad(u_emission_mean, pixel).rgb) - 1.0;
    imageStore(u_radiance, pixel, vec4(blended * albedo + emission, 1.0));
#else
    imageStore(u_out, pixel, vec4(filtered, 0.0));
#endif
}
