#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
// The BDPT light pass: one light subpath per invocation, started on an emitter picked in proportion
// to power (the starts stratified over the invocations: emission_numbers) and continued by BSDF
// sampling in importance transport (adjoint BSDF: no radiance scaling at refraction, Veach's
// shading-normal correction). Every vertex on a non-delta surface that can still be connected
// within max_depth goes to the light vertex cache, in the subpath's own slots (so the cache's
// layout does not depend on thread timing), and every such vertex is connected to the pinhole
// camera (light tracing, t = 1) and splatted into b_splat in fixed point (integer sums do not
// depend on the order either); the camera pass scales the splats by pixels / light subpaths.
#define SCENE_IN_WORKGROUP
#include "common/math.glsl"
#include "common/rng.glsl"
#include "common/scene.glsl"
#include "common/frame.glsl"
#include "common/traverse.glsl"
#include "common/bsdf.glsl"
#include "common/lights.glsl"
#include "common/surface.glsl"
#include "common/camera.glsl"
#include "common/light_emit.glsl"
#include "bdpt/bdpt.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 18, std430) buffer Stats { uint non_finite; uint rays; uint pad0; uint pad1; } b_stats;
layout(set = 0, binding = 20, std430) writeonly buffer Lvc { LightVertex v[]; } b_lvc;
layout(set = 0, binding = 21, std430) writeonly buffer LvcLengths { uint n[]; } b_lvc_lengths;
layout(set = 0, binding = 22, std430) buffer Splat { uint64_t v[]; } b_splat;
layout(set = 0, binding = 26, std430) writeonly buffer LvcColors { uvec2 c[]; } b_lvc_colors;

void splat_add(uint i, float x) {
    atomicAdd(b_splat.v[i], splat_fixed(x));
}

// Light tracing's share of connection roulette (bdpt.glsl; Settings::bdpt_connection_roulette, at
// most 1; 0: off): a camera connection whose MIS weight is under LIGHT_TRACING_ROULETTE is traced
// with probability weight / LIGHT_TRACING_ROULETTE and what it brings divided by that probability.
// Unbiased; under the power heuristic such a connection adds little next to the camera subpaths'
// strategies for the same path, and at 0.1 the light pass was 3.5-5.5% faster on an H200 for no
// error measurable at equal samples (bench/README.md).
layout(constant_id = 126) const float LIGHT_TRACING_ROULETTE = 0.1;

// Distinguishes light-subpath random streams from the camera pass's per-pixel ones.
const uint LIGHT_STREAM = 0x4c495448u;

// Light tracing: connects the vertex at s (BSDF m, local frame t b s.ns, wl = direction towards
// the previous vertex) to the camera, under light tracing's roulette (which draws its number from
// rng only where it applies). Returns 1 when the contribution was not finite.
uint connect_to_camera(Surface s, BsdfParams m, vec3 t, vec3 b, vec3 wl, vec3 beta, float dvcm, float dvc,
                       inout uint rng) {
    Camera c = b_frame.f.camera;
    if (c.position_aperture.w > 0.0) {
        return 0u;
    }
    uvec2 size = uvec2(b_frame.f.width, b_frame.f.height);
    float aspect = float(size.x) / float(size.y);
    vec3 film = camera_project(c, s.p, aspect);
    if (film.z <= 0.0 || any(lessThan(film.xy, vec2(0.0))) || any(greaterThanEqual(film.xy, vec2(1.0)))) {
        return 0u;
    }
    vec3 to_camera = c.position_aperture.xyz - s.p;
    float dist2 = dot(to_camera, to_camera);
    float dist = sqrt(dist2);
    vec3 dir = to_camera / dist;
    float cos_in = abs(dot(s.ng, wl));
    if (cos_in < 1e-6) {
        return 0u;
    }
    float rev_pdf;
    vec3 f = bsdf_eval(m, to_local(dir, t, b, s.ns), to_local(wl, t, b, s.ns), rev_pdf);
    if (max3(f) <= 0.0) {
        return 0u;
    }
    float cos_out = abs(dot(s.ng, dir));
    float cos_camera = film.z / dist;
    // The pinhole's importance per unit solid angle over the whole film, and the film's area
    // density of this vertex as the camera would sample it, per light subpath.
    float importance = 1.0 / (film_area(c, aspect) * cos_camera * cos_camera * cos_camera);
    float camera_pdf = importance * cos_out / (dist2 * pc.light_ratio);
    float w_light = mis(camera_pdf) * (dvcm + dvc * mis(rev_pdf));
    float w = 1.0 / (1.0 + w_light);
    vec3 value = beta * f * (cos_out / cos_in) * (importance / dist2) * w;
    if (any(isnan(value)) || any(isinf(value))) {
        return 1u;
    }
    if (w < LIGHT_TRACING_ROULETTE) {
        if (rng_next(rng) * LIGHT_TRACING_ROULETTE >= w) {
            return 0u;
        }
        value *= LIGHT_TRACING_ROULETTE / w;
    }
    // Traced from the camera to the vertex (lifted off its surface): rays from one origin walk the
    // tree's nodes around the camera together.
    vec3 to_vertex = offset_origin(s.p, s.ng, dir) - c.position_aperture.xyz;
    float reach = length(to_vertex);
    if (max3(value) <= 0.0 || counted_occluded(c.position_aperture.xyz, to_vertex / reach, reach)) {
        return 0u;
    }
    uvec2 pixel = min(uvec2(film.xy * vec2(size)), size - 1u);
    uint i = 3u * (pixel.y * size.x + pixel.x);
    splat_add(i, value.r);
    splat_add(i + 1u, value.g);
    splat_add(i + 2u, value.b);
    return 0u;
}

