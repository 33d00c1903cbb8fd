// One unidirectional path (next-event estimation + BSDF sampling with the power heuristic,
// Russian roulette), shared by the path tracer and the SVGF gradient pass, which replays a pixel's
// path with exactly the path tracer's random numbers. Requires math, rng, scene, traverse, bsdf,
// lights and surface.
//
// The path's steps are also functions of their own (what a miss brings, what a hit emits, the
// light sample and its shadow ray, the next direction), which the wavefront path tracer
// (shaders/wavefront/) runs as kernels over queues of paths, drawing the same random numbers in
// the same order. trace_path keeps the steps written out: composed of these functions the
// megakernel took more registers on an H100 (cornell-box 72 -> 96, classroom 96 -> 128) and 5-13%
// more time (classroom 7.13 -> 8.06 ms at 1080p; bench/README.md). tests/wavefront.rs checks that
// both compute the same image, bit for bit, from the same random numbers.
#ifndef LUCID_PATH_GLSL
#define LUCID_PATH_GLSL

// What a path carries from one segment to the next: its throughput and how its last direction was
// sampled (for MIS where the segment meets an emitter or the sky).
struct PathState {
    vec3 beta;       // throughput
    float prev_pdf;  // solid-angle pdf of the last direction (BSDF sampling)
    bool prev_delta; // the last direction came from a delta lobe (or the camera): no MIS
    vec3 prev_p;     // the vertex the last direction left from
};

// The state of a path whose camera ray starts at `origin`.
PathState path_start(vec3 origin) {
    PathState st;
    st.beta = vec3(1.0);
    st.prev_pdf = 0.0;
    st.prev_delta = true;
    st.prev_p = origin;
    return st;
}

// The radiance the sky and the sun bring along `d`, a ray of path `st` that hit nothing,
// MIS-weighted against their light samples.
vec3 path_miss(PathState st, vec3 d) {
    vec3 sun = sun_radiance(d);
    float w_sun = st.prev_delta ? 1.0 : power_heuristic(st.prev_pdf, sun_pdf());
    float w_env = st.prev_delta || !environment_sampled() ? 1.0 : power_heuristic(st.prev_pdf, environment_pdf(d));
    return st.beta * (environment_radiance(d) * w_env + sun * w_sun);
}

// The radiance surface `s`, hit by a ray of path `st` along `d`, emits towards it, MIS-weighted
// against the light samples that could have found it.
vec3 path_emission(PathState st, Surface s, vec3 d) {
    vec3 emitted = surface_emission(s, d);
    if (max3(emitted) > 0.0) {
        float w = st.prev_delta ? 1.0 : power_heuristic(st.prev_pdf, surface_light_pdf(s, st.prev_p));
        return st.beta * emitted * w;
    }
    return vec3(0.0);
}

// The material at a hit and its shading frame.
struct Shading {
    BsdfParams m;
    vec3 t;  // tangent
    vec3 b;  // bitangent
    vec3 wo; // towards where the ray came from, in the frame
};

// The shading of surface `s` hit along `d`; textures filtered for `footprint` (NO_FOOTPRINT:
// level 0).
Shading path_shading(Surface s, vec3 d, float footprint) {
    Shading sh;
    sh.m = material_params_lod(s.material, s.uv, s.color, footprint);
    make_frame(s.ns, sh.t, sh.b);
    sh.wo = to_local(-d, sh.t, sh.b, s.ns);
    return sh;
}

// A shadow ray of next-event estimation, with what it brings to the path when unoccluded.
struct ShadowRay {
    vec3 origin;
    vec3 dir;
    float t_max;
    vec3 radiance; // throughput x BSDF x light x MIS weight / pdf
};

// Next-event estimation at `s` with light sample `u_light`: false when it cannot bring anything
// (a delta BSDF, no light sampled, the BSDF zero towards it), else the shadow ray to test.
bool path_light_sample(PathState st, Surface s, Shading sh, vec4 u_light, out ShadowRay ray) {
    if (bsdf_is_delta(sh.m)) {
        return false;
    }
    LightSample ls;
    if (!(sample_light(s.p, u_light, ls) && ls.pdf > 0.0)) {
        return false;
    }
    float bsdf_pdf;
    vec3 f = bsdf_eval(sh.m, sh.wo, to_local(ls.wi, sh.t, sh.b, s.ns), bsdf_pdf);
    if (!(max3(f) > 0.0)) {
        return false;
    }
    light_shadow_ray(s.p, s.ng, ls, ray.origin, ray.dir, ray.t_max);
    float w = ls.delta ? 1.0 : power_heuristic(ls.pdf, bsdf_pdf);
    ray.radiance = st.beta * f * ls.radiance * (w * ls.weight);
    return true;
}

// Samples the direction after the vertex at `s` (at `depth`) with `u_bsdf`, then Russian roulette
// from `rr_depth` on (one draw of `rng`): false when the path ends, else `st` and the next ray
// (o, d).
bool path_continue(inout PathState st, Surface s, Shading sh, vec3 u_bsdf, uint depth, uint rr_depth, inout uint rng, out vec3 o, out vec3 d) {
    BsdfSample bs;
    if (!bsdf_sample(sh.m, sh.wo, u_bsdf, bs)) {
        return false;
    }
    vec3 wi = to_world(bs.wi, sh.t, sh.b, s.ns);
    st.beta *= bs.weight;
    st.prev_pdf = bs.pdf;
    st.prev_delta = bs.delta;
    st.prev_p = s.p;
    o = offset_origin(s.p, s.ng, wi);
    d = wi;
    if (depth + 1u >= rr_depth) {
        float q = min(max3(st.beta), 0.95);
        if (rng_next(rng) >= q) {
            return false;
        }
        st.beta /= q;
    }
    return true;
}

