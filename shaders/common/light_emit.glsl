// Emission sampling for light subpaths (bidirectional methods) and the emission and NEE pdfs their
// MIS weights need. A light-table entry is picked as NEE picks it (the alias table NEE uses); emissive triangles and spheres emit from a uniform point with a cosine-weighted direction
// on the front side, point lights uniformly over the sphere, spot lights uniformly within the outer
// cone. The sun and the environment emit no light subpaths: paths that start on them are left to
// the camera subpath's own strategies (BSDF sampling and NEE). Requires math.glsl, scene.glsl,
// lights.glsl, surface.glsl.
#ifndef LUCID_LIGHT_EMIT_GLSL
#define LUCID_LIGHT_EMIT_GLSL

struct EmitSample {
    vec3 p;          // origin on the light
    vec3 n;          // emitting normal (zero for delta lights)
    vec3 dir;        // unit emission direction
    vec3 weight;     // emission * cos / pdf: the throughput of the subpath's first vertex
    float pdf_dir;   // pdf of (point, direction) in area x solid angle, for MIS
    float cos_light; // cosine between n and dir (1 for delta lights)
    uint index;      // light-table entry
    uint kind;       // LIGHT_*
    bool delta;
};

// Probability (for MIS) that light sampling picks an area emitter with `emission` and `area`,
// among the light table alone (the sun excluded).
float emitter_selection(vec3 emission, float area) {
    return light_selection(emitter_power(emission, area));
}

float sphere_area(float r) {
    return 4.0 * PI * r * r;
}

// Solid-angle pdf of a direction emitted by a delta light from the table entry `index`.
float delta_emit_pdf(uint index, Light light) {
    float selection = b_light_table.e[index].pdf;
    if (light.kind == LIGHT_SPOT) {
        return selection / (2.0 * PI * max(1.0 - light.p1.w, 1e-7));
    }
    return selection / (4.0 * PI);
}

// Starts a light subpath: u.x picks the light, u.yz the point, v the direction.
bool sample_emission(vec3 u, vec2 v, out EmitSample e) {
    e.n = vec3(0.0);
    e.delta = false;
    e.cos_light = 1.0;
    uint count = b_scene.p.counts0.w;
    if (count == 0u) {
        return false;
    }
    e.index = pick_light(min(u.x, 0.99999994), count);
    Light light = b_lights.l[e.index];
    e.kind = light.kind;
    float selection = b_light_table.e[e.index].pdf;
    if (selection <= 0.0) {
        return false;
    }
    if (light.kind == LIGHT_TRIANGLE || (HAS_SPHERES && light.kind == LIGHT_SPHERE)) {
        float area;
        vec3 emission = light.emission.rgb;
        if (light.kind == LIGHT_TRIANGLE) {
            float su = sqrt(u.y);
            vec2 bary = vec2(1.0 - su, u.z * su);
            e.p = bary.x * light.p0.xyz + bary.y * light.p1.xyz + (1.0 - bary.x - bary.y) * light.p2.xyz;
            e.n = triangle_front_normal(light);
            area = light.p0.w;
            emission = triangle_light_radiance(light, bary);
        } else {
            float z = 1.0 - 2.0 * u.y;
            float r = sqrt(max(0.0, 1.0 - z * z));
            float phi = 2.0 * PI * u.z;
            e.n = vec3(r * cos(phi), r * sin(phi), z);
            e.p = light.p0.xyz + light.p0.w * e.n;
            area = sphere_area(light.p0.w);
        }
        vec3 t;
        vec3 b;
        make_frame(e.n, t, b);
        vec3 local = sample_cosine_hemisphere(v);
        e.dir = to_world(local, t, b, e.n);
        e.cos_light = local.z;
        if (area <= 0.0 || e.cos_light <= 0.0) {
            return false;
        }
        e.weight = emission * (PI * area / selection);
        e.pdf_dir = emitter_selection(light.emission.rgb, area) / area * e.cos_light * INV_PI;
        return e.pdf_dir > 0.0;
    }
    if (!HAS_DELTA_LIGHTS) {
        return false;
    }
    e.delta = true;
    e.p = light.p0.xyz;
    e.pdf_dir = delta_emit_pdf(e.index, light);
    if (light.kind == LIGHT_SPOT) {
        vec3 axis = light.p1.xyz;
        vec3 t;
        vec3 b;
        make_frame(axis, t, b);
        e.dir = to_world(sample_cone(v, light.p1.w), t, b, axis);
        float cos_a = dot(e.dir, axis);
        float falloff = clamp((cos_a - light.p1.w) / max(light.p2.x - light.p1.w, 1e-4), 0.0, 1.0);
        e.weight = light.emission.rgb * (falloff * falloff / e.pdf_dir);
        return falloff > 0.0;
    }
    float z = 1.0 - 2.0 * v.x;
    float r = sqrt(max(0.0, 1.0 - z * z));
    e.dir = vec3(r * cos(2.0 * PI * v.y), r * sin(2.0 * PI * v.y), z);
    e.weight = light.emission.rgb / e.pdf_dir;
    return true;
}

