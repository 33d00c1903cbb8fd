#version 460
// Batch ray queries against the scene BVH: closest hit (distance, object id) and occlusion, one
// invocation per ray, the occlusion also as the pair walk answers it (trace_occluded_pair) with the
// ray walked first beside its neighbour (index ^ 1) and second after it. Used to check the GPU
// traversal against the CPU one, and for picking.
#define SCENE_IN_WORKGROUP
#include "common/math.glsl"
#include "common/scene.glsl"
#include "common/traverse.glsl"

layout(local_size_x = 64) in;

struct RayIn {
    vec4 origin_tmax;
    vec4 dir;
};

struct HitOut {
    float t;         // distance, or -1 on a miss
    uint object_id;  // scene instance, or 0x80000000 | sphere; ~0 on a miss
    uint occluded;   // any-hit result within t_max
    uint paired;     // the same from the pair walk: bit 0 walked first, bit 1 walked second
};

layout(set = 0, binding = 16, std430) readonly buffer Rays { RayIn r[]; } b_rays;
layout(set = 0, binding = 17, std430) writeonly buffer Hits { HitOut h[]; } b_hits;

layout(push_constant) uniform Params {
    uint count;
} params;

void main() {
    scene_to_workgroup(gl_WorkGroupSize.x);
    uint index = gl_GlobalInvocationID.x;
    if (index >= params.count) {
        return;
    }
    RayIn ray = b_rays.r[index];
    Hit hit;
    HitOut result;
    if (trace_closest(ray.origin_tmax.xyz, ray.dir.xyz, ray.origin_tmax.w, hit)) {
        result.t = hit.t;
        Instance inst = b_instances.i[hit.instance];
        if (inst.kind == INSTANCE_SPHERES) {
            result.object_id = 0x80000000u | b_spheres.s[hit.primitive].scene_sphere;
        } else if (inst.kind == INSTANCE_FLATTENED) {
            result.object_id = b_triangle_ids.t[hit.primitive].y;
        } else {
            result.object_id = inst.scene_instance;
        }
    } else {
        result.t = -1.0;
        result.object_id = 0xffffffffu;
    }
    result.occluded = trace_occluded(ray.origin_tmax.xyz, ray.dir.xyz, ray.origin_tmax.w) ? 1u : 0u;
    RayIn other = b_rays.r[min(index ^ 1u, params.count - 1u)];
    bvec2 first = trace_occluded_pair(ray.origin_tmax.xyz, ray.dir.xyz, ray.origin_tmax.w, other.origin_tmax.xyz,
                                      other.dir.xyz, other.origin_tmax.w);
    bvec2 second = trace_occluded_pair(other.origin_tmax.xyz, other.dir.xyz, other.origin_tmax.w,
                                       ray.origin_tmax.xyz, ray.dir.xyz, ray.origin_tmax.w);
    result.paired = (first.x ? 1u : 0u) | (second.y ? 2u : 0u);
    b_hits.h[index] = result;
}