// The random numbers of a vertex, in the order trace_path draws them: the light sample's, then
// the BSDF sample's (Russian roulette draws one more in path_continue).
void path_vertex_numbers(inout uint rng, out vec4 u_light, out vec3 u_bsdf) {
    u_light = vec4(rng_next(rng), rng_next2(rng), rng_side(rng));
    u_bsdf = vec3(rng_next2(rng), rng_next(rng));
}

// trace_path hands the first hit's demodulation albedo (white for the sky and dielectrics) and the
// radiance it (or the sky) emits towards the camera to the statements PATH_KEEP_FIRST_ALBEDO(v) and
// PATH_KEEP_FIRST_EMISSION(v), which the including shader defines: the path tracer keeps them in
// workgroup memory where it writes the denoiser's images, rather than carry them through the whole
// path in registers, and drops them where it does not (shaders/path_trace, bench/README.md). A
// shader that defines neither has no trace_path.
#ifdef PATH_KEEP_FIRST_ALBEDO

// The radiance the path brings from its segment `first_depth` on, whose next ray is (o, d) and
// whose throughput and MIS state are beta, prev_pdf, prev_delta and prev_p (a camera ray's at
// segment 0, whose cone widens by `spread` radians per unit distance: textures at the first hit are
// filtered for it); adds the rays it traces to `rays`. Where the including shader defines
// PATH_PARK (path_trace/long_paths.glsl), a path still alive after PARK_DEPTH segments is handed
// to it and ends here.
vec3 trace_path_from(uint first_depth, vec3 o, vec3 d, vec3 beta, float prev_pdf, bool prev_delta, vec3 prev_p,
                     inout uint rng, uint max_depth, uint rr_depth, float spread, inout uint rays) {
    vec3 radiance = vec3(0.0);
    if (first_depth == 0u) {
        PATH_KEEP_FIRST_ALBEDO(vec3(1.0));
        PATH_KEEP_FIRST_EMISSION(vec3(0.0));
    }
    for (uint depth = first_depth; depth < max_depth; ++depth) {
        Hit hit;
        rays += 1u;
        if (!trace_closest(o, d, T_INFINITY, hit)) {
            vec3 sun = sun_radiance(d);
            float w_sun = prev_delta ? 1.0 : power_heuristic(prev_pdf, sun_pdf());
            float w_env = prev_delta || !environment_sampled() ? 1.0 : power_heuristic(prev_pdf, environment_pdf(d));
            radiance += beta * (environment_radiance(d) * w_env + sun * w_sun);
            if (depth == 0u) {
                PATH_KEEP_FIRST_EMISSION(radiance);
            }
            break;
        }
        Surface s = surface_at(hit, o, d);
        vec3 emitted = surface_emission(s, d);
        if (max3(emitted) > 0.0) {
            float w = prev_delta ? 1.0 : power_heuristic(prev_pdf, surface_light_pdf(s, prev_p));
            radiance += beta * emitted * w;
        }
        if (depth == 0u) {
            PATH_KEEP_FIRST_EMISSION(radiance);
        }
        if (depth + 1u >= max_depth) {
            break;
        }
        float footprint = depth == 0u ? cone_lod(s, d, hit.t * spread) : NO_FOOTPRINT;
        BsdfParams m = material_params_lod(s.material, s.uv, s.color, footprint);
        if (depth == 0u) {
            PATH_KEEP_FIRST_ALBEDO(demodulation_albedo(m));
        }
        vec3 t;
        vec3 b;
        make_frame(s.ns, t, b);
        vec3 wo = to_local(-d, t, b, s.ns);
        vec4 u_light = vec4(rng_next(rng), rng_next2(rng), rng_side(rng));
        vec3 u_bsdf = vec3(rng_next2(rng), rng_next(rng));
        if (!bsdf_is_delta(m)) {
            LightSample ls;
            if (sample_light(s.p, u_light, ls) && ls.pdf > 0.0) {
                float bsdf_pdf;
                vec3 f = bsdf_eval(m, wo, to_local(ls.wi, t, b, s.ns), bsdf_pdf);
                if (max3(f) > 0.0) {
                    vec3 origin;
                    vec3 dir;
                    float t_max;
                    light_shadow_ray(s.p, s.ng, ls, origin, dir, t_max);
                    rays += 1u;
                    if (!trace_occluded(origin, dir, t_max)) {
                        float w = ls.delta ? 1.0 : power_heuristic(ls.pdf, bsdf_pdf);
                        radiance += beta * f * ls.radiance * (w * ls.weight);
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
#ifdef PATH_PARK
        if (depth + 1u == PARK_DEPTH) {
            PATH_PARK(o, d, beta, prev_pdf, prev_delta, prev_p, rng);
            break;
        }
#endif
    }
    return radiance;
}

// The radiance of the path starting with the camera ray (o, d); see trace_path_from.
vec3 trace_path(vec3 o, vec3 d, inout uint rng, uint max_depth, uint rr_depth, float spread, inout uint rays) {
    return trace_path_from(0u, o, d, vec3(1.0), 0.0, true, o, rng, max_depth, rr_depth, spread, rays);
}

#endif

#endif
