// One iteration of SVGF's edge-avoiding a-trous wavelet filter, its taps read from shared memory
// (the tile of common/atrous_tile.glsl, which declares the workgroup size). Requires math.glsl,
// image_coords.glsl, svgf/common.glsl, the sampler `u_in` (illumination rgb,
// standard deviation a: svgf_pack_filtered; clamped to its edge), the images `u_depth`,
// `u_normal_roughness`, `u_depth_slope` (svgf/variance.comp), and `params` with `step` (a power
// of two), `sigma_z`, `sigma_n`, `sigma_l`.
#ifndef LUCID_SVGF_ATROUS_GLSL
#define LUCID_SVGF_ATROUS_GLSL

#include "common/atrous_tile.glsl"

// Per cell, as the halves the images hold: illumination rg, illumination b and standard
// deviation, normal xy, normal z (and 16 unused bits).
shared uvec4 s_svgf_texel[ATROUS_ROWS * ATROUS_COLUMNS];

// Per cell, the view depth and the illumination's luminance. The depth is -infinity where no
// surface is (the sky, outside the image): a tap there weighs exactly 0, as if skipped.
shared vec2 s_svgf_depth_luminance[ATROUS_ROWS * ATROUS_COLUMNS];

uvec4 svgf_atrous_texel(ivec2 cell) {
    return s_svgf_texel[atrous_cell_index(cell)];
}

vec4 svgf_atrous_color(uvec4 texel) {
    return vec4(unpackHalf2x16(texel.x), unpackHalf2x16(texel.y));
}

vec3 svgf_atrous_normal(uvec4 texel) {
    return vec3(unpackHalf2x16(texel.z), unpackHalf2x16(texel.w).x);
}

// The depth of a cell where no surface is: -infinity.
float svgf_atrous_no_surface() {
    return -uintBitsToFloat(0x7f800000u);
}

vec2 svgf_atrous_depth_luminance(ivec2 cell) {
    return s_svgf_depth_luminance[atrous_cell_index(cell)];
}

// Reads tile cell `cell` into shared memory: no surface outside the image.
void svgf_atrous_load_cell(AtrousTile tile, ivec2 cell, ivec2 size) {
    ivec2 q = atrous_cell_pixel(tile, cell);
    uvec4 texel = uvec4(0u);
    vec2 depth_luminance = vec2(svgf_atrous_no_surface(), 0.0);
    if (inside_image(q, size)) {
        vec4 c = texelFetch(u_in, q, 0);
        vec3 n = imageLoad(u_normal_roughness, q).xyz;
        texel = uvec4(packHalf2x16(c.rg), packHalf2x16(c.ba), packHalf2x16(n.xy),
                      packHalf2x16(vec2(n.z, 0.0)));
        float z = imageLoad(u_depth, q).x;
        depth_luminance = vec2(z > 0.0 ? z : svgf_atrous_no_surface(), luminance(c.rgb));
    }
    s_svgf_texel[atrous_cell_index(cell)] = texel;
    s_svgf_depth_luminance[atrous_cell_index(cell)] = depth_luminance;
}

// Reads the tile into shared memory, invocation (x, y) taking the cells (x + 16 i, y + 16 j).
void svgf_atrous_load(AtrousTile tile, ivec2 size) {
    for (int row = int(gl_LocalInvocationID.y); row < ATROUS_ROWS; row += ATROUS_GROUP) {
        for (int column = int(gl_LocalInvocationID.x); column < tile.columns;
             column += ATROUS_GROUP) {
            svgf_atrous_load_cell(tile, ivec2(column, row), size);
        }
    }
}

// The standard deviations of the 3x3 pixels around `pixel`, row by row, clamped at the image's
// border (by the sampler): four gathers of 2x2 texels, the first ending at `pixel` (its
// coordinate is the corner between pixel - 1 and pixel). From step 2 on a pixel's neighbours
// are not in its tile.
float[9] svgf_atrous_deviations(ivec2 pixel, ivec2 size) {
    vec2 corner = vec2(pixel) / vec2(size);
    // Each gather's texels: x (left, bottom), y (right, bottom), z (right, top), w (left, top).
    vec4 top_left = textureGather(u_in, corner, 3);
    vec4 top_right = textureGatherOffset(u_in, corner, ivec2(2, 0), 3);
    vec4 bottom_left = textureGatherOffset(u_in, corner, ivec2(0, 2), 3);
    vec4 bottom_right = textureGatherOffset(u_in, corner, ivec2(2, 2), 3);
    return float[9](top_left.w, top_left.z, top_right.w, top_left.x, top_left.y, top_right.x,
                    bottom_left.w, bottom_left.z, bottom_right.w);
}

// The 3x3 Gaussian of the variance around `pixel`, clamped at the image's border: the luminance
// scale of the edge stopping.
float svgf_blurred_variance(ivec2 pixel, ivec2 size) {
    const float gauss[2] = float[2](0.25, 0.125);
    float deviations[9] = svgf_atrous_deviations(pixel, size);
    float blurred_variance = 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            float deviation = deviations[3 * dy + dx + 4];
            blurred_variance += gauss[abs(dx)] * gauss[abs(dy)] * 4.0 * (deviation * deviation);
        }
    }
    return blurred_variance;
}

