// One iteration of SVGF's edge-avoiding a-trous wavelet filter. Requires math.glsl,
// svgf/common.glsl, svgf/depth_slope.glsl, the images `u_in` (illumination rgb, variance a),
// `u_depth`, `u_normal_roughness`, and `params` with `step`, `sigma_z`, `sigma_n`, `sigma_l`.
// Texels are packed by svgf_pack_filtered (standard deviation in alpha).
#ifndef LUCID_SVGF_ATROUS_GLSL
#define LUCID_SVGF_ATROUS_GLSL

// The 5x5 B3-spline kernel taps `params.step` pixels apart, weighted by depth, normal and
// luminance edge stopping (the luminance scale is the 3x3-blurred standard deviation). Variance is
// filtered with the squared weights.
vec4 svgf_atrous(ivec2 pixel, ivec2 size) {
    vec4 centre = imageLoad(u_in, pixel);
    float z = imageLoad(u_depth, pixel).x;
    if (z <= 0.0) {
        return centre;
    }
    centre.a = svgf_filtered_variance(centre);
    vec3 n = imageLoad(u_normal_roughness, pixel).xyz;
    float slope = svgf_depth_slope(pixel, size);
    float l = luminance(centre.rgb);
    const float gauss[2] = float[2](0.25, 0.125);
    float blurred_variance = 0.0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            ivec2 q = clamp(pixel + ivec2(dx, dy), ivec2(0), size - 1);
            blurred_variance += gauss[abs(dx)] * gauss[abs(dy)] * 4.0 * svgf_filtered_variance(imageLoad(u_in, q));
        }
    }
    float sigma_l_std = params.sigma_l * sqrt(max(blurred_variance, 0.0));
    const float kernel[3] = float[3](0.375, 0.25, 0.0625);
    vec3 color_sum = centre.rgb;
    float variance_sum = centre.a;
    float weight_sum = 1.0;
    for (int dy = -2; dy <= 2; ++dy) {
        for (int dx = -2; dx <= 2; ++dx) {
            if (dx == 0 && dy == 0) {
                continue;
            }
            ivec2 q = pixel + ivec2(dx, dy) * params.step;
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) {
                continue;
            }
            float zq = imageLoad(u_depth, q).x;
            if (zq <= 0.0) {
                continue;
            }
            vec4 tap = imageLoad(u_in, q);
            float w = kernel[abs(dx)] * kernel[abs(dy)] / (kernel[0] * kernel[0])
                * svgf_edge_weight(z, zq, slope, float(params.step) * length(vec2(dx, dy)), n,
                                   imageLoad(u_normal_roughness, q).xyz, l, luminance(tap.rgb),
                                   sigma_l_std, params.sigma_z, params.sigma_n);
            color_sum += w * tap.rgb;
            variance_sum += w * w * svgf_filtered_variance(tap);
            weight_sum += w;
        }
    }
    return svgf_pack_filtered(color_sum / weight_sum, variance_sum / (weight_sum * weight_sum));
}

#endif