// Area-measure pdf (discrete probability for delta lights) that NEE from `receiver` picks the
// origin of `e`, including the light table's share of NEE.
float emission_nee_pdf(EmitSample e, vec3 receiver) {
    Light light = b_lights.l[e.index];
    float table = table_selection();
    if (e.kind == LIGHT_TRIANGLE) {
        return table * emitter_selection(light.emission.rgb, light.p0.w) / light.p0.w;
    }
    if (HAS_SPHERES && e.kind == LIGHT_SPHERE) {
        vec3 d = receiver - e.p;
        float dist2 = dot(d, d);
        float cos_l = abs(dot(e.n, d)) * inversesqrt(dist2);
        return sphere_light_pdf(receiver, light.p0, light.emission.rgb) * cos_l / dist2;
    }
    return HAS_DELTA_LIGHTS ? table * b_light_table.e[e.index].pdf : 0.0;
}

// Emission pdf (area x solid angle, for MIS) of an emitting surface point `s` towards a direction
// with cosine `cos_out` to its front normal.
float surface_emission_pdf(Surface s, float cos_out) {
    vec3 emission = b_materials.m[s.material].emission;
    float area = s.sphere ? sphere_area(s.center_radius.w) : 0.5 * length(cross(s.p1 - s.p0, s.p2 - s.p0));
    if (area <= 0.0) {
        return 0.0;
    }
    return emitter_selection(emission, area) / area * cos_out * INV_PI;
}

// For a light sample `ls` that sample_light(p, u, ls) drew, the emission pdf (area x solid angle)
// of the same segment traced from the light towards p, and the cosine at the light (1 for delta
// lights). Returns false when the sample is the sun's.
bool light_sample_emission(vec3 p, LightSample ls, out float pdf_dir, out float cos_light) {
    pdf_dir = 0.0;
    cos_light = 1.0;
    if (ls.light == SUN_LIGHT || ls.light == ENVIRONMENT_LIGHT) {
        return false;
    }
    uint index = ls.light;
    Light light = b_lights.l[index];
    if (light.kind == LIGHT_TRIANGLE) {
        vec3 front = triangle_front_normal(light);
        cos_light = max(0.0, -dot(front, ls.wi));
        pdf_dir = emitter_selection(light.emission.rgb, light.p0.w) / light.p0.w * cos_light * INV_PI;
    } else if (HAS_SPHERES && light.kind == LIGHT_SPHERE) {
        vec3 n = normalize(p + ls.wi * ls.dist - light.p0.xyz);
        float area = sphere_area(light.p0.w);
        cos_light = max(0.0, -dot(n, ls.wi));
        pdf_dir = emitter_selection(light.emission.rgb, area) / area * cos_light * INV_PI;
    } else if (HAS_DELTA_LIGHTS) {
        pdf_dir = delta_emit_pdf(index, light);
    }
    return true;
}

#endif