// Light subpaths start stratified: the five numbers that pick the light, the point on it and the
// direction come from cell index * EMIT_CELLS / light_paths of a grid of 8^5 cells in Morton order,
// jittered within the cell and shifted by one offset a frame (modulo 1). Each start stays uniform,
// the frame's starts cover the grid evenly, and neighbouring invocations leave from nearby points in
// nearby directions, so their first rays and camera connections walk the same nodes.
const uint EMIT_CELL_BITS = 3u;
const uint EMIT_CELLS = 1u << (5u * EMIT_CELL_BITS);

// Coordinate `dim` (0-4) of Morton-ordered cell `cell`.
float emit_stratum(uint cell, uint dim) {
    uint c = 0u;
    for (uint j = 0u; j < EMIT_CELL_BITS; ++j) {
        c |= ((cell >> (5u * j + dim)) & 1u) << j;
    }
    return float(c);
}

// The emission's numbers for light subpath `index`: u picks the light and the point, v the direction.
void emission_numbers(uint index, inout uint rng, out vec3 u, out vec2 v) {
    uint frame_rng = rng_init(uvec2(0xffffffffu, LIGHT_STREAM), b_frame.f.frame_index, b_frame.f.seed);
    uint cell = uint((uint64_t(index) * uint64_t(EMIT_CELLS)) / uint64_t(pc.light_paths));
    const float scale = 1.0 / float(1u << EMIT_CELL_BITS);
    u.x = fract((emit_stratum(cell, 0u) + rng_next(rng)) * scale + rng_next(frame_rng));
    u.y = fract((emit_stratum(cell, 1u) + rng_next(rng)) * scale + rng_next(frame_rng));
    u.z = fract((emit_stratum(cell, 2u) + rng_next(rng)) * scale + rng_next(frame_rng));
    v.x = fract((emit_stratum(cell, 3u) + rng_next(rng)) * scale + rng_next(frame_rng));
    v.y = fract((emit_stratum(cell, 4u) + rng_next(rng)) * scale + rng_next(frame_rng));
}

// Stores the subpath's next vertex in its slot `slot` of the cache, with its BSDF's base colour
// `base_color` where LVC_COLORS.
void store_vertex(uint slot, Surface s, vec3 base_color, vec3 wl, vec3 beta, float dvcm, float dvc, uint segments) {
    LightVertex v;
    v.p = s.p;
    v.material = s.material;
    v.throughput = beta;
    v.dvcm = dvcm;
    v.wi = wl;
    v.dvc = dvc;
    v.ng = encode_normal(s.ng);
    v.ns = encode_normal(s.ns);
    v.uv = packHalf2x16(s.uv);
    v.segments = segments;
    b_lvc.v[slot] = v;
    if (LVC_COLORS) {
        b_lvc_colors.c[slot] = encode_lvc_color(base_color);
    }
}

