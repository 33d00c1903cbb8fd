// Ray queries over the two-level BVH (TLAS over instances, BLAS over triangles or spheres) in
// either GPU layout (WIDE_BVH): stack-based, near child first, with early exit for shadow rays; a
// single triangle instance is walked without the top level (SINGLE_INSTANCE); hits on cut-out
// materials count only where the surface is there (common/opacity.glsl, HAS_ALPHA_TEST). The
// binary walks are in traverse_binary.glsl, the wide ones in traverse_wide.glsl; a small scene's
// BLAS and triangles are read from workgroup memory in the shaders that copy them there
// (common/workgroup_scene.glsl). Requires scene.glsl.
#ifndef LUCID_TRAVERSE_GLSL
#define LUCID_TRAVERSE_GLSL

#include "common/opacity.glsl"

layout(constant_id = 100) const bool HAS_SPHERES = true;
// The scene is packed as exactly one triangle instance (GpuScene::single_instance, e.g. a fully
// flattened static scene), alone or beside the sphere instance of at most MAX_LOOSE_SPHERES
// spheres: trace_ray tests the spheres one by one and walks the triangles' BLAS directly, without
// the top level.
layout(constant_id = 108) const bool SINGLE_INSTANCE = false;
// The scene has so few instances (more than one, at most passes/src/plumbing/scene_buffers.rs's
// MAX_FEW_INSTANCES) that trace_ray walks each one's BLAS in turn rather than the top level.
layout(constant_id = 119) const bool FEW_INSTANCES = false;
// The BVH nodes are compressed 8-wide ones (lucid_engine::scene::gpu::BvhLayout::Wide), not binary.
layout(constant_id = 116) const bool WIDE_BVH = false;

#include "common/workgroup_scene.glsl"

const float T_INFINITY = 3.0e38;
// The root of an empty tree, in both layouts.
const uint BVH_EMPTY = 0xffffffffu;

struct Hit {
    float t;
    uint instance;  // index in b_instances
    uint primitive; // global triangle index, or sphere index
    vec2 bary;      // barycentrics (v1, v2) for triangles
};

// Entry distance of the ray into the box [lo, hi], or T_INFINITY when missed or beyond t_max.
float box_entry(vec3 lo, vec3 hi, vec3 scaled_origin, vec3 inv_dir, float t_max) {
    vec3 t0 = fma(lo, inv_dir, -scaled_origin);
    vec3 t1 = fma(hi, inv_dir, -scaled_origin);
    vec3 near = min(t0, t1);
    vec3 far = max(t0, t1);
    float enter = max(max(near.x, near.y), max(near.z, 0.0));
    float leave = min(min(far.x, far.y), min(far.z, t_max));
    return enter <= leave ? enter : T_INFINITY;
}

vec3 safe_inverse(vec3 d) {
    const float tiny = 1e-20;
    return 1.0 / vec3(abs(d.x) > tiny ? d.x : (d.x >= 0.0 ? tiny : -tiny),
                      abs(d.y) > tiny ? d.y : (d.y >= 0.0 ? tiny : -tiny),
                      abs(d.z) > tiny ? d.z : (d.z >= 0.0 ? tiny : -tiny));
}

// Moller-Trumbore with one early exit, on the first barycentric; the other tests are one select
// (the lanes of a subgroup test different triangles, so each further exit costs a branch and
// saves little). Returns t (or T_INFINITY) and barycentrics (zero on a miss).
float intersect_triangle(uint tri, vec3 o, vec3 d, float t_max, out vec2 bary) {
    vec4 a;
    vec4 b;
    float c;
    triangle_edges(tri, a, b, c);
    vec3 p0 = a.xyz;
    vec3 e1 = vec3(a.w, b.xy);
    vec3 e2 = vec3(b.zw, c);
    vec3 pv = cross(d, e2);
    float det = dot(e1, pv);
    float inv_det = 1.0 / det;
    vec3 tv = o - p0;
    float u = dot(tv, pv) * inv_det;
    if (!(u >= 0.0 && u <= 1.0)) {
        bary = vec2(0.0);
        return T_INFINITY;
    }
    vec3 qv = cross(tv, e1);
    float v = dot(d, qv) * inv_det;
    float t = dot(e2, qv) * inv_det;
    bool hit = abs(det) >= 1e-12 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t < t_max;
    bary = hit ? vec2(u, v) : vec2(0.0);
    return hit ? t : T_INFINITY;
}

