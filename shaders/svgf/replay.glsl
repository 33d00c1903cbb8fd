// A copy of the path tracer's `trace_path` (shaders/path_trace/path_trace.comp) without ray
// counting, so that the gradient pass re-traces a pixel's path with exactly the random numbers the
// path tracer drew for it. Keep it in step with the path tracer: a difference shows up as a
// spurious temporal gradient where only the camera moves (tests/svgf_history.rs checks that
// there is none). Requires the includes of the path tracer.
#ifndef LUCID_SVGF_REPLAY_GLSL
#define LUCID_SVGF_REPLAY_GLSL

vec3 svgf_replay_path(vec3 o, vec3 d, inout uint rng, uint max_depth, uint rr_depth, out vec3 first_albedo) {
    vec3 radiance = vec3(0.0);
    vec3 beta = vec3(1.0);
    float prev_pdf = 0.0;
    bool prev_delta = true;
    vec3 prev_p = o;
    first_albedo = vec3(1.0);
    for (uint depth = 0u; depth < max_depth; ++depth) {
        Hit hit;
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

#endif
