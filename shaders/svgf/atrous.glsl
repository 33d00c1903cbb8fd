// One iteration of SVGF's edge-avoiding a-trous wavelet filter, its taps read from shared memory.
// Requires math.glsl, image_coords.glsl, svgf/common.glsl, the images `u_in` (illumination rgb,
// standard deviation a: svgf_pack_filtered), `u_depth`, `u_normal_roughness`, `u_depth_slope`
// (svgf/variance.comp), and `params` with `step` (a power of two), `sigma_z`, `sigma_n`,
// `sigma_l`. Declares the workgroup size; the dispatch is `threads` in
// passes/src/denoise/svgf/atrous.rs.
//
// Work layout. A workgroup of 16x16 invocations filters pixels `step` apart in y (one residue of
// y modulo `step`) and, in x, runs of `run` = min(step, 4) adjacent pixels `step` apart (run
// adjacent residues of x modulo `step`), so that the 5x5 taps of all its pixels, +-1 and +-2
// steps away, fall on one dense tile of cells: 20 rows of `run` * (16 / run + 4) columns (20 for
// step 1, 24 for step 2, 32 from step 4 on), the workgroup's own pixels and a halo of two steps.
// The tile is read from memory once (1.6, 1.9 or 2.5 texels of each image per pixel instead of 25)
// and its 24 taps per pixel come from shared memory. The runs of 4 adjacent pixels keep the reads
// of large steps whole 32-byte sectors of the rgba16f images (a single residue would use 8 of
// every 32 bytes fetched). Cell (column, row) is pixel
//     origin + (column % run, 0) + step * (column / run, row),
// and invocation (x, y) filters cell (x + 2 run, y + 2).
#ifndef LUCID_SVGF_ATROUS_GLSL
#define LUCID_SVGF_ATROUS_GLSL

#define SVGF_ATROUS_GROUP 16
layout(local_size_x = SVGF_ATROUS_GROUP, local_size_y = SVGF_ATROUS_GROUP) in;

// The taps reach two steps beyond the workgroup's pixels.
const int SVGF_ATROUS_HALO = 2;
const int SVGF_ATROUS_ROWS = SVGF_ATROUS_GROUP + 2 * SVGF_ATROUS_HALO;
// The longest run of adjacent residues, and the widest tile (that of the longest run).
const int SVGF_ATROUS_MAX_RUN = 4;
const int SVGF_ATROUS_COLUMNS =
    SVGF_ATROUS_MAX_RUN * (SVGF_ATROUS_GROUP / SVGF_ATROUS_MAX_RUN + 2 * SVGF_ATROUS_HALO);
// Row stride of the depths: 16 modulo 32 words, so that the two rows of 16 cells a subgroup of 32
// reads fall in different banks.
const int SVGF_ATROUS_DEPTH_STRIDE = 48;

// Per cell, as the halves the images hold: illumination rg, illumination b and standard
// deviation, normal xy, normal z (and 16 unused bits).
shared uvec4 s_svgf_texel[SVGF_ATROUS_ROWS * SVGF_ATROUS_COLUMNS];
// Per cell, the view depth; 0 outside the image, which the taps skip as they skip the sky.
shared float s_svgf_depth[SVGF_ATROUS_ROWS * SVGF_ATROUS_DEPTH_STRIDE];

// Where a workgroup's tile lies (see the layout above).
struct SvgfAtrousTile {
    ivec2 origin;
    int run;
    int columns;
};

SvgfAtrousTile svgf_atrous_tile() {
    int step = params.step;
    SvgfAtrousTile tile;
    tile.run = min(step, SVGF_ATROUS_MAX_RUN);
    tile.columns = tile.run * (SVGF_ATROUS_GROUP / tile.run + 2 * SVGF_ATROUS_HALO);
    // Workgroups go through the runs of residues first, then the tiles of each residue's grid.
    int runs = step / tile.run;
    ivec2 group = ivec2(gl_WorkGroupID.xy);
    ivec2 residue = ivec2(group.x % runs * tile.run, group.y % step);
    ivec2 first = ivec2(group.x / runs * (SVGF_ATROUS_GROUP / tile.run),
                        group.y / step * SVGF_ATROUS_GROUP);
    tile.origin = residue + step * (first - SVGF_ATROUS_HALO);
    return tile;
}

ivec2 svgf_atrous_cell_pixel(SvgfAtrousTile tile, ivec2 cell) {
    return tile.origin + ivec2(cell.x % tile.run, 0)
        + params.step * ivec2(cell.x / tile.run, cell.y);
}

uvec4 svgf_atrous_texel(ivec2 cell) {
    return s_svgf_texel[cell.y * SVGF_ATROUS_COLUMNS + cell.x];
}

vec4 svgf_atrous_color(uvec4 texel) {
    return vec4(unpackHalf2x16(texel.x), unpackHalf2x16(texel.y));
}

