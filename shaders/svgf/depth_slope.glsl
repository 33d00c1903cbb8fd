// Screen-space slope of the G-buffer's view depth. Requires `u_depth` (r32f, readonly) declared.
#ifndef LUCID_SVGF_DEPTH_SLOPE_GLSL
#define LUCID_SVGF_DEPTH_SLOPE_GLSL

// The smaller one-sided difference on each axis (a depth edge beside the pixel does not count),
// the larger of the two axes.
float svgf_depth_slope(ivec2 pixel, ivec2 size) {
    float z = imageLoad(u_depth, pixel).x;
    float zl = imageLoad(u_depth, clamp(pixel - ivec2(1, 0), ivec2(0), size - 1)).x;
    float zr = imageLoad(u_depth, clamp(pixel + ivec2(1, 0), ivec2(0), size - 1)).x;
    float zu = imageLoad(u_depth, clamp(pixel - ivec2(0, 1), ivec2(0), size - 1)).x;
    float zd = imageLoad(u_depth, clamp(pixel + ivec2(0, 1), ivec2(0), size - 1)).x;
    float gx = min(abs(zr - z), abs(z - zl));
    float gy = min(abs(zd - z), abs(z - zu));
    return max(gx, gy);
}

#endif
