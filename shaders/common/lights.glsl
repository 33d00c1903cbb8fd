// Light sampling for next-event estimation and the matching pdfs for MIS: emissive triangles and
// spheres, point and spot lights (an alias table, half by power and half uniform: see
// lucid_engine::scene::LightDistribution), the sun, and an environment map (its cells by an alias
// table after the lights', lucid_engine::scene::EnvironmentDistribution); a constant or gradient
// environment is reached by BSDF sampling only. Requires scene.glsl, math.glsl, traverse.glsl.
#ifndef LUCID_LIGHTS_GLSL
#define LUCID_LIGHTS_GLSL

layout(constant_id = 104) const bool HAS_SUN = true;
layout(constant_id = 105) const bool HAS_DELTA_LIGHTS = true;
layout(constant_id = 106) const bool HAS_ENVIRONMENT = true;
layout(constant_id = 118) const bool HAS_ENVIRONMENT_MAP = true;
// Some emissive material has an emissive texture.
layout(constant_id = 113) const bool HAS_EMISSIVE_TEXTURES = true;

// Candidates resampled per next-event light sample (sample_light) when the table has more than
// one light; 1 turns resampling off.
const uint LIGHT_CANDIDATES = 4u;
// Off where the table's lights are the triangles of one flat emitter, which reach every point
// alike but for their distance (lucid_engine::scene::gpu::GpuScene::lights_form_one_flat_emitter):
// sample_light then draws one light from the table without resampling.
layout(constant_id = 121) const bool RESAMPLE_LIGHTS = true;

// LightSample::light of the sun and of the environment map.
const uint SUN_LIGHT = 0xffffffffu;
const uint ENVIRONMENT_LIGHT = 0xfffffffeu;

struct LightSample {
    vec3 wi;        // unit direction from the shading point to the light
    float dist;     // distance to the sampled point (T_INFINITY for the sun)
    vec3 radiance;  // arriving radiance (or intensity / dist^2 for delta lights)
    float pdf;      // solid-angle pdf of the light table's (or the sun's) strategy, selection
                    // included (selection only for delta lights): what MIS weighs
    float weight;   // what multiplies radiance in the estimate: 1 / pdf, or with resampling its
                    // unbiased contribution weight
    bool delta;
    uint light;     // the light-table entry, SUN_LIGHT or ENVIRONMENT_LIGHT
};

bool sun_enabled() {
    return HAS_SUN && b_scene.p.sun.radiance_enabled.w > 0.0;
}

bool environment_sampled() {
    return HAS_ENVIRONMENT_MAP && b_scene.p.environment.kind == 2u;
}

// Probability that next-event estimation samples the environment map: half when there is
// anything else to sample, else all.
float environment_selection() {
    if (!environment_sampled()) {
        return 0.0;
    }
    return b_scene.p.counts0.w > 0u || sun_enabled() ? 0.5 : 1.0;
}

// Probability of choosing the sun: half of what the map leaves when the light table has lights.
float sun_selection() {
    if (!sun_enabled()) {
        return 0.0;
    }
    float rest = 1.0 - environment_selection();
    return b_scene.p.counts0.w > 0u ? 0.5 * rest : rest;
}

// Probability of choosing the light table.
float table_selection() {
    return 1.0 - sun_selection() - environment_selection();
}

// The map's image coordinates of unit direction d (lucid_engine::scene::environment_map).
vec2 environment_uv(vec3 d) {
    float u = 0.5 + atan(d.x, -d.z) * (0.5 * INV_PI);
    return vec2(fract(u), acos(clamp(d.y, -1.0, 1.0)) * INV_PI);
}

vec3 environment_direction(vec2 uv) {
    float phi = (uv.x - 0.5) * 2.0 * PI;
    float theta = uv.y * PI;
    return vec3(sin(theta) * sin(phi), cos(theta), -sin(theta) * cos(phi));
}

