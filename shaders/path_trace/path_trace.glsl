// Unidirectional path tracing (common/path.glsl), `spp` samples per pixel, one thread per pixel,
// in batches of samples (common/sample_batch.glsl): the images hold the running sums (each sample
// adds to them, so that no sum is held in registers while a path is traced, bench/README.md) until
// the frame's last sample writes the averages, and b_rng_state each pixel's generator between
// batches; on frames with replay on, a pixel per stratum replays last frame's paths instead
// (common/replay.glsl) so that the denoiser gets noise-free temporal gradients at no extra paths.
// Writes the noisy radiance and, with SURFACE_OUTPUTS, the radiance demodulated by the first hit
// (emission removed, divided by albedo) and that hit's albedo and emission. Non-finite samples are
// dropped and counted in b_stats, as are the rays traced (for rays/s figures) and the pixels whose
// loops the device cut short.
// The body of path_trace.comp (without the denoiser's images, or with them and one sample a pixel;
// path_trace_in_workgroup.comp is the same for a scene walked in workgroup memory) and
// path_trace_surfaces.comp (with them and more samples), which define how trace_path hands over
// the first hit's albedo and emission:
// PATH_KEEP_FIRST_ALBEDO(v) and PATH_KEEP_FIRST_EMISSION(v) keep them, PATH_FIRST_ALBEDO and
// PATH_FIRST_EMISSION read them back after the path.
#include "common/math.glsl"
#include "common/rng.glsl"
#include "common/scene.glsl"
#include "common/frame.glsl"
#include "common/traverse.glsl"
#include "common/bsdf.glsl"
#include "common/lights.glsl"
#include "common/surface.glsl"
#include "common/camera.glsl"
#include "common/transport_outputs.glsl"

// Workgroups of 8x8 pixels; PATH_TRACE_WORKGROUP_WIDTH 16 makes them 16x8.
#ifndef PATH_TRACE_WORKGROUP_WIDTH
#define PATH_TRACE_WORKGROUP_WIDTH 8
#endif
layout(local_size_x = PATH_TRACE_WORKGROUP_WIDTH, local_size_y = 8) in;

layout(set = 0, binding = 16, rgba32f) uniform image2D u_radiance;
layout(set = 0, binding = 17, rgba32f) uniform image2D u_demodulated;
layout(set = 0, binding = 18, rgba32f) uniform image2D u_albedo;
layout(set = 0, binding = 19, rgba32f) uniform image2D u_emission;
layout(set = 0, binding = 20, std430) buffer Stats { uint non_finite; uint rays; uint cut_short; uint pad1; } b_stats;
layout(set = 0, binding = 21, rgba16f) uniform readonly image2D u_motion;
layout(set = 0, binding = 22, std430) buffer RngState { uint s[]; } b_rng_state;

#include "common/sample_batch.glsl"
#include "parking/parking.glsl"
#include "path_trace/long_paths.glsl"
#include "common/path.glsl"
#include "common/replay.glsl"

layout(push_constant) uniform Push { ReplayParams replay; SampleBatch batch; } push;

// One path of pixel `source` from a camera ray jittered over it (last frame's camera where
// `replayed`); adds the rays it traces to `rays`.
vec3 trace_pixel_path(ivec2 source, bool replayed, inout uint rng, inout uint rays) {
    uvec2 size = uvec2(b_frame.f.width, b_frame.f.height);
    // Read afresh for every path, so that the camera is not held in registers while one is traced
    // (a select, as an `if` here costs 96 registers instead of 72 on an H100).
    Camera camera = camera_select(replayed, b_frame.f.camera, b_frame.f.prev_camera);
    vec2 ndc = film_ndc(vec2(source), rng_next2(rng), vec2(size));
    vec3 origin;
    vec3 dir;
    camera_ray(camera, ndc, float(size.x) / float(size.y), rng_next2(rng), origin, dir);
    return trace_path(origin, dir, rng, b_frame.f.max_depth, b_frame.f.rr_depth, pixel_spread(camera, float(size.y)),
                      rays);
}

