// One unidirectional path (next-event estimation + BSDF sampling with the power heuristic,
// Russian roulette), shared by the path tracer and the SVGF gradient pass, which replays a pixel's
// path with exactly the path tracer's random numbers. Requires math, rng, scene, traverse, bsdf,
// lights and surface.
#ifndef LUCID_PATH_GLSL
#define LUCID_PATH_GLSL

struct PathResult {
    vec3 radiance;       // the path's contribution
    vec3 first_albedo;   // demodulation albedo of the first hit (white for the sky and dielectrics)
    vec3 first_emission; // radiance emitted towards the camera by the first hit (or the sky)
};

// Traces the path starting with the camera ray (o, d), whose cone widens by `spread` radians per
// unit distance (textures at the first hit are filtered for it); adds the rays it traces to
// `rays`.
PathResult trace_path(vec3 o, vec3 d, inout uint rng, uint max_depth, uint rr_depth, float spread, inout uint rays) {
    PathResult r;
    r.radiance = vec3(0.0);
    r.first_albedo = vec3(1.0);
    r.first_emission = vec3(0.0);
    vec3 beta = vec3(1.0);
    float prev_pdf = 0.0;
    bool prev_delta = true;
    vec3 prev_p = o;
    for (uint depth = 0u; depth < max_depth; ++depth) {
        Hit hit;
        rays += 1u;
        if (!trace_closest(o, d, T_INFINITY, hit)) {
            vec3 sun = sun_radiance(d);
            float w_sun = prev_delta ? 1.0 : power_heuristic(prev_pdf, sun_pdf());
            float w_env = prev_delta || !environment_sampled() ? 1.0 : power_heuristic(prev_pdf, environment_pdf(d));
            r.radiance += beta * (environment_radiance(d) * w_env + sun * w_sun);
            if (depth == 0u) {
                r.first_emission = r.radiance;
            }
            break;
        }
        Surface s = surface_at(hit, o, d);
        vec3 emitted = surface_emission(s, d);
        if (max3(emitted) > 0.0) {
            float w = prev_delta ? 1.0 : power_heuristic(prev_pdf, surface_light_pdf(s, prev_p));
            r.radiance += beta * emitted * w;
        }
        if (depth == 0u) {
            r.first_emission = r.radiance;
        }
        if (depth + 1u >= max_depth) {
            break;
        }
        float footprint = depth == 0u ? cone_lod(s, d, hit.t * spread) : NO_FOOTPRINT;
        BsdfParams m = material_params_lod(s.material, s.uv, s.color, footprint);
        if (depth == 0u) {
            r.first_albedo = demodulation_albedo(m);
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
                    vec3 origin = offset_origin(s.p, s.ng, ls.wi);
                    float t_max = ls.dist >= T_INFINITY ? T_INFINITY : ls.dist * (1.0 - 1e-3);
                    rays += 1u;
                    if (!trace_occluded(origin, ls.wi, t_max)) {
                        float w = ls.delta ? 1.0 : power_heuristic(ls.pdf, bsdf_pdf);
                        r.radiance += beta * f * ls.radiance * (w * ls.weight);
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
    return r;
}

#endif
