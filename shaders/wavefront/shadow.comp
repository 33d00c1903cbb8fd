#version 460
// Wavefront path tracing, kernel 4 of 5: the occlusion test of each shadow ray in bounce
// `push.depth`'s shadow queue (dispatched indirectly); an unoccluded one adds what its light
// sample brings to its path's radiance, as trace_path does (common/path.glsl).
#include "wavefront/common.glsl"

layout(local_size_x = 128) in;

layout(set = 0, binding = 21, std430) buffer PathRadiance { vec4 v[]; } b_path_radiance;
layout(set = 0, binding = 25, std430) readonly buffer Counts { uint c[]; } b_counts;
layout(set = 0, binding = 29, std430) readonly buffer ShadowQueue { uint q[]; } b_shadow_queue;
layout(set = 0, binding = 30, std430) readonly buffer ShadowRays { ShadowRecord r[]; } b_shadow_rays;

layout(push_constant) uniform Push { uint depth; } push;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= b_counts.c[shadow_slot(push.depth)]) {
        return;
    }
    uint path = b_shadow_queue.q[i];
    ShadowRecord ray = b_shadow_rays.r[path];
    if (!trace_occluded(ray.origin.xyz, ray.direction.xyz, ray.origin.w)) {
        b_path_radiance.v[path].xyz += ray.radiance.xyz;
    }
}