void main() {
    scene_to_workgroup(gl_WorkGroupSize.x * gl_WorkGroupSize.y);
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = uvec2(b_frame.f.width, b_frame.f.height);
    if (any(greaterThanEqual(uvec2(pixel), size))) {
        return;
    }
    uint frame = b_frame.f.frame_index;
    // The pixel whose random numbers and camera this thread's paths use: its own, or on a replay
    // pick, last frame's pixel it came from.
    ivec2 source = pixel;
    bool replayed = false;
    if (replay_picked(pixel, push.replay, frame, ivec2(size))) {
        ivec2 q = replay_source(pixel, imageLoad(u_motion, pixel).xy, push.replay, frame, ivec2(size));
        if (q != NO_REPLAY) {
            source = q;
            frame -= 1u;
            replayed = true;
        }
    }
    SampleBatch batch = push.batch;
    uint state_index = uint(pixel.y) * size.x + uint(pixel.x);
    bool first = batch_is_first(batch);
    uint rng = first ? rng_init(uvec2(source), frame, b_frame.f.seed) : b_rng_state.s[state_index];
    uint spp = b_frame.f.samples_per_pixel;
    uint rays = 0u;
    uint dropped = 0u;
    // Each sample adds to what the images hold (zero before the frame's first sample); the
    // frame's last also averages.
    bool last = batch_is_last(batch, spp);
    float last_scale = last ? 1.0 / float(spp) : 1.0;
    if (ONE_SAMPLE) {
        // The frame's only sample, written as it is (no running sums are read: 1% off `classroom`
        // on an H200, bench/README.md); the first hit's albedo and emission are in their images
        // already (PATH_KEEP_FIRST_ALBEDO and PATH_KEEP_FIRST_EMISSION), read back to demodulate.
        vec3 path = trace_pixel_path(source, replayed, rng, rays);
        bool finite = !(any(isnan(path)) || any(isinf(path)));
        dropped += finite ? 0u : 1u;
        imageStore(u_radiance, pixel, vec4(finite ? path : vec3(0.0), 1.0));
        if (SURFACE_OUTPUTS) {
            vec3 demodulated = vec3(0.0);
            if (finite) {
                demodulated = demodulate(path, imageLoad(u_emission, pixel).rgb, imageLoad(u_albedo, pixel).rgb);
            } else {
                imageStore(u_emission, pixel, vec4(0.0, 0.0, 0.0, 1.0));
            }
            imageStore(u_demodulated, pixel, vec4(demodulated, 1.0));
        }
    }
    // The batch's samples, added to the running sums (none with ONE_SAMPLE, traced above).
    for (uint i = 0u; i < (ONE_SAMPLE ? 0u : batch.count); ++i) {
        vec3 path = trace_pixel_path(source, replayed, rng, rays);
        bool finite = !(any(isnan(path)) || any(isinf(path)));
        dropped += finite ? 0u : 1u;
        bool fresh = first && i == 0u;
        float scale = i + 1u == batch.count ? last_scale : 1.0;
        vec3 radiance = finite ? path : vec3(0.0);
        vec3 sum = (fresh ? vec3(0.0) : imageLoad(u_radiance, pixel).rgb) + radiance;
        imageStore(u_radiance, pixel, vec4(sum * scale, 1.0));
        if (SURFACE_OUTPUTS) {
            vec3 first_albedo = PATH_FIRST_ALBEDO;
            vec3 first_emission = PATH_FIRST_EMISSION;
            vec3 demodulated = finite ? demodulate(path, first_emission, first_albedo) : vec3(0.0);
            vec3 emission = finite ? first_emission : vec3(0.0);
            vec3 demodulated_sum = (fresh ? vec3(0.0) : imageLoad(u_demodulated, pixel).rgb) + demodulated;
            vec3 albedo_sum = (fresh ? vec3(0.0) : imageLoad(u_albedo, pixel).rgb) + first_albedo;
            vec3 emission_sum = (fresh ? vec3(0.0) : imageLoad(u_emission, pixel).rgb) + emission;
            imageStore(u_demodulated, pixel, vec4(demodulated_sum * scale, 1.0));
            imageStore(u_albedo, pixel, vec4(albedo_sum * scale, 1.0));
            imageStore(u_emission, pixel, vec4(emission_sum * scale, 1.0));
        }
    }
    if (dropped > 0u) {
        atomicAdd(b_stats.non_finite, dropped);
    }
    uint total_rays = subgroupAdd(rays);
    if (subgroupElect()) {
        atomicAdd(b_stats.rays, total_rays);
    }
    if (loop_limit_reached(batch.count + 1u)) {
        atomicAdd(b_stats.cut_short, 1u);
    }
    if (!last) {
        b_rng_state.s[state_index] = rng;
    }
}