vec3 environment_radiance(vec3 dir) {
    if (!HAS_ENVIRONMENT) {
        return vec3(0.0);
    }
    Environment e = b_scene.p.environment;
    if (HAS_ENVIRONMENT_MAP && e.kind == 2u) {
        return sample_texture(e.map_record, environment_uv(dir)).rgb;
    }
    if (e.kind == 0u) {
        return e.zenith.rgb;
    }
    return dir.y <= 0.0 ? e.ground.rgb : mix(e.horizon.rgb, e.zenith.rgb, sqrt(dir.y));
}

// Solid-angle density of next-event estimation sampling the environment map in direction dir
// (cell probability over the cell's solid angle at dir), its selection included; 0 without a map.
float environment_cell_pdf(uint cell, float sin_theta) {
    Environment e = b_scene.p.environment;
    if (sin_theta <= 0.0) {
        return 0.0;
    }
    float p = b_light_table.e[b_scene.p.counts0.w + cell].pdf;
    return environment_selection() * p * float(e.cells_x * e.cells_y) / (2.0 * PI * PI * sin_theta);
}

float environment_pdf(vec3 dir) {
    if (!environment_sampled()) {
        return 0.0;
    }
    Environment e = b_scene.p.environment;
    uvec2 cell = min(uvec2(environment_uv(dir) * vec2(e.cells_x, e.cells_y)), uvec2(e.cells_x, e.cells_y) - 1u);
    return environment_cell_pdf(cell.y * e.cells_x + cell.x, sqrt(max(0.0, 1.0 - dir.y * dir.y)));
}

// Samples the environment map: a cell by its alias table (u.x), a uniform point of it in image
// coordinates (u.yz).
bool sample_environment(vec3 u, out LightSample ls) {
    Environment e = b_scene.p.environment;
    uint cells = e.cells_x * e.cells_y;
    uint offset = b_scene.p.counts0.w;
    float scaled = u.x * float(cells);
    uint column = min(uint(scaled), cells - 1u);
    LightTableEntry entry = b_light_table.e[offset + column];
    uint cell = fract(scaled) < entry.threshold ? column : entry.alias - offset;
    vec2 uv = (vec2(cell % e.cells_x, cell / e.cells_x) + u.yz) / vec2(e.cells_x, e.cells_y);
    ls.wi = environment_direction(uv);
    ls.dist = T_INFINITY;
    ls.delta = false;
    ls.light = ENVIRONMENT_LIGHT;
    ls.radiance = environment_radiance(ls.wi);
    ls.pdf = environment_cell_pdf(cell, sin(uv.y * PI));
    ls.weight = ls.pdf > 0.0 ? 1.0 / ls.pdf : 0.0;
    return ls.pdf > 0.0;
}

// The sun's radiance seen along dir (0 outside its disc).
vec3 sun_radiance(vec3 dir) {
    if (!sun_enabled()) {
        return vec3(0.0);
    }
    Sun s = b_scene.p.sun;
    return dot(dir, s.direction_cos.xyz) >= s.direction_cos.w ? s.radiance_enabled.rgb : vec3(0.0);
}

float sun_pdf() {
    float cos_max = b_scene.p.sun.direction_cos.w;
    return sun_selection() / (2.0 * PI * max(1.0 - cos_max, 1e-7));
}

// The emitting side of a triangle light: its winding normal times the side packed in p1.w.
vec3 triangle_front_normal(Light light) {
    return normalize(cross(light.p1.xyz - light.p0.xyz, light.p2.xyz - light.p0.xyz)) * light.p1.w;
}

// Emitted radiance of material m at uv: its emission times its emissive texture.
vec3 material_emission(Material m, vec2 uv) {
    vec3 e = m.emission;
    if (HAS_EMISSIVE_TEXTURES && m.emissive_texture != NO_TEXTURE) {
        e *= sample_texture(m.emissive_texture, uv).rgb;
    }
    return e;
}