vec3 svgf_atrous_normal(uvec4 texel) {
    return vec3(unpackHalf2x16(texel.z), unpackHalf2x16(texel.w).x);
}

float svgf_atrous_depth(ivec2 cell) {
    return s_svgf_depth[cell.y * SVGF_ATROUS_DEPTH_STRIDE + cell.x];
}

// Reads the tile into shared memory, the workgroup's invocations taking every 256th cell.
void svgf_atrous_load(SvgfAtrousTile tile, ivec2 size) {
    int cells = tile.columns * SVGF_ATROUS_ROWS;
    for (int i = int(gl_LocalInvocationIndex); i < cells;
         i += SVGF_ATROUS_GROUP * SVGF_ATROUS_GROUP) {
        ivec2 cell = ivec2(i % tile.columns, i / tile.columns);
        ivec2 q = svgf_atrous_cell_pixel(tile, cell);
        uvec4 texel = uvec4(0u);
        float z = 0.0;
        if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size))) {
            vec4 c = imageLoad(u_in, q);
            vec3 n = imageLoad(u_normal_roughness, q).xyz;
            texel = uvec4(packHalf2x16(c.rg), packHalf2x16(c.ba), packHalf2x16(n.xy),
                          packHalf2x16(vec2(n.z, 0.0)));
            z = imageLoad(u_depth, q).x;
        }
        s_svgf_texel[cell.y * SVGF_ATROUS_COLUMNS + cell.x] = texel;
        s_svgf_depth[cell.y * SVGF_ATROUS_DEPTH_STRIDE + cell.x] = z;
    }
}

// The 3x3 Gaussian of the variance around `pixel`, clamped at the image's border: the luminance
// scale of the edge stopping. From step 2 on a pixel's neighbours are not in its tile: they are
// read from `u_in`.
float svgf_blurred_variance(ivec2 pixel, ivec2 size) {
    const float gauss[2] = float[2](0.25, 0.125);
    float blurred_variance = 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = clamp(pixel + ivec2(dx, dy), ivec2(0), size - 1);
            blurred_variance += gauss[abs(dx)] * gauss[abs(dy)] * 4.0
                * svgf_filtered_variance(imageLoad(u_in, q));
        }
    }
    return blurred_variance;
}

// The 5x5 B3-spline kernel taps `params.step` pixels apart around tile cell `cell`, weighted by
// depth (with the centre's `slope`), normal and luminance edge stopping (the luminance scale is
// the standard deviation from `blurred_variance`). Variance is filtered with the squared weights.
vec4 svgf_atrous_filter(int run, ivec2 cell, float slope, float blurred_variance) {
    uvec4 texel = svgf_atrous_texel(cell);
    vec4 centre = svgf_atrous_color(texel);
    float z = svgf_atrous_depth(cell);
    if (z <= 0.0) {
        return centre;
    }
    float variance = svgf_filtered_variance(centre);
    vec3 n = svgf_atrous_normal(texel);
    float l = luminance(centre.rgb);
    float sigma_l_std = params.sigma_l * sqrt(max(blurred_variance, 0.0));
    const float kernel[3] = float[3](0.375, 0.25, 0.0625);
    vec3 color_sum = centre.rgb;
    float variance_sum = variance;
    float weight_sum = 1.0;
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            if (dx == 0 && dy == 0) {
                continue;
            }
            ivec2 q = cell + ivec2(dx * run, dy);
            float zq = svgf_atrous_depth(q);
            if (zq <= 0.0) {
                continue;
            }
            uvec4 tap_texel = svgf_atrous_texel(q);
            vec4 tap = svgf_atrous_color(tap_texel);
            float w = kernel[abs(dx)] * kernel[abs(dy)] / (kernel[0] * kernel[0])
                * svgf_edge_weight(z, zq, slope, float(params.step) * length(vec2(dx, dy)), n,
                                   svgf_atrous_normal(tap_texel), l, luminance(tap.rgb),
                                   sigma_l_std, params.sigma_z, params.sigma_n);
            color_sum += w * tap.rgb;
            variance_sum += w * w * svgf_filtered_variance(tap);
            weight_sum += w;
        }
    }
    return svgf_pack_filtered(color_sum / weight_sum, variance_sum / (weight_sum * weight_sum));
}

// Filters this invocation's pixel: returns false if it lies outside the image, else its filtered
// texel (`filtered`, at `pixel`). The pixel's own reads (depth slope, blurred variance) go out
// before the tile's, so that they wait together.
bool svgf_atrous(out ivec2 pixel, out vec4 filtered) {
    ivec2 size = imageSize(u_in);
    SvgfAtrousTile tile = svgf_atrous_tile();
    ivec2 cell = ivec2(gl_LocalInvocationID.xy)
        + ivec2(SVGF_ATROUS_HALO * tile.run, SVGF_ATROUS_HALO);
    pixel = svgf_atrous_cell_pixel(tile, cell);
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
