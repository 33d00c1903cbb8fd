#version 460
// Wavefront path tracing, kernel 1 of 5 (passes/src/light_transport/wavefront/): the camera ray of
// sample `push.sample_index` of every pixel, exactly as the megakernel draws it (shaders/path_trace/
// path_trace.glsl: the first sample's generator from rng_init, later samples' from where the
// pixel's last path left it; on a replay pick, last frame's pixel, camera and random numbers,
// common/replay.glsl), into the path state; the first ray queue holds every path. The first
// invocation resets the queue lengths and the indirect arguments: the first ray queue's to every
// path, the others' to none.
#include "wavefront/common.glsl"
#include "wavefront/path_state.glsl"
#include "common/replay.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 24, std430) writeonly buffer RayQueue { uint q[]; } b_ray_queue;
layout(set = 0, binding = 25, std430) writeonly buffer Counts { uint c[]; } b_counts;
layout(set = 0, binding = 26, std430) writeonly buffer ArgsEven { uint a[]; } b_args_even;
layout(set = 0, binding = 27, std430) writeonly buffer ArgsOdd { uint a[]; } b_args_odd;
layout(set = 0, binding = 33, rgba16f) uniform readonly image2D u_motion;

// slots: the queue slots (lengths and indirect arguments); counters: the lengths to reset, the
// material bins' too (queues.glsl).
layout(push_constant) uniform Push { ReplayParams replay; uint sample_index; uint slots; uint counters; } push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = uvec2(b_frame.f.width, b_frame.f.height);
    uint paths = size.x * size.y;
    if (gl_GlobalInvocationID.xy == uvec2(0u)) {
        // No ray is traced when paths have no segment (max_depth 0, as trace_path).
        uint first = b_frame.f.max_depth > 0u ? paths : 0u;
        for (uint slot = 0u; slot < push.counters; ++slot) {
            b_counts.c[slot] = slot == 0u ? first : 0u;
        }
        for (uint slot = 0u; slot < push.slots; ++slot) {
            uint groups = slot == 0u ? (first + QUEUE_GROUP - 1u) / QUEUE_GROUP : 0u;
            b_args_even.a[4u * slot] = groups;
            b_args_odd.a[4u * slot] = 0u;
            for (uint i = 1u; i < 3u; ++i) {
                b_args_even.a[4u * slot + i] = 1u;
                b_args_odd.a[4u * slot + i] = 1u;
            }
        }
    }
    if (any(greaterThanEqual(uvec2(pixel), size))) {
        return;
    }
    uint path = uint(pixel.y) * size.x + uint(pixel.x);
    // The pixel whose random numbers and camera this path uses: its own, or on a replay pick,
    // last frame's pixel it came from.
    uint frame = b_frame.f.frame_index;
    ivec2 source = pixel;
    Camera camera = b_frame.f.camera;
    if (replay_picked(pixel, push.replay, frame, ivec2(size))) {
        ivec2 q = replay_source(pixel, imageLoad(u_motion, pixel).xy, push.replay, frame, ivec2(size));
        if (q != NO_REPLAY) {
            source = q;
            frame -= 1u;
            camera = b_frame.f.prev_camera;
        }
    }
    uint rng = push.sample_index == 0u
        ? rng_init(uvec2(source), frame, b_frame.f.seed)
        : b_path_rng.s[path];
    vec2 ndc = film_ndc(vec2(source), rng_next2(rng), vec2(size));
    vec3 origin;
    vec3 dir;
    camera_ray(camera, ndc, float(size.x) / float(size.y), rng_next2(rng), origin, dir);
    store_path_state(path, path_start(origin), origin, dir, pixel_spread(camera, float(size.y)));
    b_path_rng.s[path] = rng;
    b_path_radiance.v[path] = vec4(0.0);
    if (SURFACE_OUTPUTS) {
        b_first_hit.v[2u * path] = vec4(1.0);
        b_first_hit.v[2u * path + 1u] = vec4(0.0);
    }
    b_ray_queue.q[path] = path;
}
