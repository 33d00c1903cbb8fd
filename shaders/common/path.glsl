// One unidirectional path (next-event estimation + BSDF sampling with the power heuristic,
// Russian roulette) as a resumable state: `path_begin` starts it at a camera ray, each
// `path_bounce` adds one vertex. A thread can therefore run one bounce at a time and start a new
// path as soon as one ends (path regeneration), and the SVGF gradient pass replays a pixel's path
// with exactly the path tracer's random numbers. Requires math, rng, scene, traverse, bsdf,
// lights and surface.
#ifndef LUCID_PATH_GLSL
#define LUCID_PATH_GLSL

struct PathState {
    vec3 origin;
    vec3 dir;
    vec3 beta;           // throughput
    vec3 radiance;       // gathered so far
    vec3 prev_p;         // the previous vertex (for the emitter's MIS pdf)
    float prev_pdf;      // solid-angle pdf of the BSDF sample that led here
    bool prev_delta;     // that sample was specular
    uint depth;          // vertices found so far
    vec3 first_albedo;   // demodulation albedo of the first hit (white for the sky and dielectrics)
    vec3 first_emission; // radiance emitted towards the camera by the first hit (or the sky)
};

PathState path_begin(vec3 origin, vec3 dir) {
    PathState st;
    st.origin = origin;
    st.dir = dir;
    st.beta = vec3(1.0);
    st.radiance = vec3(0.0);
    st.prev_p = origin;
    st.prev_pdf = 0.0;
    st.prev_delta = true;
    st.depth = 0u;
    st.first_albedo = vec3(1.0);
    st.first_emission = vec3(0.0);
    return st;
}

// Finds the next vertex, adds its emission and a light sample, and samples the BSDF for the next
// direction. Returns false once the path has ended (st.radiance is then final). Adds the rays it
// traces to `rays`. With max_depth 0 nothing is traced.
bool path_bounce(inout PathState st, inout uint rng, uint max_depth, uint rr_depth, inout uint rays) {
    if (st.depth >= max_depth) {
        return false;
    }
    uint depth = st.depth;
    st.depth += 1u;
    Hit hit;
    rays += 1u;
    if (!trace_closest(st.origin, st.dir, T_INFINITY, hit)) {
        vec3 sun = sun_radiance(st.dir);
        float w_sun = st.prev_delta ? 1.0 : power_heuristic(st.prev_pdf, sun_pdf());
        st.radiance += st.beta * (environment_radiance(st.dir) + sun * w_sun);
        if (depth == 0u) {
            st.first_emission = st.radiance;
        }
        return false;
    }
    Surface s = surface_at(hit, st.origin, st.dir);
    vec3 emitted = surface_emission(s, st.dir);
    if (max3(emitted) > 0.0) {
        float w = st.prev_delta ? 1.0 : power_heuristic(st.prev_pdf, surface_light_pdf(s, st.prev_p));
        st.radiance += st.beta * emitted * w;
    }
    if (depth == 0u) {
        st.first_emission = st.radiance;
    }
    if (depth + 1u >= max_depth) {
        return false;
    }
    BsdfParams m = material_params(s.material, s.uv);
    if (depth == 0u) {
        st.first_albedo = demodulation_albedo(m);
    }
    vec3 t;
    vec3 b;
    make_frame(s.ns, t, b);
    vec3 wo = to_local(-st.dir, t, b, s.ns);
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
                rays += 1u;
                if (!trace_occluded(origin, ls.wi, t_max)) {
                    float w = ls.delta ? 1.0 : power_heuristic(ls.pdf, bsdf_pdf);
                    st.radiance += st.beta * f * ls.radiance * (w / ls.pdf);
                }
            }
        }
    }
    BsdfSample bs;
    if (!bsdf_sample(m, wo, u_bsdf, bs)) {
        return false;
    }
    vec3 wi = to_world(bs.wi, t, b, s.ns);
    st.beta *= bs.weight;
    st.prev_pdf = bs.pdf;
    st.prev_delta = bs.delta;
    st.prev_p = s.p;
    st.origin = offset_origin(s.p, s.ng, wi);
    st.dir = wi;
    if (depth + 1u >= rr_depth) {
        float q = min(max3(st.beta), 0.95);
        if (rng_next(rng) >= q) {
            return false;
        }
        st.beta /= q;
    }
    return true;
}

// Runs a whole path from a camera ray.
PathState path_trace_all(vec3 origin, vec3 dir, inout uint rng, uint max_depth, uint rr_depth, inout uint rays) {
    PathState st = path_begin(origin, dir);
    while (path_bounce(st, rng, max_depth, rr_depth, rays)) {
    }
    return st;
}

// The radiance with the first hit's emission removed and divided by its albedo: what SVGF filters.
vec3 path_demodulated(PathState st) {
    return max(st.radiance - st.first_emission, vec3(0.0)) / max(st.first_albedo, vec3(1e-3));
}

#endif
