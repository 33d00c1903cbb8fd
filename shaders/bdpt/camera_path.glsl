// BDPT's camera subpaths (camera.comp; camera_long.comp goes on with the ones it parked): emission
// hits (s = 0), NEE (s = 1) and connections to the light vertex cache (s > 1) at every vertex,
// each with its recursive MIS weight (bdpt.glsl), NEE's shadow ray walked with the first
// connection's where PAIRED_SHADOW_RAYS (bdpt.glsl). Where the including shader defines CAMERA_PARK
// (bdpt/long_paths.glsl), a subpath still alive after PARK_DEPTH segments is handed to it and ends
// here. Requires bdpt.glsl, light_emit.glsl, camera.glsl and surface.glsl.
#ifndef LUCID_CAMERA_PATH_GLSL
#define LUCID_CAMERA_PATH_GLSL

layout(set = 0, binding = 21, std430) readonly buffer Lvc { LightVertex v[]; } b_lvc;
layout(set = 0, binding = 22, std430) readonly buffer LvcLengths { uint n[]; } b_lvc_lengths;
layout(set = 0, binding = 23, std430) readonly buffer LvcColors { uvec2 c[]; } b_lvc_colors;

// A camera subpath vertex: position, normals, frame, BSDF, direction towards the previous vertex
// (local), throughput and MIS quantities.
struct CameraVertex {
    Surface s;
    BsdfParams m;
    vec3 t;
    vec3 b;
    vec3 wo;
    vec3 beta;
    float dvcm;
    float dvc;
};

// A shadow ray still to be traced and what its strategy brings where it is not occluded (t_max 0:
// no ray, nothing brought).
struct ShadowRay {
    vec3 origin;
    float t_max;
    vec3 dir;
    vec3 value;
};

const ShadowRay NO_SHADOW_RAY = ShadowRay(vec3(0.0), 0.0, vec3(0.0, 0.0, 1.0), vec3(0.0));

// Next-event estimation (s = 1) from camera vertex c: its shadow ray.
ShadowRay connect_to_light(CameraVertex c, inout uint rng) {
    vec4 u = vec4(rng_next(rng), rng_next2(rng), rng_side(rng));
    LightSample ls;
    if (!sample_light(c.s.p, u, ls) || ls.pdf <= 0.0) {
        return NO_SHADOW_RAY;
    }
    vec3 wi = to_local(ls.wi, c.t, c.b, c.s.ns);
    float bsdf_pdf;
    float rev_pdf;
    vec3 f = bsdf_eval_both(c.m, c.wo, wi, bsdf_pdf, rev_pdf);
    if (max3(f) <= 0.0) {
        return NO_SHADOW_RAY;
    }
    float w;
    float emit_pdf;
    float cos_light;
    if (light_sample_emission(c.s.p, ls, emit_pdf, cos_light)) {
        float cos_here = abs(dot(c.s.ng, ls.wi));
        // Area pdfs at the light: NEE's (a probability for delta lights) and, at this vertex, the
        // emitted subpath's.
        float nee_area = ls.delta ? ls.pdf : ls.pdf * cos_light / (ls.dist * ls.dist);
        float emit_area = emit_pdf * cos_here / (ls.dist * ls.dist);
        float w_light = ls.delta ? 0.0 : mis(bsdf_pdf / ls.pdf);
        float w_camera = mis(emit_area / nee_area) * (c.dvcm + c.dvc * mis(rev_pdf));
        w = 1.0 / (1.0 + w_light + w_camera);
    } else {
        w = mis_pair(ls.pdf, bsdf_pdf);
    }
    if (w <= 0.0) {
        return NO_SHADOW_RAY;
    }
    ShadowRay r;
    light_shadow_ray(c.s.p, c.s.ng, ls, r.origin, r.dir, r.t_max);
    r.value = f * ls.radiance * (w * ls.weight);
    return r;
}