// log2 of the 5x5 B3-spline kernel's 1D weights 0, 1 and 2 taps from the centre, relative to the
// centre's (3/8, 1/4, 1/16 over 3/8).
const float SVGF_ATROUS_LOG2_KERNEL[3] = float[3](0.0, log2(0.25 / 0.375), log2(0.0625 / 0.375));
const float SVGF_LOG2E = 1.44269504088896;

// What the edge-stopping weights of a centre pixel's taps divide by, as rates of exp2: each tap's
// weight is exp2(log2 kernel + sigma_n log2(max(n.n_q, 0)) - |z - z_q| depth_rate(distance)
// - |l - l_q| luminance_rate), the kernel weight times svgf_edge_weight in one exp2.
struct SvgfAtrousRates {
    // The depth rate is log2(e) / (depth_slope * distance in taps + depth_offset).
    float depth_slope;
    float depth_offset;
    float luminance_rate;
};

SvgfAtrousRates svgf_atrous_rates(float z, float slope, float blurred_variance) {
    SvgfAtrousRates rates;
    rates.depth_slope = params.sigma_z * slope * float(params.step);
    rates.depth_offset = 1e-3 * z + 1e-6;
    float sigma_l_std = params.sigma_l * sqrt(max(blurred_variance, 0.0));
    rates.luminance_rate = SVGF_LOG2E / (sigma_l_std + 1e-8);
    return rates;
}

// The weight of the tap (dx, dy) taps away, at depth and luminance `tap_zl` and normal `tap_n`,
// of a centre at `zl` and `n` (0 where the tap's depth is -infinity, no surface).
float svgf_atrous_weight(SvgfAtrousRates rates, ivec2 d, vec2 zl, vec3 n, vec2 tap_zl,
                         vec3 tap_n) {
    float depth_rate = SVGF_LOG2E / (rates.depth_slope * length(vec2(d)) + rates.depth_offset);
    float exponent = SVGF_ATROUS_LOG2_KERNEL[abs(d.x)] + SVGF_ATROUS_LOG2_KERNEL[abs(d.y)]
        + params.sigma_n * log2(max(dot(n, tap_n), 0.0))
        - abs(zl.x - tap_zl.x) * depth_rate - abs(zl.y - tap_zl.y) * rates.luminance_rate;
    return exp2(exponent);
}

// The 5x5 B3-spline kernel taps `params.step` pixels apart around tile cell `cell`, weighted by
// depth (with the centre's `slope`), normal and luminance edge stopping (the luminance scale is
// the standard deviation from `blurred_variance`): svgf_atrous_weight. Variance is filtered with
// the squared weights.
vec4 svgf_atrous_filter(int run, ivec2 cell, float slope, float blurred_variance) {
    uvec4 texel = svgf_atrous_texel(cell);
    vec4 centre = svgf_atrous_color(texel);
    vec2 zl = svgf_atrous_depth_luminance(cell);
    if (zl.x <= 0.0) {
        return centre;
    }
    vec3 n = svgf_atrous_normal(texel);
    SvgfAtrousRates rates = svgf_atrous_rates(zl.x, slope, blurred_variance);
    vec3 color_sum = centre.rgb;
    float variance_sum = svgf_filtered_variance(centre);
    float weight_sum = 1.0;
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            if (dx == 0 && dy == 0) {
                continue;
            }
            ivec2 q = cell + ivec2(dx * run, dy);
            uvec4 tap_texel = svgf_atrous_texel(q);
            vec4 tap = svgf_atrous_color(tap_texel);
            float w = svgf_atrous_weight(rates, ivec2(dx, dy), zl, n,
                                         svgf_atrous_depth_luminance(q),
                                         svgf_atrous_normal(tap_texel));
            color_sum += w * tap.rgb;
            // w^2 times the variance, the square of the standard deviation the texel holds.
            float weighted_deviation = w * tap.a;
            variance_sum += weighted_deviation * weighted_deviation;
            weight_sum += w;
        }
    }
    return svgf_pack_filtered(color_sum / weight_sum, variance_sum / (weight_sum * weight_sum));
}

// Filters this invocation's pixel: returns false if it lies outside the image, else its filtered
// texel (`filtered`, at `pixel`). The pixel's own reads (depth slope, blurred variance) go out
// before the tile's, so that they wait together.
bool svgf_atrous(out ivec2 pixel, out vec4 filtered) {
    ivec2 size = textureSize(u_in, 0);
    AtrousTile tile = atrous_tile(params.step);
    ivec2 cell = atrous_own_cell(tile);
    pixel = atrous_cell_pixel(tile, cell);
    bool inside = pixel_in_bounds(pixel, size);
    float slope = 0.0;
    float blurred_variance = 0.0;
    if (inside) {
        slope = imageLoad(u_depth_slope, pixel).x;
        blurred_variance = svgf_blurred_variance(pixel, size);
    }
    svgf_atrous_load(tile, size);
    barrier();
    if (inside) {
        filtered = svgf_atrous_filter(tile.run, cell, slope, blurred_variance);
    }
    return inside;
}

#endif
