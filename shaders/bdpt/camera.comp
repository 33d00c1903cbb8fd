#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// BDPT camera pass: `spp` camera subpaths per pixel (camera_path.glsl). At each vertex: emission
// hit (s = 0), NEE (s = 1) and connections to CONNECTIONS light vertices drawn from the light
// vertex cache (a light subpath uniformly, then one of its vertices uniformly; s > 1), each with
// its recursive MIS weight (see bdpt.glsl). With PARK_DEPTH set, subpaths alive after PARK_DEPTH
// segments are parked for camera_long.comp (bdpt/long_paths.glsl). Paths lit by the sun or the
// environment are found by this pass alone and weighted between BSDF sampling and NEE as the path
// tracer does. Adds the light pass's splats and writes radiance, radiance demodulated by the
// first hit (its emission removed, divided by its albedo) and that hit's albedo and emission.
// Non-finite samples are dropped and counted in b_stats, as are the pixels whose loops the device
// cut short. The samples come in batches (common/sample_batch.glsl): the images hold the running
// sums (each sample adds to them) until the frame's last sample writes the averages, and
// b_rng_state each pixel's generator between batches.
#define SCENE_IN_WORKGROUP
#include "common/math.glsl"
#include "common/rng.glsl"
#include "common/scene.glsl"
#include "common/frame.glsl"
#include "common/traverse.glsl"
#include "common/bsdf.glsl"
#include "common/lights.glsl"
#include "common/surface.glsl"
#include "common/camera.glsl"
#include "common/light_emit.glsl"
#include "bdpt/bdpt.glsl"
#include "common/transport_outputs.glsl"
#include "parking/parking.glsl"
#include "bdpt/long_paths.glsl"
#include "bdpt/camera_path.glsl"

layout(local_size_x = 16, local_size_y = 8) in;

layout(set = 0, binding = 16, rgba32f) uniform image2D u_radiance;
layout(set = 0, binding = 17, rgba32f) uniform writeonly image2D u_demodulated;
layout(set = 0, binding = 18, rgba32f) uniform image2D u_albedo;
layout(set = 0, binding = 19, rgba32f) uniform image2D u_emission;
layout(set = 0, binding = 20, std430) buffer Stats { uint non_finite; uint rays; uint cut_short; uint pad1; } b_stats;
layout(set = 0, binding = 24, std430) readonly buffer Splat { uint64_t v[]; } b_splat;
layout(set = 0, binding = 25, std430) buffer RngState { uint s[]; } b_rng_state;

// Writes pixel's averages over the frame's `spp` samples from their sums, the light tracer's splat
// added to the radiance.
void store_averages(ivec2 pixel, uvec2 size, uint spp, vec3 sum, vec3 albedo_sum, vec3 emission_sum) {
    uint i = 3u * (uint(pixel.y) * size.x + uint(pixel.x));
    vec3 splat = vec3(float(b_splat.v[i]), float(b_splat.v[i + 1u]), float(b_splat.v[i + 2u]))
        * (pc.splat_scale / SPLAT_ONE);
    vec3 radiance = sum / float(spp) + splat;
    vec3 albedo = albedo_sum / float(spp);
    vec3 emission = emission_sum / float(spp);
    imageStore(u_radiance, pixel, vec4(radiance, 1.0));
    if (SURFACE_OUTPUTS) {
        imageStore(u_demodulated, pixel, vec4(demodulate(radiance, emission, albedo), 1.0));
        imageStore(u_albedo, pixel, vec4(albedo, 1.0));
        imageStore(u_emission, pixel, vec4(emission, 1.0));
    }
}

// One camera sample of `pixel` from a ray jittered over it, with its first hit's albedo and
// emission; a non-finite one is counted in `dropped` and comes back as zero radiance and emission.
vec3 trace_pixel_sample(ivec2 pixel, inout uint rng, out vec3 albedo, out vec3 emission, inout uint dropped) {
    uvec2 size = uvec2(b_frame.f.width, b_frame.f.height);
    vec2 ndc = film_ndc(vec2(pixel), rng_next2(rng), vec2(size));
    vec3 origin;
    vec3 dir;
    camera_ray(b_frame.f.camera, ndc, float(size.x) / float(size.y), rng_next2(rng), origin, dir);
    vec3 l = trace_camera(origin, dir, rng, b_frame.f.max_depth, b_frame.f.rr_depth, albedo, emission);
    if (any(isnan(l)) || any(isinf(l))) {
        dropped += 1u;
        l = vec3(0.0);
        emission = vec3(0.0);
    }
    return l;
}

void main() {
    scene_to_workgroup(gl_WorkGroupSize.x * gl_WorkGroupSize.y);
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = uvec2(b_frame.f.width, b_frame.f.height);
    if (any(greaterThanEqual(uvec2(pixel), size))) {
        return;
    }
    SampleBatch batch = pc.batch;
    uint state_index = uint(pixel.y) * size.x + uint(pixel.x);
    bool first = batch_is_first(batch);
    uint rng = first ? rng_init(uvec2(pixel), b_frame.f.frame_index, b_frame.f.seed)
                     : b_rng_state.s[state_index];
    uint spp = b_frame.f.samples_per_pixel;
    bool last = batch_is_last(batch, spp);
    uint dropped = 0u;
    if (ONE_SAMPLE) {
        // The frame's only sample, written as its average at once (no running sums are read).
        vec3 albedo;
        vec3 emission;
        vec3 l = trace_pixel_sample(pixel, rng, albedo, emission, dropped);
        store_averages(pixel, size, 1u, l, albedo, emission);
    }
    // Otherwise each sample adds to what the images hold (zero before the frame's first sample),
    // so that no sum is held in registers while a path is traced; the frame's last sample writes
    // the averages.
    for (uint i = 0u; i < (ONE_SAMPLE ? 0u : batch.count); ++i) {
        vec3 albedo;
        vec3 emission;
        vec3 l = trace_pixel_sample(pixel, rng, albedo, emission, dropped);
        bool fresh = first && i == 0u;
        vec3 sum = (fresh ? vec3(0.0) : imageLoad(u_radiance, pixel).rgb) + l;
        vec3 albedo_sum = vec3(0.0);
        vec3 emission_sum = vec3(0.0);
        if (SURFACE_OUTPUTS) {
            albedo_sum = (fresh ? vec3(0.0) : imageLoad(u_albedo, pixel).rgb) + albedo;
            emission_sum = (fresh ? vec3(0.0) : imageLoad(u_emission, pixel).rgb) + emission;
        }
        if (last && i + 1u == batch.count) {
            store_averages(pixel, size, spp, sum, albedo_sum, emission_sum);
        } else {
            imageStore(u_radiance, pixel, vec4(sum, 1.0));
            if (SURFACE_OUTPUTS) {
                imageStore(u_albedo, pixel, vec4(albedo_sum, 1.0));
                imageStore(u_emission, pixel, vec4(emission_sum, 1.0));
            }
        }
    }
    if (dropped > 0u) {
        atomicAdd(b_stats.non_finite, dropped);
    }
    uint rays = subgroupAdd(rays_traced);
    if (subgroupElect()) {
        atomicAdd(b_stats.rays, rays);
    }
    if (loop_limit_reached(batch.count + 1u)) {
        atomicAdd(b_stats.cut_short, 1u);
    }
    if (!last) {
        b_rng_state.s[state_index] = rng;
    }
}
