// Long paths parked (bench/README.md, "Long paths"): with PARK_DEPTH set (one sample a pixel), a
// light transport kernel stores each path still alive after PARK_DEPTH segments in its pixel's
// 64-byte record (its own layout, in its own b_parked) and sets the pixel's flag in b_parked_flags,
// rather than tracing it on; parking/list.comp lists the flagged pixels, and the algorithm's
// continuation kernel (with PARKING_CONTINUE defined) traces those paths on, one invocation each
// over that compacted list, and adds what they bring with add_parked_radiance. A subgroup of the
// first kernel then waits for its longest path up to PARK_DEPTH only, not for the few paths Russian
// roulette keeps to the maximum depth. 0: off. Each part's non-finite radiance is dropped and
// counted on its own: where the first part was dropped, the pixel keeps what the continuation adds
// (one kernel drops the whole path). Requires frame.glsl and transport_outputs.glsl.
#ifndef LUCID_PARKING_GLSL
#define LUCID_PARKING_GLSL

layout(constant_id = 122) const uint PARK_DEPTH = 0u;

#ifdef PARKING_CONTINUE
layout(set = 0, binding = 16, rgba32f) uniform image2D u_radiance;
layout(set = 0, binding = 17, rgba32f) uniform writeonly image2D u_demodulated;
layout(set = 0, binding = 18, rgba32f) uniform readonly image2D u_albedo;
layout(set = 0, binding = 19, rgba32f) uniform readonly image2D u_emission;
layout(set = 0, binding = 20, std430) buffer Stats { uint non_finite; uint rays; uint cut_short; uint pad1; } b_stats;
layout(set = 0, binding = 29, std430) readonly buffer ParkedList { uint q[]; } b_parked_list;
layout(set = 0, binding = 30, std430) readonly buffer ParkedCount { uint n; } b_parked_count;

// Adds `rest`, the radiance a parked path brought after PARK_DEPTH segments, to the radiance of
// the pixel at `pixel_index` (row-major), and with SURFACE_OUTPUTS computes its demodulated
// radiance again from the first hit's albedo and emission the first kernel wrote; a non-finite
// `rest` is dropped and counted.
void add_parked_radiance(uint pixel_index, vec3 rest) {
    if (any(isnan(rest)) || any(isinf(rest))) {
        atomicAdd(b_stats.non_finite, 1u);
        return;
    }
    uint width = b_frame.f.width;
    ivec2 pixel = ivec2(pixel_index % width, pixel_index / width);
    vec3 radiance = imageLoad(u_radiance, pixel).rgb + rest;
    imageStore(u_radiance, pixel, vec4(radiance, 1.0));
    if (SURFACE_OUTPUTS) {
        vec3 demodulated = demodulate(radiance, imageLoad(u_emission, pixel).rgb, imageLoad(u_albedo, pixel).rgb);
        imageStore(u_demodulated, pixel, vec4(demodulated, 1.0));
    }
}
#else
layout(set = 0, binding = 31, std430) writeonly buffer ParkedFlags { uint f[]; } b_parked_flags;

// The record and flag index of this invocation's pixel (row-major).
uint parking_pixel() {
    return gl_GlobalInvocationID.y * b_frame.f.width + gl_GlobalInvocationID.x;
}
#endif

#endif