// Connection (s > 1, t > 1) of camera vertex c to the cached light vertex v, under connection
// roulette below `threshold` (bdpt.glsl's CONNECTION_ROULETTE; 0: none) with the uniform number
// u_roulette: its shadow ray.
ShadowRay connect_vertices(CameraVertex c, LightVertex v, uint slot, float threshold, float u_roulette) {
    vec3 to_light = v.p - c.s.p;
    float dist2 = dot(to_light, to_light);
    if (dist2 < 1e-12) {
        return NO_SHADOW_RAY;
    }
    float dist = sqrt(dist2);
    vec3 dir = to_light / dist;
    vec3 wi = to_local(dir, c.t, c.b, c.s.ns);
    float camera_pdf;
    float camera_rev_pdf;
    vec3 fc = bsdf_eval_both(c.m, c.wo, wi, camera_pdf, camera_rev_pdf);
    if (max3(fc) <= 0.0) {
        return NO_SHADOW_RAY;
    }
    vec3 ns = decode_normal(v.ns);
    vec3 ng = decode_normal(v.ng);
    vec3 t;
    vec3 b;
    make_frame(ns, t, b);
    vec2 uv = unpackHalf2x16(v.uv);
    BsdfParams ml = LVC_COLORS ? material_params_with_base(v.material, uv, decode_lvc_color(b_lvc_colors.c[slot]))
                               : material_params(v.material, uv, vec3(1.0));
    vec3 to_camera = to_local(-dir, t, b, ns);
    vec3 wl = to_local(v.wi, t, b, ns);
    float light_rev_pdf;
    float light_pdf;
    vec3 fl = bsdf_eval_both(ml, to_camera, wl, light_rev_pdf, light_pdf);
    float cos_light_in = abs(dot(ng, v.wi));
    if (max3(fl) <= 0.0 || cos_light_in < 1e-6) {
        return NO_SHADOW_RAY;
    }
    float cos_light = abs(dot(ng, dir));
    float cos_camera = abs(dot(c.s.ng, dir));
    float w_light = mis(camera_pdf * cos_light / dist2) * (v.dvcm + v.dvc * mis(light_rev_pdf));
    float w_camera = mis(light_pdf * cos_camera / dist2) * (c.dvcm + c.dvc * mis(camera_rev_pdf));
    // The light side carries the adjoint BSDF's shading-normal correction.
    vec3 value = fc * fl * v.throughput * (cos_light / (cos_light_in * dist2 * (1.0 + w_light + w_camera)));
    // What it adds to the sample: traced with probability share / threshold below the threshold.
    float share = max3(c.beta * value);
    if (share <= 0.0 || u_roulette * threshold >= share) {
        return NO_SHADOW_RAY;
    }
    if (share < threshold) {
        value *= threshold / share;
    }
    // Traced from the light vertex's end: an occluder near the light, where light subpaths start,
    // ends the walk at once.
    ShadowRay r;
    r.origin = offset_origin(c.s.p, c.s.ng, dir);
    r.dir = dir;
    r.t_max = dist * (1.0 - 1e-3);
    reverse_segment(r.origin, r.dir, r.t_max);
    r.value = value;
    return r;
}

// What the shadow rays a and b bring where they are not occluded: walked together
// (trace_occluded_pair) with PAIRED_SHADOW_RAYS, else b alone (a is then no ray: NEE's shadow ray
// was walked at once).
void trace_shadow_pair(ShadowRay a, ShadowRay b, out vec3 from_a, out vec3 from_b) {
    bvec2 occluded = PAIRED_SHADOW_RAYS
        ? counted_occluded_pair(a.origin, a.dir, a.t_max, b.origin, b.dir, b.t_max)
        : bvec2(false, b.t_max > 0.0 && counted_occluded(b.origin, b.dir, b.t_max));
    from_a = occluded.x ? vec3(0.0) : a.value;
    from_b = occluded.y ? vec3(0.0) : b.value;
}

