// Shared by the bidirectional path tracing passes: parameters, the light-vertex-cache record, the
// MIS heuristic and small helpers. Mirrors lucid_passes::bdpt (Params, LIGHT_VERTEX_BYTES).
//
// MIS follows the recursive formulation of SmallVCM / "Implementing Vertex Connection and Merging"
// (Georgiev 2012) restricted to vertex connection: each subpath vertex carries dvcm and dvc, partial
// sums of pdf ratios, from which every strategy's weight 1 / (1 + w_light + w_camera) follows in
// O(1). Area conversions use geometric normals; Russian roulette is left out of the pdfs (the
// weights still sum to one, so the estimate stays unbiased). Requires math.glsl, bsdf.glsl,
// traverse.glsl.
#ifndef LUCID_BDPT_GLSL
#define LUCID_BDPT_GLSL

#include "common/sample_batch.glsl"

// Power heuristic (exponent 2) when true, balance heuristic otherwise.
layout(constant_id = 120) const bool MIS_POWER = true;

// Cached light vertices each camera vertex connects to (a constant, so that one connection is no
// loop: BDPT's camera pass up to 3.5% faster on an H200, bench/README.md).
layout(constant_id = 124) const uint CONNECTIONS = 1u;

// Connection roulette (Settings::bdpt_connection_roulette; 0: off). At the camera vertices before
// Russian roulette's start, a connection whose unoccluded contribution (its largest channel, the
// camera subpath's throughput included) is under CONNECTION_ROULETTE times the largest channel of
// what the camera subpath has gathered so far is traced with probability contribution / threshold,
// and what it brings is divided by that probability: unbiased, and most of the shadow rays of
// connections that would change their sample little are not traced (bench/README.md). Light
// tracing's camera connections have a roulette of their own on the same setting (light.comp).
layout(constant_id = 125) const float CONNECTION_ROULETTE = 0.1;

// Next-event estimation's shadow ray waits for the first connection's, and the two are walked
// together (trace_occluded_pair: a lane whose first walk ends goes on with its second, so that a
// subgroup waits for its slowest pair rather than its slowest NEE ray and then its slowest
// connection). On an H200 BDPT's camera pass on `classroom` took 4.1% less time, though holding
// the waiting ray took it from 72 to 96 registers; where that cost more than the pairing saved the
// renderer turns it off (bdpt::pairs_shadow_rays, bench/README.md), and NEE's ray is walked at once.
layout(constant_id = 127) const bool PAIRED_SHADOW_RAYS = true;

layout(push_constant) uniform Params {
    uint light_paths;  // light subpaths traced this frame
    uint stride;       // light-pass invocations per dispatch row
    float light_ratio; // light subpaths per camera sample
    float splat_scale; // pixels / light subpaths
    SampleBatch batch; // the camera pass's samples this dispatch
} pc;

// A light subpath vertex on a non-delta surface, 64 bytes. Subpath i's k-th is in cache slot
// k * light_paths + i (vertex-major: the stores of a light-pass subgroup's subpaths at one bounce
// fall side by side, which took 5-12% off the light pass on an H200, bench/README.md).
struct LightVertex {
    vec3 p;
    uint material;
    vec3 throughput; // emission / pdf, including every BSDF factor up to (not at) this vertex
    float dvcm;
    vec3 wi;         // unit direction towards the previous vertex of the light subpath
    float dvc;
    uint ng;         // geometric normal, octahedral (decode_normal)
    uint ns;         // shading normal, octahedral
    uint uv;         // packHalf2x16
    uint segments;   // segments from the light
};

// A cached vertex's base colour, where textures or vertex colours make it vary over a material
// (LVC_COLORS; in the parallel buffer b_lvc_colors, so that other scenes keep 64-byte vertices):
// RGB as half floats. The camera pass's connections then evaluate the vertex's BSDF without its
// base colour texture (BDPT's camera pass on `classroom` 5% faster on an H200, 72 registers instead
// of 96, bench/README.md).
const bool LVC_COLORS = HAS_TEXTURES || HAS_VERTEX_COLORS;

uvec2 encode_lvc_color(vec3 c) {
    return uvec2(packHalf2x16(c.rg), packHalf2x16(vec2(c.b, 0.0)));
}

vec3 decode_lvc_color(uvec2 c) {
    return vec3(unpackHalf2x16(c.x), unpackHalf2x16(c.y).x);
}

// Light-tracing splats are summed in fixed point with 32 fractional bits (64-bit integers need the
// int64 extensions in the including shader): integer sums do not depend on the order threads add in.
const float SPLAT_ONE = 4294967296.0;

// A non-negative splat in fixed point (clamped to 1e9 so that sums cannot wrap).
uint64_t splat_fixed(float x) {
    return uint64_t(min(x, 1e9) * SPLAT_ONE);
}

// Rays this invocation traced (for rays/s figures), through the two wrappers below.
uint rays_traced = 0u;

bool counted_closest(vec3 origin, vec3 dir, out Hit hit) {
    rays_traced += 1u;
    return trace_closest(origin, dir, T_INFINITY, hit);
}

bool counted_occluded(vec3 origin, vec3 dir, float t_max) {
    rays_traced += 1u;
    return trace_occluded(origin, dir, t_max);
}

// Both shadow rays' occlusion (t_max <= 0: none), walked together.
bvec2 counted_occluded_pair(vec3 o0, vec3 d0, float t0, vec3 o1, vec3 d1, float t1) {
    rays_traced += (t0 > 0.0 ? 1u : 0u) + (t1 > 0.0 ? 1u : 0u);
    return trace_occluded_pair(o0, d0, t0, o1, d1, t1);
}

float mis(float x) {
    return MIS_POWER ? x * x : x;
}

// The two-strategy weight of a (MIS-exponentiated) over b.
float mis_pair(float a, float b) {
    float ma = mis(a);
    float mb = mis(b);
    return ma + mb > 0.0 ? ma / (ma + mb) : 0.0;
}

// Octahedral encoding of a unit vector (the inverse of decode_normal).
uint encode_normal(vec3 n) {
    vec2 e = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    if (n.z < 0.0) {
        vec2 s = vec2(e.x >= 0.0 ? 1.0 : -1.0, e.y >= 0.0 ? 1.0 : -1.0);
        e = (1.0 - abs(e.yx)) * s;
    }
    return packSnorm2x16(e);
}

// f(wo -> wi) / f(wi -> wo) in the local frame: eta^2 across a dielectric refraction, 1 otherwise.
// Multiplying a BSDF sample drawn from wo by it gives the importance-transport (adjoint) weight.
float adjoint_scale(BsdfParams m, vec3 wo, vec3 wi) {
    if (m.kind != MATERIAL_DIELECTRIC || wo.z * wi.z >= 0.0) {
        return 1.0;
    }
    float eta = wo.z > 0.0 ? m.ior : 1.0 / m.ior;
    return eta * eta;
}

// Area of the film of a pinhole camera at unit distance.
float film_area(Camera c, float aspect) {
    float tan_half = c.up_tan_half_fov.w;
    return 4.0 * tan_half * tan_half * aspect;
}

#endif
