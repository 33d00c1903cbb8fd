// Wavefront path tracing, kernel 2 of 5: the closest hit of each ray in bounce `push.depth`'s ray
// queue (dispatched indirectly, as many workgroups as the queue needs), into the path's hit
// record (instance MISS when it hit nothing). With BIN_BY_MATERIAL (extend_binned.comp) it also
// appends the path to its hit's material bin (queues.glsl) for shade_binned.
#include "wavefront/common.glsl"

layout(local_size_x = 128) in;

layout(set = 0, binding = 16, std430) readonly buffer RayOrigin { vec4 v[]; } b_ray_origin;
layout(set = 0, binding = 17, std430) readonly buffer RayDirection { vec4 v[]; } b_ray_direction;
layout(set = 0, binding = 24, std430) readonly buffer RayQueue { uint q[]; } b_ray_queue;
layout(set = 0, binding = 28, std430) writeonly buffer Hits { Hit h[]; } b_hits;
#ifdef BIN_BY_MATERIAL
layout(set = 0, binding = 25, std430) buffer Counts { uint c[]; } b_counts;
layout(set = 0, binding = 32, std430) writeonly buffer BinnedQueue { uint q[]; } b_binned_queue;
const uint APPEND_QUEUES = MATERIAL_BINS;
#include "wavefront/append.glsl"
#else
layout(set = 0, binding = 25, std430) readonly buffer Counts { uint c[]; } b_counts;
#endif

layout(push_constant) uniform Push { uint depth; } push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    bool queued = i < b_counts.c[ray_slot(push.depth)];
#ifndef BIN_BY_MATERIAL
    if (!queued) {
        return;
    }
#endif
    uint path = queued ? b_ray_queue.q[i] : 0u;
    Hit hit;
    hit.instance = MISS;
    if (queued) {
        if (!trace_closest(b_ray_origin.v[path].xyz, b_ray_direction.v[path].xyz, T_INFINITY, hit)) {
            hit.instance = MISS;
        }
        b_hits.h[path] = hit;
    }
#ifdef BIN_BY_MATERIAL
    // Every invocation takes part in the appends (they hold barriers); one past the queue in none.
    uint kind = !queued || hit.instance == MISS ? 0u : b_materials.m[hit_material(hit)].kind;
    uint bin = queued ? material_bin(hit.instance, kind) : MATERIAL_BINS;
    append_begin();
    uint rank = 0u;
    uint slots[MATERIAL_BINS];
    for (uint b = 0u; b < MATERIAL_BINS; ++b) {
        uint r = append_rank(bin == b, b);
        rank = bin == b ? r : rank;
        slots[b] = material_bin_slot(push.depth, b, b_frame.f.max_depth);
    }
    append_reserve(slots);
    if (queued) {
        b_binned_queue.q[bin * b_frame.f.width * b_frame.f.height + append_place(bin, rank)] = path;
    }
#endif
}