// Connections from camera vertex c (at `segments` from the camera) to cached light vertices: each
// of the CONNECTIONS draws picks a light subpath uniformly, then one of its n stored vertices
// uniformly, and is weighted n / draws (its probability is 1 / (subpaths * n), and the cache's
// connections estimate the sum over all light vertices divided by the subpaths). Connection
// roulette below `threshold` takes its uniform number from the vertex pick's fraction, which is
// independent of the vertex picked, so that it draws no number of its own. NEE's shadow ray `nee`
// is walked with the first connection's, and what it brings goes to from_nee.
vec3 connect_to_cache(CameraVertex c, ShadowRay nee, uint segments, uint max_depth, float threshold, inout uint rng,
                      out vec3 from_nee) {
    from_nee = vec3(0.0);
    vec3 sum = vec3(0.0);
    for (uint k = 0u; k < CONNECTIONS; ++k) {
        ShadowRay r = NO_SHADOW_RAY;
        if (pc.light_paths > 0u) {
            uint path = min(uint(rng_next(rng) * float(pc.light_paths)), pc.light_paths - 1u);
            float u_vertex = rng_next(rng);
            uint n = b_lvc_lengths.n[path];
            if (n > 0u) {
                float pick = u_vertex * float(n);
                uint slot = min(uint(pick), n - 1u) * pc.light_paths + path;
                LightVertex v = b_lvc.v[slot];
                if (v.segments + segments + 1u <= max_depth) {
                    r = connect_vertices(c, v, slot, threshold, fract(pick));
                    r.value *= float(n);
                }
            }
        }
        vec3 from_first;
        vec3 from_cache;
        trace_shadow_pair(k == 0u ? nee : NO_SHADOW_RAY, r, from_first, from_cache);
        from_nee += from_first;
        sum += from_cache;
    }
    return sum / float(CONNECTIONS);
}

// The emission hit at s seen along d from prev_p, weighted against NEE and the connections.
vec3 emission_hit(Surface s, vec3 d, vec3 prev_p, uint depth, float dvcm, float dvc, float cos_in, float dist2) {
    vec3 emitted = surface_emission(s, d);
    if (max3(emitted) <= 0.0 || depth == 0u) {
        return emitted;
    }
    float nee_area = surface_light_pdf(s, prev_p) * cos_in / dist2;
    float w_camera = mis(nee_area) * dvcm + mis(surface_emission_pdf(s, cos_in)) * dvc;
    return emitted / (1.0 + w_camera);
}