// Radiance a triangle light emits at the point of vertex weights (bary.x, bary.y, 1 - both) for
// its p0, p1, p2: its emission, times its emissive texture there, times how much of a cut-out
// surface is there (0 or 1 for a mask, the opacity for blending, which a ray meets with that
// probability). The light table and the MIS pdfs keep weighing the emission factor alone: the
// estimate stays unbiased, texels just get samples in proportion to area.
vec3 triangle_light_radiance(Light light, vec2 bary) {
    vec3 e = light.emission.rgb;
    if (!HAS_EMISSIVE_TEXTURES && !HAS_ALPHA_TEST) {
        return e;
    }
    Material m = b_materials.m[light.material];
    bool textured = HAS_EMISSIVE_TEXTURES && m.emissive_texture != NO_TEXTURE;
    bool cut_out = HAS_ALPHA_TEST && (m.flags & MATERIAL_CUT_OUT) != 0u;
    if (!textured && !cut_out) {
        return e;
    }
    vec2 uv;
    float vertex_alpha;
    triangle_uv_alpha(light.index, vec3(bary, 1.0 - bary.x - bary.y), uv, vertex_alpha);
    if (textured) {
        e *= sample_texture(m.emissive_texture, uv).rgb;
    }
    if (cut_out) {
        e *= surface_coverage(m, material_opacity(m, uv, vertex_alpha));
    }
    return e;
}

// An area emitter's power as the light table weighs it: on its strongest channel
// (lucid_engine::scene::selection_power).
float emitter_power(vec3 emission, float area) {
    return PI * area * max3(emission);
}

// The probability that the light table picks an emitter of `power` (the sun's share excluded):
// half in proportion to power, half uniform over the lights with power.
float light_selection(float power) {
    return power > 0.0 ? power * b_scene.p.light.z + b_scene.p.light.y : 0.0;
}

// Solid-angle pdf that NEE samples the point `p_light` on emissive triangle `tri` of `instance`
// (world vertices p0..p2) from `p`.
float triangle_light_pdf(vec3 p, vec3 p_light, vec3 front, vec3 p0, vec3 p1, vec3 p2, vec3 emission) {
    float total = b_scene.p.light.x;
    float area = 0.5 * length(cross(p1 - p0, p2 - p0));
    if (total <= 0.0 || area <= 0.0) {
        return 0.0;
    }
    vec3 d = p_light - p;
    float dist2 = dot(d, d);
    float cos_l = abs(dot(front, normalize(d)));
    float selection = light_selection(emitter_power(emission, area)) * table_selection();
    return selection * dist2 / max(cos_l * area, 1e-12);
}

float sphere_light_pdf(vec3 p, vec4 center_radius, vec3 emission) {
    float total = b_scene.p.light.x;
    float r = center_radius.w;
    float d2 = dot(center_radius.xyz - p, center_radius.xyz - p);
    if (total <= 0.0 || d2 <= r * r) {
        return 0.0;
    }
    float cos_max = sqrt(max(0.0, 1.0 - r * r / d2));
    float selection = light_selection(emitter_power(emission, 4.0 * PI * r * r)) * table_selection();
    return selection / (2.0 * PI * max(1.0 - cos_max, 1e-7));
}

uint pick_light(float u, uint count) {
    float scaled = u * float(count);
    uint i = min(uint(scaled), count - 1u);
    LightTableEntry e = b_light_table.e[i];
    return fract(scaled) < e.threshold ? i : e.alias;
}

