// Wavefront path tracing, kernel 3 of 5: one vertex of each path in bounce `push.depth`'s ray queue
// (dispatched indirectly), the loop body of trace_path through the path's step functions
// (common/path.glsl) and with its random numbers: what a miss brings or the hit emits (MIS), and
// unless the path is at its longest, the light sample (its shadow ray appended to the bounce's
// shadow queue for the shadow kernel), the next direction and Russian roulette (a surviving path
// appended to the next bounce's ray queue). Appends are compacted per workgroup (append.glsl): one
// atomic per workgroup and queue reserves the places, and the queue's indirect arguments grow by
// the workgroups the new places begin, so they always hold ceil(length / QUEUE_GROUP) without a
// kernel of their own. With BIN_BY_MATERIAL (shade_binned.comp) it takes the bounce's paths from
// extend's material bins, one bin after the other, instead of the ray queue.
#include "wavefront/common.glsl"
#include "wavefront/path_state.glsl"

layout(local_size_x = 128) in;

#ifdef BIN_BY_MATERIAL
layout(set = 0, binding = 32, std430) readonly buffer BinnedQueue { uint q[]; } b_binned_queue;
#else
layout(set = 0, binding = 24, std430) readonly buffer RayQueue { uint q[]; } b_ray_queue;
#endif
layout(set = 0, binding = 25, std430) buffer Counts { uint c[]; } b_counts;
layout(set = 0, binding = 26, std430) buffer ArgsOut { uint a[]; } b_args_out;
layout(set = 0, binding = 28, std430) readonly buffer Hits { Hit h[]; } b_hits;
layout(set = 0, binding = 29, std430) writeonly buffer ShadowQueue { uint q[]; } b_shadow_queue;
layout(set = 0, binding = 30, std430) writeonly buffer ShadowRays { ShadowRecord r[]; } b_shadow_rays;
layout(set = 0, binding = 31, std430) writeonly buffer NextRayQueue { uint q[]; } b_next_ray_queue;

layout(push_constant) uniform Push { uint depth; } push;

// Appends to the bounce's shadow queue (0) and the next bounce's ray queue (1), growing their
// indirect arguments.
const uint APPEND_QUEUES = 2u;
#define APPEND_ARGS
#include "wavefront/append.glsl"

// The path at place `i` of the bounce's queue (i below its length).
uint queued_path(uint i) {
#ifdef BIN_BY_MATERIAL
    uint paths = b_frame.f.width * b_frame.f.height;
    uint first = 0u;
    for (uint bin = 0u; bin < MATERIAL_BINS; ++bin) {
        uint n = b_counts.c[material_bin_slot(push.depth, bin, b_frame.f.max_depth)];
        if (i < first + n) {
            return b_binned_queue.q[bin * paths + (i - first)];
        }
        first += n;
    }
    return 0u; // not reached: the bins hold every path of the ray queue
#else
    return b_ray_queue.q[i];
#endif
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    uint depth = push.depth;
    bool queued = i < b_counts.c[ray_slot(depth)];
    uint path = queued ? queued_path(i) : 0u;
    bool shadow_wanted = false;
    bool next_wanted = false;
    if (queued) {
        PathState st = load_path_state(path);
        vec3 o = b_ray_origin.v[path].xyz;
        vec3 d = b_ray_direction.v[path].xyz;
        uint rng = b_path_rng.s[path];
        vec3 radiance = b_path_radiance.v[path].xyz;
        Hit hit = b_hits.h[path];
        Surface s;
        if (hit.instance == MISS) {
            radiance += path_miss(st, d);
        } else {
            s = surface_at(hit, o, d);
            radiance += path_emission(st, s, d);
        }
        // What the first hit (or the sky) emits towards the camera.
        if (SURFACE_OUTPUTS && depth == 0u) {
            b_first_hit.v[2u * path + 1u] = vec4(radiance, 0.0);
        }
        // The light sample and the next direction, unless the path ends here.
        if (hit.instance != MISS && depth + 1u < b_frame.f.max_depth) {
            float spread = b_prev_vertex.v[path].w;
            float footprint = depth == 0u ? cone_lod(s, d, hit.t * spread) : NO_FOOTPRINT;
            Shading sh = path_shading(s, d, footprint);
            if (SURFACE_OUTPUTS && depth == 0u) {
                b_first_hit.v[2u * path] = vec4(demodulation_albedo(sh.m), 0.0);
            }
            vec4 u_light;
            vec3 u_bsdf;
            path_vertex_numbers(rng, u_light, u_bsdf);
            ShadowRay shadow;
            shadow_wanted = path_light_sample(st, s, sh, u_light, shadow);
            if (shadow_wanted) {
                b_shadow_rays.r[path] = ShadowRecord(vec4(shadow.origin, shadow.t_max), vec4(shadow.dir, 0.0), vec4(shadow.radiance, 0.0));
            }
            next_wanted = path_continue(st, s, sh, u_bsdf, depth, b_frame.f.rr_depth, rng, o, d);
            if (next_wanted) {
                store_path_state(path, st, o, d, 0.0);
            }
        }
        b_path_rng.s[path] = rng;
        b_path_radiance.v[path] = vec4(radiance, 0.0);
    }
    append_begin();
    uint shadow_rank = append_rank(shadow_wanted, 0u);
    uint next_rank = append_rank(next_wanted, 1u);
    append_reserve(uint[APPEND_QUEUES](shadow_slot(depth), ray_slot(depth + 1u)));
    if (shadow_wanted) {
        b_shadow_queue.q[append_place(0u, shadow_rank)] = path;
    }
    if (next_wanted) {
        b_next_ray_queue.q[append_place(1u, next_rank)] = path;
    }
}