// Nearest positive root of |o + t d - c| = r within (0, t_max).
float intersect_sphere(uint s, vec3 o, vec3 d, float t_max) {
    vec4 cr = b_spheres.s[s].center_radius;
    vec3 oc = o - cr.xyz;
    float a = dot(d, d);
    float b = dot(oc, d);
    float c = dot(oc, oc) - cr.w * cr.w;
    float disc = b * b - a * c;
    if (disc < 0.0) {
        return T_INFINITY;
    }
    float q = sqrt(disc);
    float t = (-b - q) / a;
    if (t <= 1e-5 * cr.w / sqrt(a)) {
        t = (-b + q) / a;
    }
    return (t > 1e-5 * cr.w / sqrt(a) && t < t_max) ? t : T_INFINITY;
}

// Makes (t, instance, primitive, bary) the hit when t is closer; returns whether it was.
bool record_hit(float t, uint instance, uint primitive, vec2 bary, inout Hit hit) {
    if (t < hit.t) {
        hit.t = t;
        hit.instance = instance;
        hit.primitive = primitive;
        hit.bary = bary;
        return true;
    }
    return false;
}

// Intersects primitive `prim` (a triangle, or a sphere of the sphere instance) of instance
// `inst_index` in object space; updates hit and returns true when it is closer.
bool intersect_primitive(uint inst_index, Instance inst, uint prim, vec3 o, vec3 d, inout Hit hit) {
    vec2 bary = vec2(0.0);
    float t;
    // With SINGLE_INSTANCE no BLAS walk meets a sphere: trace_ray tests them one by one.
    if (HAS_SPHERES && !SINGLE_INSTANCE && inst.kind == INSTANCE_SPHERES) {
        t = intersect_sphere(prim, o, d, hit.t);
    } else {
        t = intersect_triangle(prim, o, d, hit.t, bary);
        if (HAS_ALPHA_TEST && t < hit.t) {
            uint material = inst.kind == INSTANCE_FLATTENED ? b_triangle_ids.t[prim].x : inst.material;
            if (!hit_counts(material, prim, bary, o, d)) {
                t = T_INFINITY;
            }
        }
    }
    return record_hit(t, inst_index, prim, bary, hit);
}

// Intersects instance `inst_index` (its BLAS, through its transform) with the world-space ray;
// defined below, used by the top-level walks.
bool intersect_instance(uint inst_index, vec3 origin, vec3 dir, bool any_hit, inout Hit hit);

#include "common/traverse_binary.glsl"
#include "common/traverse_wide.glsl"

// Traverses one instance's BLAS in object space. Updates hit when closer; with any_hit, stops at
// the first hit and returns true.
bool traverse_blas(uint inst_index, Instance inst, vec3 o, vec3 d, bool any_hit, inout Hit hit) {
    if (WIDE_BVH) {
        return traverse_blas_wide(inst_index, inst, o, d, any_hit, hit);
    }
    return traverse_blas_binary(inst_index, inst, o, d, any_hit, hit);
}

bool intersect_instance(uint inst_index, vec3 origin, vec3 dir, bool any_hit, inout Hit hit) {
    Instance inst = b_instances.i[inst_index];
    vec3 o = transform_point(inst.world_to_object, origin);
    vec3 d = transform_vector(inst.world_to_object, dir);
    return traverse_blas(inst_index, inst, o, d, any_hit, hit);
}

// Tests every sphere of the sphere instance `slot` (world space, as its transform is the identity)
// one by one, as SINGLE_INSTANCE does. Updates hit when closer; with any_hit, stops at the first hit
// and returns true.
bool intersect_loose_spheres(uint slot, vec3 origin, vec3 dir, bool any_hit, inout Hit hit) {
    bool found = false;
    for (uint s = 0u; s < b_scene.p.counts0.z; ++s) {
        if (record_hit(intersect_sphere(s, origin, dir, hit.t), slot, s, vec2(0.0), hit)) {
            found = true;
            if (any_hit) {
                return true;
            }
        }
    }
    return found;
}