// The radiance the camera subpath brings from its segment `first_depth` on, whose next ray is
// (o, d) and whose throughput and MIS state are beta, dvcm, dvc, prev_pdf, prev_delta and prev_p
// (the camera ray's at segment 0, camera_subpath); its first hit's albedo and emission go to
// first_albedo and first_emission (left at 1 and 0 from a later segment).
vec3 trace_camera_from(uint first_depth, vec3 o, vec3 d, vec3 beta, float dvcm, float dvc, float prev_pdf,
                       bool prev_delta, vec3 prev_p, inout uint rng, uint max_depth, uint rr_depth,
                       out vec3 first_albedo, out vec3 first_emission) {
    Camera cam = b_frame.f.camera;
    uvec2 size = uvec2(b_frame.f.width, b_frame.f.height);
    vec3 radiance = vec3(0.0);
    CameraVertex c;
    c.beta = beta;
    c.dvcm = dvcm;
    c.dvc = dvc;
    first_albedo = vec3(1.0);
    first_emission = vec3(0.0);
    for (uint depth = first_depth; depth < max_depth; ++depth) {
        Hit hit;
        if (!counted_closest(o, d, hit)) {
            float w_sun = prev_delta ? 1.0 : mis_pair(prev_pdf, sun_pdf());
            float w_env = prev_delta || !environment_sampled() ? 1.0 : mis_pair(prev_pdf, environment_pdf(d));
            radiance += c.beta * (environment_radiance(d) * w_env + sun_radiance(d) * w_sun);
            if (depth == 0u) {
                first_emission = radiance;
            }
            break;
        }
        c.s = surface_at(hit, o, d);
        vec3 seg = c.s.p - prev_p;
        float dist2 = dot(seg, seg);
        float cos_in = abs(dot(c.s.ng, d));
        if (cos_in < 1e-6) {
            break;
        }
        c.dvcm *= mis(dist2) / mis(cos_in);
        c.dvc /= mis(cos_in);
        radiance += c.beta * emission_hit(c.s, d, prev_p, depth, c.dvcm, c.dvc, cos_in, dist2);
        if (depth == 0u) {
            first_emission = radiance;
        }
        if (depth + 1u >= max_depth) {
            break;
        }
        // Textures at the first hit are filtered for the pixel's ray cone; light subpaths and later
        // hits read level 0.
        float footprint = depth == 0u ? cone_lod(c.s, d, sqrt(dist2) * pixel_spread(cam, float(size.y))) : NO_FOOTPRINT;
        c.m = material_params_lod(c.s.material, c.s.uv, c.s.color, footprint);
        if (depth == 0u) {
            first_albedo = demodulation_albedo(c.m);
        }
        make_frame(c.s.ns, c.t, c.b);
        c.wo = to_local(-d, c.t, c.b, c.s.ns);
        if (!bsdf_is_delta(c.m)) {
            ShadowRay nee = connect_to_light(c, rng);
            if (!PAIRED_SHADOW_RAYS) {
                if (nee.t_max > 0.0 && !counted_occluded(nee.origin, nee.dir, nee.t_max)) {
                    radiance += c.beta * nee.value;
                }
                nee = NO_SHADOW_RAY;
            }
            // Connection roulette before Russian roulette's start only: a parked subpath's record
            // holds nothing of what it gathered, so its continuation could not set the threshold.
            // Where subpaths are parked (at rr_depth: Renderer::park_depth), that is the whole
            // first kernel and none of the continuation, which the compiler then knows. Where NEE's
            // shadow ray waits to be walked with the connection's, its share is left out: counted
            // as if unoccluded it rouletted connections its occluded rays needed (6% more error on
            // `classroom` at equal samples, bench/README.md).
            bool roulette = first_depth == 0u && (PARK_DEPTH != 0u || depth < rr_depth);
            float threshold = roulette ? CONNECTION_ROULETTE * max3(radiance) : 0.0;
            vec3 from_nee;
            vec3 from_cache = connect_to_cache(c, nee, depth + 1u, max_depth, threshold, rng, from_nee);
            radiance += c.beta * from_nee;
            radiance += c.beta * from_cache;
        }
        vec3 u_bsdf = vec3(rng_next2(rng), rng_next(rng));
        BsdfSample bs;
        if (!bsdf_sample(c.m, c.wo, u_bsdf, bs)) {
            break;
        }
        vec3 wi = to_world(bs.wi, c.t, c.b, c.s.ns);
        float cos_out = abs(dot(c.s.ng, wi));
        c.beta *= bs.weight;
        if (bs.delta) {
            c.dvcm = 0.0;
            c.dvc *= mis(cos_out);
        } else {
            c.dvc = mis(cos_out / bs.pdf) * (c.dvc * mis(bs.rev_pdf) + c.dvcm);
            c.dvcm = mis(1.0 / bs.pdf);
        }
        prev_pdf = bs.pdf;
        prev_delta = bs.delta;
        prev_p = c.s.p;
        o = offset_origin(c.s.p, c.s.ng, wi);
        d = wi;
        if (depth + 1u >= rr_depth) {
            float q = min(max3(c.beta), 0.95);
            if (rng_next(rng) >= q) {
                break;
            }
            c.beta /= q;
        }
#ifdef CAMERA_PARK
        if (depth + 1u == PARK_DEPTH) {
            CAMERA_PARK(o, d, c.beta, c.dvcm, c.dvc, prev_pdf, prev_delta, prev_p, rng);
            break;
        }
#endif
    }
    return radiance;
}

// The radiance of the camera subpath starting with the camera ray (o, d); see trace_camera_from.
vec3 trace_camera(vec3 o, vec3 d, inout uint rng, uint max_depth, uint rr_depth, out vec3 first_albedo,
                  out vec3 first_emission) {
    Camera cam = b_frame.f.camera;
    float aspect = float(b_frame.f.width) / float(b_frame.f.height);
    // Light tracing's share: its sample count and the camera's film density (zero with a lens,
    // which light tracing does not handle).
    float cos_camera = dot(d, cam.forward.xyz);
    float light_tracing = cam.position_aperture.w > 0.0 ? 0.0 : pc.light_ratio * film_area(cam, aspect);
    float dvcm = mis(light_tracing * cos_camera * cos_camera * cos_camera);
    return trace_camera_from(0u, o, d, vec3(1.0), dvcm, 0.0, 0.0, true, o, rng, max_depth, rr_depth, first_albedo,
                             first_emission);
}

#endif