// Samples point u on light-table entry `index`, which was picked with probability `selection`
// (the sun's share included), as seen from p. Sets everything but `weight`.
bool sample_table_light(vec3 p, uint index, float selection, vec2 u, out LightSample ls) {
    ls.delta = false;
    ls.dist = T_INFINITY;
    ls.radiance = vec3(0.0);
    ls.pdf = 0.0;
    ls.wi = vec3(0.0, 1.0, 0.0);
    ls.light = index;
    Light light = b_lights.l[index];
    if (light.kind == LIGHT_TRIANGLE) {
        float su = sqrt(u.x);
        vec2 bary = vec2(1.0 - su, u.y * su);
        vec3 q = bary.x * light.p0.xyz + bary.y * light.p1.xyz + (1.0 - bary.x - bary.y) * light.p2.xyz;
        vec3 front = triangle_front_normal(light);
        vec3 d = q - p;
        float dist2 = dot(d, d);
        ls.dist = sqrt(dist2);
        ls.wi = d / ls.dist;
        float cos_l = -dot(front, ls.wi);
        float area = light.p0.w;
        if (cos_l <= 0.0 || area <= 0.0) {
            return false;
        }
        ls.radiance = triangle_light_radiance(light, bary);
        ls.pdf = selection * dist2 / (cos_l * area);
        return true;
    }
    if (HAS_SPHERES && light.kind == LIGHT_SPHERE) {
        vec3 c = light.p0.xyz;
        float r = light.p0.w;
        vec3 to_c = c - p;
        float d2 = dot(to_c, to_c);
        if (d2 <= r * r) {
            return false;
        }
        float d = sqrt(d2);
        float cos_max = sqrt(max(0.0, 1.0 - r * r / d2));
        vec3 axis = to_c / d;
        vec3 t;
        vec3 b;
        make_frame(axis, t, b);
        vec3 local = sample_cone(u, cos_max);
        ls.wi = to_world(local, t, b, axis);
        // Distance to the first intersection with the sphere along wi.
        float proj = d * local.z;
        float h2 = max(0.0, r * r - (d2 - proj * proj));
        ls.dist = proj - sqrt(h2);
        ls.radiance = light.emission.rgb;
        ls.pdf = selection / (2.0 * PI * max(1.0 - cos_max, 1e-7));
        return true;
    }
    if (HAS_DELTA_LIGHTS) {
        vec3 d = light.p0.xyz - p;
        float dist2 = dot(d, d);
        ls.dist = sqrt(dist2);
        ls.wi = d / ls.dist;
        ls.delta = true;
        ls.pdf = selection;
        float falloff = 1.0;
        if (light.kind == LIGHT_SPOT) {
            float cos_a = dot(-ls.wi, light.p1.xyz);
            float cos_outer = light.p1.w;
            float cos_inner = light.p2.x;
            falloff = clamp((cos_a - cos_outer) / max(cos_inner - cos_outer, 1e-4), 0.0, 1.0);
            falloff *= falloff;
        }
        ls.radiance = light.emission.rgb * falloff / max(dist2, 1e-8);
        return falloff > 0.0;
    }
    return false;
}

// Offsets of the resampling candidates' random numbers: the R3 sequence (Roberts 2018), so that a
// pixel's candidates spread over the table rather than repeat.
const vec3 CANDIDATE_STEP = vec3(0.8191725134, 0.6710436067, 0.5497004779);