void main() {
    scene_to_workgroup(gl_WorkGroupSize.x * gl_WorkGroupSize.y);
    uint index = gl_GlobalInvocationID.y * pc.stride + gl_GlobalInvocationID.x;
    uint max_depth = b_frame.f.max_depth;
    if (index >= pc.light_paths || max_depth < 2u) {
        return;
    }
    uint rr_depth = b_frame.f.rr_depth;
    uint rng = rng_init(uvec2(index, LIGHT_STREAM), b_frame.f.frame_index, b_frame.f.seed);
    uint stored = 0u;
    EmitSample e;
    vec3 u_emit;
    vec2 v_emit;
    emission_numbers(index, rng, u_emit, v_emit);
    if (!sample_emission(u_emit, v_emit, e)) {
        b_lvc_lengths.n[index] = 0u;
        return;
    }
    vec3 beta = e.weight;
    float rr_scale = 1.0 / max(max3(beta), 1e-30);
    vec3 prev_p = e.p;
    vec3 o = e.delta ? e.p : offset_origin(e.p, e.n, e.dir);
    vec3 d = e.dir;
    float dvcm = 0.0;
    float dvc = 0.0;
    uint dropped = 0u;
    for (uint segments = 1u; segments < max_depth; ++segments) {
        Hit hit;
        if (!counted_closest(o, d, hit)) {
            break;
        }
        Surface s = surface_at(hit, o, d);
        vec3 seg = s.p - prev_p;
        float dist2 = dot(seg, seg);
        float cos_in = abs(dot(s.ng, d));
        if (cos_in < 1e-6) {
            break;
        }
        if (segments == 1u) {
            dvcm = mis(emission_nee_pdf(e, s.p) * dist2 / (e.pdf_dir * cos_in));
            dvc = e.delta ? 0.0 : mis(e.cos_light / (e.pdf_dir * cos_in));
        } else {
            dvcm *= mis(dist2) / mis(cos_in);
            dvc /= mis(cos_in);
        }
        BsdfParams m = material_params(s.material, s.uv, s.color);
        vec3 t;
        vec3 b;
        make_frame(s.ns, t, b);
        vec3 wl = -d;
        bool connectible = !bsdf_is_delta(m);
        bool last = segments + 2u > max_depth;
        if (connectible) {
            if (!last) {
                store_vertex(stored * pc.light_paths + index, s, m.color, wl, beta, dvcm, dvc, segments);
                stored += 1u;
            }
            dropped += connect_to_camera(s, m, t, b, wl, beta, dvcm, dvc, rng);
        }
        if (last) {
            break;
        }
        vec3 wo = to_local(wl, t, b, s.ns);
        vec3 u_bsdf = vec3(rng_next2(rng), rng_next(rng));
        BsdfSample bs;
        if (!bsdf_sample(m, wo, u_bsdf, bs) || abs(bs.wi.z) < 1e-6) {
            break;
        }
        vec3 wi = to_world(bs.wi, t, b, s.ns);
        float cos_out = abs(dot(s.ng, wi));
        // Adjoint BSDF with the shading-normal correction |wo.ns| |wi.ng| / (|wo.ng| |wi.ns|).
        beta *= bs.weight * adjoint_scale(m, wo, bs.wi) * (abs(wo.z) * cos_out / (cos_in * abs(bs.wi.z)));
        if (bs.delta) {
            dvcm = 0.0;
            dvc *= mis(cos_out);
        } else {
            dvc = mis(cos_out / bs.pdf) * (dvc * mis(bs.rev_pdf) + dvcm);
            dvcm = mis(1.0 / bs.pdf);
        }
        prev_p = s.p;
        o = offset_origin(s.p, s.ng, wi);
        d = wi;
        if (segments >= rr_depth) {
            float q = min(max3(beta) * rr_scale, 0.95);
            if (rng_next(rng) >= q) {
                break;
            }
            beta /= q;
        }
    }
    b_lvc_lengths.n[index] = stored;
    if (dropped > 0u) {
        atomicAdd(b_stats.non_finite, dropped);
    }
    uint rays = subgroupAdd(rays_traced);
    if (subgroupElect()) {
        atomicAdd(b_stats.rays, rays);
    }
}