// Closest hit along origin + t * dir for t in (0, t_max). Returns false on a miss.
bool trace_ray(vec3 origin, vec3 dir, float t_max, bool any_hit, out Hit hit) {
    hit.t = t_max;
    hit.instance = 0xffffffffu;
    hit.primitive = 0u;
    hit.bary = vec2(0.0);
    uint word = b_scene.p.counts1.z; // the TLAS root (a binary child word or a wide node)
    if (word == BVH_EMPTY) {
        return false;
    }
    if (SINGLE_INSTANCE) {
        // The spheres first (their instance, where there is one, is one of the two), then the
        // triangle instance: a flattened one is in world space; any other keeps its transform (a
        // dynamic one).
        uint slot = 0u;
        bool found = false;
        if (HAS_SPHERES) {
            uint spheres = b_instances.i[0].kind == INSTANCE_SPHERES ? 0u : 1u;
            slot = 1u - spheres;
            found = intersect_loose_spheres(spheres, origin, dir, any_hit, hit);
            if (found && any_hit) {
                return true;
            }
        }
        Instance inst = b_instances.i[slot];
        if (inst.kind == INSTANCE_FLATTENED) {
            return traverse_blas(slot, inst, origin, dir, any_hit, hit) || found;
        }
        vec3 o = transform_point(inst.world_to_object, origin);
        vec3 d = transform_vector(inst.world_to_object, dir);
        return traverse_blas(slot, inst, o, d, any_hit, hit) || found;
    }
    if (FEW_INSTANCES) {
        bool found = false;
        for (uint i = 0u; i < b_scene.p.counts0.y; ++i) {
            if (intersect_instance(i, origin, dir, any_hit, hit)) {
                found = true;
                if (any_hit) {
                    return true;
                }
            }
        }
        return found;
    }
    if (WIDE_BVH) {
        return trace_wide_tlas(word, origin, dir, any_hit, hit);
    }
    return trace_binary_tlas(word, origin, dir, any_hit, hit);
}

bool trace_closest(vec3 origin, vec3 dir, float t_max, out Hit hit) {
    return trace_ray(origin, dir, t_max, false, hit);
}

bool trace_occluded(vec3 origin, vec3 dir, float t_max) {
    Hit hit;
    return trace_ray(origin, dir, t_max, true, hit);
}

// Whether each of two shadow rays (t_max <= 0: none) is occluded within (0, t_max). With one
// triangle instance (SINGLE_INSTANCE) both walk its BLAS in one loop (occluded_pair_blas_binary
// or occluded_pair_blas_wide), after the loose spheres; otherwise they are traced one after the
// other.
bvec2 trace_occluded_pair(vec3 o0, vec3 d0, float t0, vec3 o1, vec3 d1, float t1) {
    if (!SINGLE_INSTANCE) {
        return bvec2(t0 > 0.0 && trace_occluded(o0, d0, t0), t1 > 0.0 && trace_occluded(o1, d1, t1));
    }
    if (b_scene.p.counts1.z == BVH_EMPTY) {
        return bvec2(false);
    }
    uint slot = 0u;
    bvec2 by_spheres = bvec2(false);
    if (HAS_SPHERES) {
        uint spheres = b_instances.i[0].kind == INSTANCE_SPHERES ? 0u : 1u;
        slot = 1u - spheres;
        Hit hit;
        hit.t = t0;
        by_spheres.x = t0 > 0.0 && intersect_loose_spheres(spheres, o0, d0, true, hit);
        hit.t = t1;
        by_spheres.y = t1 > 0.0 && intersect_loose_spheres(spheres, o1, d1, true, hit);
    }
    Instance inst = b_instances.i[slot];
    if (inst.kind != INSTANCE_FLATTENED) {
        o0 = transform_point(inst.world_to_object, o0);
        d0 = transform_vector(inst.world_to_object, d0);
        o1 = transform_point(inst.world_to_object, o1);
        d1 = transform_vector(inst.world_to_object, d1);
    }
    float s0 = by_spheres.x ? 0.0 : t0;
    float s1 = by_spheres.y ? 0.0 : t1;
    bvec2 by_triangles = WIDE_BVH ? occluded_pair_blas_wide(slot, inst, o0, d0, s0, o1, d1, s1)
                                  : occluded_pair_blas_binary(slot, inst, o0, d0, s0, o1, d1, s1);
    return bvec2(by_spheres.x || by_triangles.x, by_spheres.y || by_triangles.y);
}

#endif