// Samples a light as seen from p for next-event estimation. u.x picks the environment map, the sun
// or the light table, u.yz place the point, u.w resamples. With more than one light in the table,
// LIGHT_CANDIDATES candidates are drawn from the table and one is kept in proportion to the radiance it brings to
// p unshadowed over its pdf (resampled importance sampling, Talbot et al. 2005): a light that
// does not reach p (a spot aimed elsewhere, a triangle facing away) is not kept while another
// does. `ls.weight` is then the unbiased contribution weight sum(w) / (M * target) in place of
// 1 / pdf, and `ls.pdf` stays the table's pdf, which MIS weighs on every side (the weights of
// all strategies still sum to one). Without RESAMPLE_LIGHTS one light is drawn from the table.
bool sample_light(vec3 p, vec4 u, out LightSample ls) {
    ls.delta = false;
    ls.dist = T_INFINITY;
    ls.radiance = vec3(0.0);
    ls.pdf = 0.0;
    ls.weight = 0.0;
    ls.wi = vec3(0.0, 1.0, 0.0);
    ls.light = SUN_LIGHT;
    float p_environment = environment_selection();
    if (u.x < p_environment) {
        return sample_environment(vec3(u.x / p_environment, u.yz), ls);
    }
    float p_sun = sun_selection();
    uint count = b_scene.p.counts0.w;
    if (u.x < p_environment + p_sun) {
        Sun s = b_scene.p.sun;
        vec3 t;
        vec3 b;
        make_frame(s.direction_cos.xyz, t, b);
        ls.wi = to_world(sample_cone(u.yz, s.direction_cos.w), t, b, s.direction_cos.xyz);
        ls.radiance = s.radiance_enabled.rgb;
        ls.pdf = sun_pdf();
        ls.weight = 1.0 / ls.pdf;
        return true;
    }
    if (count == 0u) {
        return false;
    }
    float table = table_selection();
    float u_pick = table < 1.0 ? (u.x - p_environment - p_sun) / table : u.x;
    if (count == 1u || !RESAMPLE_LIGHTS || LIGHT_CANDIDATES <= 1u) {
        uint index = pick_light(min(u_pick, 0.99999994), count);
        bool ok = sample_table_light(p, index, b_light_table.e[index].pdf * table, u.yz, ls);
        ls.weight = ls.pdf > 0.0 ? 1.0 / ls.pdf : 0.0;
        return ok;
    }
    float w_sum = 0.0;
    float r = u.w;
    bool found = false;
    for (uint k = 0u; k < LIGHT_CANDIDATES; ++k) {
        vec3 uk = fract(vec3(u_pick, u.yz) + float(k) * CANDIDATE_STEP);
        uint index = pick_light(min(uk.x, 0.99999994), count);
        LightSample c;
        if (!sample_table_light(p, index, b_light_table.e[index].pdf * table, uk.yz, c) || !(c.pdf > 0.0)) {
            continue;
        }
        float w = max3(c.radiance) / c.pdf;
        if (!(w > 0.0) || isinf(w)) {
            continue;
        }
        w_sum += w;
        // Streaming selection with one uniform number, rescaled after each decision.
        float keep = w / w_sum;
        if (r < keep) {
            ls = c;
            found = true;
            r /= keep;
        } else {
            r = (r - keep) / (1.0 - keep);
        }
    }
    if (!found) {
        return false;
    }
    ls.weight = w_sum / (float(LIGHT_CANDIDATES) * max3(ls.radiance));
    return true;
}

// How far the ray from `origin` along unit `dir` runs before it leaves the scene's box
// (SceneParams::bounds_min and bounds_max); 0 where it starts outside it and does not enter.
float scene_exit(vec3 origin, vec3 dir) {
    vec3 inv_dir = safe_inverse(dir);
    vec3 t0 = (b_scene.p.bounds_min.xyz - origin) * inv_dir;
    vec3 t1 = (b_scene.p.bounds_max.xyz - origin) * inv_dir;
    vec3 far = max(t0, t1);
    return max(min(min(far.x, far.y), far.z), 0.0);
}

// The shadow ray testing light sample `ls` from the surface point p (geometric normal ng): the
// segment from p lifted off its surface to 0.1% of the distance short of the light, or towards the
// sun and the environment to where it leaves the scene's box, traced from that far end (the rays
// towards one light then leave from a small region and walk its surroundings together, and an
// occluder near the light, or a roof or wall at the scene's edge, ends them at once).
void light_shadow_ray(vec3 p, vec3 ng, LightSample ls, out vec3 origin, out vec3 dir, out float t_max) {
    origin = offset_origin(p, ng, ls.wi);
    dir = ls.wi;
    t_max = ls.dist < T_INFINITY ? ls.dist * (1.0 - 1e-3) : scene_exit(origin, dir);
    reverse_segment(origin, dir, t_max);
}

#endif
