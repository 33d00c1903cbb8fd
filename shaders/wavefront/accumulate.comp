#version 460
// Wavefront path tracing, kernel 5 of 5: adds sample `push.sample_index`'s paths to the pixels'
// sums in the output images as the megakernel adds a sample (shaders/path_trace/path_trace.glsl:
// a non-finite path is dropped and counted, its first hit's albedo kept), the frame's last sample
// writing the averages; the first invocation adds the rays the sample's queues held (every queued
// ray was traced) to the counters.
#include "wavefront/common.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 21, std430) readonly buffer PathRadiance { vec4 v[]; } b_path_radiance;
layout(set = 0, binding = 22, std430) readonly buffer FirstHit { vec4 v[]; } b_first_hit; // albedo, emission
layout(set = 0, binding = 25, std430) readonly buffer Counts { uint c[]; } b_counts;
layout(set = 0, binding = 34, rgba32f) uniform image2D u_radiance;
layout(set = 0, binding = 35, rgba32f) uniform image2D u_demodulated;
layout(set = 0, binding = 36, rgba32f) uniform image2D u_albedo;
layout(set = 0, binding = 37, rgba32f) uniform image2D u_emission;
layout(set = 0, binding = 38, std430) buffer Stats { uint non_finite; uint rays; uint cut_short; uint pad1; } b_stats;

// slots: the queue slots, whose lengths add up to the rays traced.
layout(push_constant) uniform Push { uint sample_index; uint slots; } push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = uvec2(b_frame.f.width, b_frame.f.height);
    if (gl_GlobalInvocationID.xy == uvec2(0u)) {
        uint rays = 0u;
        for (uint slot = 0u; slot < push.slots; ++slot) {
            rays += b_counts.c[slot];
        }
        atomicAdd(b_stats.rays, rays);
    }
    if (any(greaterThanEqual(uvec2(pixel), size))) {
        return;
    }
    uint path = uint(pixel.y) * size.x + uint(pixel.x);
    bool first = push.sample_index == 0u;
    uint spp = b_frame.f.samples_per_pixel;
    vec3 sum = first ? vec3(0.0) : imageLoad(u_radiance, pixel).rgb;
    vec3 demodulated_sum = vec3(0.0);
    vec3 albedo_sum = vec3(0.0);
    vec3 emission_sum = vec3(0.0);
    if (SURFACE_OUTPUTS && !first) {
        demodulated_sum = imageLoad(u_demodulated, pixel).rgb;
        albedo_sum = imageLoad(u_albedo, pixel).rgb;
        emission_sum = imageLoad(u_emission, pixel).rgb;
    }
    vec3 radiance = b_path_radiance.v[path].xyz;
    bool finite = !(any(isnan(radiance)) || any(isinf(radiance)));
    if (SURFACE_OUTPUTS) {
        vec3 albedo = b_first_hit.v[2u * path].xyz;
        albedo_sum += albedo;
        if (finite) {
            vec3 emission = b_first_hit.v[2u * path + 1u].xyz;
            demodulated_sum += demodulate(radiance, emission, albedo);
            emission_sum += emission;
        }
    }
    if (finite) {
        sum += radiance;
    } else {
        atomicAdd(b_stats.non_finite, 1u);
    }
    bool last = push.sample_index + 1u >= spp;
    float scale = last ? 1.0 / float(spp) : 1.0;
    imageStore(u_radiance, pixel, vec4(sum * scale, 1.0));
    if (SURFACE_OUTPUTS) {
        imageStore(u_demodulated, pixel, vec4(demodulated_sum * scale, 1.0));
        imageStore(u_albedo, pixel, vec4(albedo_sum * scale, 1.0));
        imageStore(u_emission, pixel, vec4(emission_sum * scale, 1.0));
    }
}
