#version 460
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require
// Unidirectional path tracing: next-event estimation and BSDF sampling combined with multiple
// importance sampling (power heuristic), Russian roulette, `spp` samples per pixel. Writes the
// noisy radiance and radiance demodulated by the first-hit albedo. Non-finite samples are dropped
// and counted in b_stats, as are the rays traced (for rays/s figures).
#include "common/math.glsl"
#include "common/rng.glsl"
#include "common/scene.glsl"
#include "common/frame.glsl"
#include "common/traverse.glsl"
#include "common/bsdf.glsl"
#include "common/lights.glsl"
#include "common/surface.glsl"
#include "common/camera.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 16, rgba32f) uniform writeonly image2D u_radiance;
layout(set = 0, binding = 17, rgba32f) uniform writeonly image2D u_demodulated;
layout(set = 0, binding = 18, std430) buffer Stats { uint non_finite; uint rays; uint pad0; uint pad1; } b_stats;

uint g_rays = 0u;

vec3 trace_path(vec3 o, vec3 d, inout uint rng, uint max_depth, uint rr_depth, out vec3 first_albedo) {
    vec3 radiance = vec3(0.0);
    vec3 beta = vec3(1.0);
    float prev_pdf = 0.0;
    bool prev_delta = true;
    vec3 prev_p = o;
    first_albedo = vec3(1.0);
    for (uint depth = 0u; depth < max_depth; ++depth) {
        Hit hit;
        g_rays += 1u;
        if (!trace_closest(o, d, T_INFINITY, hit)) {
            vec3 sun = sun_radiance(d);
            float w_sun = prev_delta ? 1.0 : power_heuristic(prev_pdf, sun_pdf());
            radiance += beta * (environment_radiance(d) + sun * w_sun);
            break;
        }
        Surface s = surface_at(hit, o, d);
        vec3 emitted = surface_emission(s, d);
        if (max3(emitted) > 0.0) {
            float w = prev_delta ? 1.0 : power_heuristic(prev_pdf, surface_light_pdf(s, prev_p));
            radiance += beta * emitted * w;
        }
        if (depth + 1u >= max_depth) {
            break;
        }
        BsdfParams m = material_params(s.material, s.uv);
        if (depth == 0u) {
            first_albedo = demodulation_albedo(m);
        }
        vec3 t;
        vec3 b;
        make_frame(s.ns, t, b);
        vec3 wo = to_local(-d, t, b, s.ns);
        vec3 u_light = vec3(rng_next(rng), rng_next2(rng));
        vec3 u_bsdf = vec3(rng_next2(rng), rng_next(rng));
        if (!bsdf_is_delta(m)) {
            LightSample ls;
            if (sample_light(s.p, u_light, ls) && ls.pdf > 0.0) {
                float bsdf_pdf;
                vec3 f = bsdf_eval(m, wo, to_local(ls.wi, t, b, s.ns), bsdf_pdf);
                if (max3(f) > 0.0) {
                    vec3 origin = offset_origin(s.p, s.ng, ls.wi);
                    float t_max = ls.dist >= T_INFINITY ? T_INFINITY : ls.dist * (1.0 - 1e-3);
                    g_rays += 1u;
                    if (!trace_occluded(origin, ls.wi, t_max)) {
                        float w = ls.delta ? 1.0 : power_heuristic(ls.pdf, bsdf_pdf);
                        radiance += beta * f * ls.radiance * (w / ls.pdf);
                    }
                }
            }
        }
        BsdfSample bs;
        if (!bsdf_sample(m, wo, u_bsdf, bs)) {
            break;
        }
        vec3 wi = to_world(bs.wi, t, b, s.ns);
        beta *= bs.weight;
        prev_pdf = bs.pdf;
        prev_delta = bs.delta;
        prev_p = s.p;
        o = offset_origin(s.p, s.ng, wi);
        d = wi;
        if (depth + 1u >= rr_depth) {
            float q = min(max3(beta), 0.95);
            if (rng_next(rng) >= q) {
                break;
            }
            beta /= q;
        }
    }
    return radiance;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uvec2 size = b_frame.f.size.xy;
    if (any(greaterThanEqual(uvec2(pixel), size))) {
        return;
    }
    uint rng = rng_init(uvec2(pixel), b_frame.f.frame.x, b_frame.f.frame.y);
    uint spp = max(b_frame.f.frame.z, 1u);
    uint max_depth = b_frame.f.frame.w;
    uint rr_depth = uint(b_frame.f.params.x);
    float aspect = float(size.x) / float(size.y);
    vec3 sum = vec3(0.0);
    vec3 albedo_sum = vec3(0.0);
    uint dropped = 0u;
    for (uint i = 0u; i < spp; ++i) {
        vec2 ndc = film_ndc(vec2(pixel), rng_next2(rng), vec2(size));
        vec3 origin;
        vec3 dir;
        camera_ray(b_frame.f.camera, ndc, aspect, rng_next2(rng), origin, dir);
        vec3 albedo;
        vec3 l = trace_path(origin, dir, rng, max_depth, rr_depth, albedo);
        if (any(isnan(l)) || any(isinf(l))) {
            dropped += 1u;
            l = vec3(0.0);
        }
        sum += l;
        albedo_sum += albedo;
    }
    if (dropped > 0u) {
        atomicAdd(b_stats.non_finite, dropped);
    }
    uint rays = subgroupAdd(g_rays);
    if (subgroupElect()) {
        atomicAdd(b_stats.rays, rays);
    }
    vec3 radiance = sum / float(spp);
    vec3 albedo = albedo_sum / float(spp);
    imageStore(u_radiance, pixel, vec4(radiance, 1.0));
    imageStore(u_demodulated, pixel, vec4(radiance / max(albedo, vec3(1e-3)), 1.0));
}
