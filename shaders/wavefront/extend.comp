#version 460
// Wavefront path tracing, kernel 2 of 5: the closest hit of each ray in bounce `push.depth`'s ray
// queue (dispatched indirectly, as many workgroups as the queue needs), into the path's hit
// record (instance MISS when it hit nothing).
#include "wavefront/common.glsl"

layout(local_size_x = 128) in;

layout(set = 0, binding = 16, std430) readonly buffer RayOrigin { vec4 v[]; } b_ray_origin;
layout(set = 0, binding = 17, std430) readonly buffer RayDirection { vec4 v[]; } b_ray_direction;
layout(set = 0, binding = 24, std430) readonly buffer RayQueue { uint q[]; } b_ray_queue;
layout(set = 0, binding = 25, std430) readonly buffer Counts { uint c[]; } b_counts;
layout(set = 0, binding = 28, std430) writeonly buffer Hits { Hit h[]; } b_hits;

layout(push_constant) uniform Push { uint depth; } push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= b_counts.c[ray_slot(push.depth)]) {
        return;
    }
    uint path = b_ray_queue.q[i];
    Hit hit;
    if (!trace_closest(b_ray_origin.v[path].xyz, b_ray_direction.v[path].xyz, T_INFINITY, hit)) {
        hit.instance = MISS;
    }
    b_hits.h[path] = hit;
}
