#version 460
// Wavefront path tracing, kernel 1 of 5 (passes/src/light_transport/wavefront/): the camera ray of
// sample `push.sample_index` of every pixel, exactly as the megakernel draws it (shaders/path_trace/
// path_trace.comp: the first sample's generator from rng_init, later samples' from where the
// pixel's last path left it), into the path state; the first ray queue holds every path. The
// first invocation resets the queue lengths and the indirect arguments: the first ray queue's
// to every path, the others' to none.
#include "wavefront/common.glsl"
#include "wavefront/path_state.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 24, std430) writeonly buffer RayQueue { uint q[]; } b_ray_queue;
layout(set = 0, binding = 25, std430) writeonly buffer Counts { uint c[]; } b_counts;
layout(set = 0, binding = 26, std430) writeonly buffer ArgsEven { uint a[]; } b_args_even;
layout(set = 0, binding = 27, std430) writeonly buffer ArgsOdd { uint a[]; } b_args_odd;

// slots: the queue slots (lengths and indirect arguments); counters: the lengths to reset, the
// material bins' too (queues.glsl).
layout(push_constant) uniform Push { uint sample_index; uint slots; uint counters; } push;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = uvec2(b_frame.f.width, b_frame.f.height);
    uint paths = size.x * size.y;
    if (gl_GlobalInvocationID.xy == uvec2(0u)) {
        for (uint slot = 0u; slot < push.counters; ++slot) {
            b_counts.c[slot] = slot == 0u ? paths : 0u;
        }
        for (uint slot = 0u; slot < push.slots; ++slot) {
            uint groups = slot == 0u ? (paths + QUEUE_GROUP - 1u) / QUEUE_GROUP : 0u;
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
    Camera camera = b_frame.f.camera;
    uint rng = push.sample_index == 0u
        ? rng_init(uvec2(pixel), b_frame.f.frame_index, b_frame.f.seed)
        : b_path_rng.s[path];
    vec2 ndc = film_ndc(vec2(pixel), rng_next2(rng), vec2(size));
    vec3 origin;
    vec3 dir;
    camera_ray(camera, ndc, float(size.x) / float(size.y), rng_next2(rng), origin, dir);
    store_path_state(path, path_start(origin), origin, dir);
    b_path_rng.s[path] = rng;
    b_path_radiance.v[path] = vec4(0.0);
    if (SURFACE_OUTPUTS) {
        b_first_hit.v[2u * path] = vec4(1.0);
        b_first_hit.v[2u * path + 1u] = vec4(0.0);
    }
    b_ray_queue.q[path] = path;
}
