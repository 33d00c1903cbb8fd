#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_basic : require
// Unidirectional path tracing (common/path.glsl), `spp` samples per pixel, with path
// regeneration: a fixed number of threads work through the image's pixels (in 8x8 tiles, one
// per workgroup-sized run of jobs), one bounce per loop iteration, and a thread whose path ended
// starts the next sample or takes the next pixel from a shared counter. Warps thus stay full
// while paths of different lengths end, instead of idling until their longest path is done.
// Each pixel's random numbers depend only on (pixel, frame, seed), so the image does not depend
// on the number of threads. Writes the noisy radiance, the radiance demodulated by the first hit
// (emission removed, divided by albedo) and that hit's albedo and emission. Non-finite samples
// are dropped and counted in b_stats, as are the rays traced (for rays/s figures).
#include "common/math.glsl"
#include "common/rng.glsl"
#include "common/scene.glsl"
#include "common/frame.glsl"
#include "common/traverse.glsl"
#include "common/bsdf.glsl"
#include "common/lights.glsl"
#include "common/surface.glsl"
#include "common/camera.glsl"
#include "common/path.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 16, rgba32f) uniform writeonly image2D u_radiance;
layout(set = 0, binding = 17, rgba32f) uniform writeonly image2D u_demodulated;
layout(set = 0, binding = 18, rgba32f) uniform writeonly image2D u_albedo;
layout(set = 0, binding = 19, rgba32f) uniform writeonly image2D u_emission;
layout(set = 0, binding = 20, std430) buffer Stats { uint non_finite; uint rays; uint pad0; uint pad1; } b_stats;
// The next job to hand out; starts at the number of threads (job i < threads goes to thread i).
layout(set = 0, binding = 21, std430) buffer Work { uint next_job; } b_work;

const uint TILE = 8u;

// The pixel of job `job`: jobs run through 8x8 tiles row by row, 64 jobs per tile.
uvec2 job_pixel(uint job, uint tiles_x) {
    uint tile = job / (TILE * TILE);
    uint within = job % (TILE * TILE);
    return uvec2(tile % tiles_x, tile / tiles_x) * TILE + uvec2(within % TILE, within / TILE);
}

// Hands the next job to each invocation that asks, with one atomic per subgroup.
uint fetch_job() {
    uvec4 asking = subgroupBallot(true);
    uint count = subgroupBallotBitCount(asking);
    uint base = 0u;
    if (subgroupElect()) {
        base = atomicAdd(b_work.next_job, count);
    }
    return subgroupBroadcastFirst(base) + subgroupBallotExclusiveBitCount(asking);
}

void main() {
    uvec2 size = b_frame.f.size.xy;
    uint tiles_x = (size.x + TILE - 1u) / TILE;
    uint jobs = tiles_x * ((size.y + TILE - 1u) / TILE) * TILE * TILE;
    uint spp = max(b_frame.f.frame.z, 1u);
    uint max_depth = b_frame.f.frame.w;
    uint rr_depth = uint(b_frame.f.params.x);
    float aspect = float(size.x) / float(size.y);

    uint rays = 0u;
    uint dropped = 0u;
    uint job = gl_GlobalInvocationID.x;
    bool fresh_job = true;
    uvec2 pixel = uvec2(0u);
    uint rng = 0u;
    uint sample_index = 0u;
    vec3 sum = vec3(0.0);
    vec3 demodulated_sum = vec3(0.0);
    vec3 albedo_sum = vec3(0.0);
    vec3 emission_sum = vec3(0.0);
    PathState path;
    bool tracing = false;
    while (true) {
        if (!tracing) {
            if (fresh_job) {
                fresh_job = false;
                if (job >= jobs) {
                    break;
                }
                pixel = job_pixel(job, tiles_x);
                if (any(greaterThanEqual(pixel, size))) {
                    job = fetch_job();
                    fresh_job = true;
                    continue;
                }
                rng = rng_init(pixel, b_frame.f.frame.x, b_frame.f.frame.y);
                sample_index = 0u;
                sum = vec3(0.0);
                demodulated_sum = vec3(0.0);
                albedo_sum = vec3(0.0);
                emission_sum = vec3(0.0);
            }
            vec2 ndc = film_ndc(vec2(pixel), rng_next2(rng), vec2(size));
            vec3 origin;
            vec3 dir;
            camera_ray(b_frame.f.camera, ndc, aspect, rng_next2(rng), origin, dir);
            path = path_begin(origin, dir);
            tracing = true;
        }
        tracing = path_bounce(path, rng, max_depth, rr_depth, rays);
        if (tracing) {
            continue;
        }
        vec3 l = path.radiance;
        vec3 demodulated = path_demodulated(path);
        if (any(isnan(l)) || any(isinf(l))) {
            dropped += 1u;
            l = vec3(0.0);
            demodulated = vec3(0.0);
        }
        sum += l;
        demodulated_sum += demodulated;
        albedo_sum += path.first_albedo;
        emission_sum += path.first_emission;
        sample_index += 1u;
        if (sample_index < spp) {
            continue;
        }
        float inv_spp = 1.0 / float(spp);
        ivec2 p = ivec2(pixel);
        imageStore(u_radiance, p, vec4(sum * inv_spp, 1.0));
        imageStore(u_demodulated, p, vec4(demodulated_sum * inv_spp, 1.0));
        imageStore(u_albedo, p, vec4(albedo_sum * inv_spp, 1.0));
        imageStore(u_emission, p, vec4(emission_sum * inv_spp, 1.0));
        job = fetch_job();
        fresh_job = true;
    }
    if (dropped > 0u) {
        atomicAdd(b_stats.non_finite, dropped);
    }
    uint total_rays = subgroupAdd(rays);
    if (subgroupElect()) {
        atomicAdd(b_stats.rays, total_rays);
    }
}
