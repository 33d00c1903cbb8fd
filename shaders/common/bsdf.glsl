// BSDFs in the local shading frame (normal = +z): Lambertian diffuse, GGX conductor (smooth or
// rough), dielectric (smooth or rough, Walter et al. 2007) and glTF's metallic-roughness model.
// Diffuse, conductors and metallic-roughness are two-sided.
// Returned values include the cosine of the incident direction. Specialization constants drop the
// code of materials a scene lacks. Requires math.glsl.
#ifndef LUCID_BSDF_GLSL
#define LUCID_BSDF_GLSL

#include "common/material_kinds.glsl"

layout(constant_id = 101) const bool HAS_CONDUCTOR = true;
layout(constant_id = 102) const bool HAS_DIELECTRIC = true;
layout(constant_id = 103) const bool HAS_DIELECTRIC_ROUGH = true;
layout(constant_id = 117) const bool HAS_METAL_ROUGH = true;

struct BsdfParams {
    uint kind;        // MATERIAL_*
    vec3 color;       // albedo, metal F0 or transmission tint
    float alpha;      // GGX alpha
    float metallic;   // metallic-roughness: the conductor's share
    vec3 specular_f0; // metallic-roughness: the specular layer's reflectance at normal incidence
    float specular_weight; // metallic-roughness: the specular layer's strength
    float ior;        // dielectric index of refraction (outside is 1)
    bool smooth_lobe; // delta reflection / refraction
    float occlusion;  // the occlusion texture's factor on the denoisers' albedo (1: none)
};

struct BsdfSample {
    vec3 wi;
    vec3 weight; // f * |cos| / pdf
    float pdf;   // solid-angle pdf (0 for delta lobes)
    float rev_pdf; // the pdf of sampling wo from wi, as bidirectional MIS weighs it (0 for delta lobes)
    bool delta;
};

float ggx_d(vec3 h, float alpha) {
    if (h.z <= 0.0) {
        return 0.0;
    }
    float a2 = alpha * alpha;
    float c2 = h.z * h.z;
    float d = c2 * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

float ggx_lambda(vec3 w, float alpha) {
    float c2 = w.z * w.z;
    float t2 = max(0.0, 1.0 - c2) / max(c2, 1e-12);
    return 0.5 * (sqrt(1.0 + alpha * alpha * t2) - 1.0);
}

// sqrt(alpha^2 + (1 - alpha^2) cos^2) for a direction of cosine `cos_theta` (> 0): |cos| (1 + 2
// Lambda), the root Smith's masking term shares with the rough conductor's forms below, which
// need no division by the cosine (G1 = 2 cos / (cos + root); the height-correlated G2 =
// 2 cos_o cos_i / (root_o cos_i + root_i cos_o); the visible normals' reflection pdf =
// D / (2 (cos_o + root_o))).
float ggx_smith_root(float cos_theta, float alpha) {
    float a2 = alpha * alpha;
    return sqrt(a2 + (1.0 - a2) * cos_theta * cos_theta);
}

float ggx_g1(vec3 w, float alpha) {
    return 1.0 / (1.0 + ggx_lambda(w, alpha));
}

float ggx_g2(vec3 wo, vec3 wi, float alpha) {
    return 1.0 / (1.0 + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
}

// Visible-normal sampling for wo in the upper hemisphere, by spherical caps (Dupuy and Benyoub
// 2023): in the configuration where the roughness is 1, the visible normals of wo are the
// directions from -wo to a uniform point of the unit sphere's cap above the plane z = -wo.z, so the
// sample needs no frame around wo (Heitz 2018's method, which this replaced, samples the same
// distribution with more arithmetic).
vec3 ggx_sample_visible(vec3 wo, float alpha, vec2 u) {
    vec3 v = normalize(vec3(alpha * wo.xy, wo.z));
    float phi = 2.0 * PI * u.x;
    float z = (1.0 - u.y) * (1.0 + v.z) - v.z;
    float sin_theta = sqrt(clamp(1.0 - z * z, 0.0, 1.0));
    vec3 h = vec3(sin_theta * cos(phi), sin_theta * sin(phi), z) + v;
    return normalize(vec3(alpha * h.xy, max(1e-6, h.z)));
}

// pdf of the visible normal h for wo (upper hemisphere).
float ggx_visible_pdf(vec3 wo, vec3 h, float alpha) {
    return ggx_g1(wo, alpha) * max(0.0, dot(wo, h)) * ggx_d(h, alpha) / max(wo.z, 1e-8);
}

// Solid-angle pdf of the reflection about the visible normal h sampled for wo (upper hemisphere).
float ggx_reflection_pdf(vec3 wo, vec3 h, float alpha) {
    return ggx_visible_pdf(wo, h, alpha) / (4.0 * max(dot(wo, h), 1e-8));
}

vec3 fresnel_schlick(vec3 f0, float cos_theta) {
    float m = clamp(1.0 - cos_theta, 0.0, 1.0);
    float m5 = m * m * m * m * m;
    return f0 + (1.0 - f0) * m5;
}

// Unpolarised Fresnel reflectance for a dielectric; eta = n_transmitted / n_incident,
// cos_i > 0 on the incident side. cos_t returns the transmitted cosine (0 on total reflection).
float fresnel_dielectric(float cos_i, float eta, out float cos_t) {
    float sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0) {
        cos_t = 0.0;
        return 1.0;
    }
    cos_t = sqrt(1.0 - sin2_t);
    float rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    float rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

// ---- diffuse ----

vec3 diffuse_eval(BsdfParams m, vec3 wo, vec3 wi, out float pdf) {
    pdf = 0.0;
    if (wo.z * wi.z <= 0.0) {
        return vec3(0.0);
    }
    pdf = abs(wi.z) * INV_PI;
    return m.color * INV_PI * abs(wi.z);
}

// diffuse_eval, and in rev_pdf the pdf of sampling wo from wi.
vec3 diffuse_eval_both(BsdfParams m, vec3 wo, vec3 wi, out float pdf, out float rev_pdf) {
    rev_pdf = wo.z * wi.z <= 0.0 ? 0.0 : abs(wo.z) * INV_PI;
    return diffuse_eval(m, wo, wi, pdf);
}

bool diffuse_sample(BsdfParams m, vec3 wo, vec2 u, out BsdfSample s) {
    vec3 wi = sample_cosine_hemisphere(u);
    s.wi = wo.z < 0.0 ? -wi : wi;
    s.pdf = wi.z * INV_PI;
    s.rev_pdf = abs(wo.z) * INV_PI;
    s.weight = m.color;
    s.delta = false;
    return s.pdf > 0.0;
}

// ---- conductor ----

// The rough conductor: value and pdf for wo -> wi, and in rev_pdf the pdf of sampling wo from wi.
vec3 conductor_eval_both(BsdfParams m, vec3 wo, vec3 wi, out float pdf, out float rev_pdf) {
    pdf = 0.0;
    rev_pdf = 0.0;
    if (m.smooth_lobe || wo.z * wi.z <= 0.0) {
        return vec3(0.0);
    }
    float flip = wo.z < 0.0 ? -1.0 : 1.0;
    wo.z *= flip;
    wi.z *= flip;
    vec3 h = normalize(wo + wi);
    float d = 0.5 * ggx_d(h, m.alpha);
    float root_o = ggx_smith_root(wo.z, m.alpha);
    float root_i = ggx_smith_root(wi.z, m.alpha);
    pdf = d / (wo.z + root_o);
    rev_pdf = d / (wi.z + root_i);
    return fresnel_schlick(m.color, dot(wi, h)) * (d * wi.z / (root_o * wi.z + root_i * wo.z));
}

bool conductor_sample(BsdfParams m, vec3 wo, vec2 u, out BsdfSample s) {
    float flip = wo.z < 0.0 ? -1.0 : 1.0;
    wo.z *= flip;
    if (m.smooth_lobe) {
        s.wi = vec3(-wo.x, -wo.y, wo.z * flip);
        s.weight = fresnel_schlick(m.color, wo.z);
        s.pdf = 0.0;
        s.rev_pdf = 0.0;
        s.delta = true;
        return true;
    }
    vec3 h = ggx_sample_visible(wo, m.alpha, u);
    vec3 wi = reflect(-wo, h);
    s.delta = false;
    if (wi.z <= 0.0) {
        return false;
    }
    float root_o = ggx_smith_root(wo.z, m.alpha);
    float root_i = ggx_smith_root(wi.z, m.alpha);
    float d = 0.5 * ggx_d(h, m.alpha);
    s.pdf = d / (wo.z + root_o);
    s.rev_pdf = d / (wi.z + root_i);
    s.weight = fresnel_schlick(m.color, dot(wi, h)) * (wi.z * (wo.z + root_o) / (root_o * wi.z + root_i * wo.z));
    s.wi = vec3(wi.xy, wi.z * flip);
    return s.pdf > 0.0;
}

// ---- dielectric ----

// Generalised half vector of a refraction, facing +z.
vec3 refraction_half(vec3 wo, vec3 wi, float eta_o, float eta_i) {
    vec3 h = -(eta_o * wo + eta_i * wi);
    return normalize(h.z < 0.0 ? -h : h);
}

vec3 dielectric_eval(BsdfParams m, vec3 wo, vec3 wi, out float pdf) {
    pdf = 0.0;
    if (m.smooth_lobe || wo.z == 0.0 || wi.z == 0.0) {
        return vec3(0.0);
    }
    bool entering = wo.z > 0.0;
    float eta = entering ? m.ior : 1.0 / m.ior; // n on the wi side of refraction / n on wo side
    // Work with wo in the upper hemisphere.
    float flip = entering ? 1.0 : -1.0;
    vec3 o = vec3(wo.xy, wo.z * flip);
    vec3 i = vec3(wi.xy, wi.z * flip);
    bool reflection = i.z > 0.0;
    vec3 h = reflection ? normalize(o + i) : refraction_half(o, i, 1.0, eta);
    if (dot(o, h) <= 0.0 || (reflection ? dot(i, h) <= 0.0 : dot(i, h) >= 0.0)) {
        return vec3(0.0);
    }
    float cos_t;
    float f = fresnel_dielectric(dot(o, h), eta, cos_t);
    float d = ggx_d(h, m.alpha);
    float g = ggx_g2(o, i, m.alpha);
    float vis = ggx_visible_pdf(o, h, m.alpha);
    if (reflection) {
        pdf = f * vis / (4.0 * dot(o, h));
        return vec3(f * d * g / (4.0 * o.z));
    }
    float denom = dot(o, h) + eta * dot(i, h);
    float jacobian = eta * eta * abs(dot(i, h)) / (denom * denom);
    pdf = (1.0 - f) * vis * jacobian;
    float value = (1.0 - f) * d * g * abs(dot(i, h)) * abs(dot(o, h)) * eta * eta / (o.z * denom * denom);
    // Radiance is scaled by 1 / eta^2 when it crosses into the other medium.
    return m.color * value / (eta * eta);
}

bool dielectric_sample(BsdfParams m, vec3 wo, vec3 u, out BsdfSample s) {
    bool entering = wo.z > 0.0;
    float eta = entering ? m.ior : 1.0 / m.ior;
    float flip = entering ? 1.0 : -1.0;
    vec3 o = vec3(wo.xy, wo.z * flip);
    vec3 h = m.smooth_lobe ? vec3(0.0, 0.0, 1.0) : ggx_sample_visible(o, m.alpha, u.xy);
    float cos_o = dot(o, h);
    if (cos_o <= 0.0) {
        return false;
    }
    float cos_t;
    float f = fresnel_dielectric(cos_o, eta, cos_t);
    vec3 i;
    bool reflection = u.z < f;
    if (reflection) {
        i = reflect(-o, h);
    } else {
        i = (-o / eta) + (cos_o / eta - cos_t) * h;
        i = normalize(i);
    }
    if (reflection ? i.z <= 0.0 : i.z >= 0.0) {
        return false;
    }
    s.wi = vec3(i.xy, i.z * flip);
    s.delta = m.smooth_lobe;
    vec3 tint = reflection ? vec3(1.0) : m.color / (eta * eta);
    if (m.smooth_lobe) {
        s.pdf = 0.0;
        s.weight = tint;
        return true;
    }
    // Microfacet: weight = G2 / G1(o) for the chosen lobe (Fresnel cancels its selection pdf).
    s.weight = tint * ggx_g2(o, i, m.alpha) / ggx_g1(o, m.alpha);
    float vis = ggx_visible_pdf(o, h, m.alpha);
    if (reflection) {
        s.pdf = f * vis / (4.0 * cos_o);
    } else {
        float denom = cos_o + eta * dot(i, h);
        s.pdf = (1.0 - f) * vis * eta * eta * abs(dot(i, h)) / (denom * denom);
    }
    return s.pdf > 0.0;
}

// ---- glTF metallic-roughness ----
// glTF 2.0's BRDF (its specification's appendix B, with KHR_materials_ior and
// KHR_materials_specular): mix(dielectric, metal, metallic). The dielectric is a GGX specular layer
// of reflectance F = weight * (F0 + (1 - F0) (1 - cos)^5) (Schlick; F0 from the IOR, 0.04 by
// default, times the specular colour) over Lambertian diffuse of albedo `color` weighted by
// 1 - max(F); the metal is GGX with Schlick's Fresnel of F0 = `color`. Fresnel is taken at the
// half vector, so the BRDF is reciprocal. Sampled by picking a lobe (specular with the probability
// of its estimated share of the reflected light) and weighted by the mixture's pdf.

float schlick_weight(float cos_theta) {
    float m = clamp(1.0 - cos_theta, 0.0, 1.0);
    return m * m * m * m * m;
}

// The dielectric layer's reflectance at the cosine's Schlick weight w.
vec3 metal_rough_layer_f(BsdfParams m, float w) {
    return m.specular_weight * (m.specular_f0 + (1.0 - m.specular_f0) * w);
}

// The probability of sampling the specular lobe from wo (upper hemisphere, cosine cos_o): the
// specular lobe's share of the reflectance estimated with Fresnel at the normal's angle, kept
// within [0.1, 0.9] unless one lobe is missing.
float metal_rough_specular_probability(BsdfParams m, float cos_o) {
    float w = schlick_weight(cos_o);
    vec3 layer_f = metal_rough_layer_f(m, w);
    vec3 f = mix(layer_f, m.color + (1.0 - m.color) * w, m.metallic);
    float specular = (f.r + f.g + f.b) / 3.0;
    float diffuse = (1.0 - m.metallic) * (1.0 - max3(layer_f)) * (m.color.r + m.color.g + m.color.b) / 3.0;
    if (diffuse <= 0.0 || specular <= 0.0) {
        return diffuse > 0.0 ? 0.0 : 1.0;
    }
    return clamp(specular / (specular + diffuse), 0.1, 0.9);
}

// The pdf of sampling wi from wo (both upper hemisphere, h their half vector; p_specular:
// metal_rough_specular_probability at wo).
float metal_rough_pdf_upper(BsdfParams m, vec3 wo, vec3 wi, vec3 h, float p_specular) {
    return mix(wi.z * INV_PI, ggx_reflection_pdf(wo, h, m.alpha), p_specular);
}

// wo and wi in the upper hemisphere; p_specular: metal_rough_specular_probability at wo.
vec3 metal_rough_eval_upper(BsdfParams m, vec3 wo, vec3 wi, float p_specular, out float pdf) {
    vec3 h = normalize(wo + wi);
    float w = schlick_weight(dot(wi, h));
    vec3 layer_f = metal_rough_layer_f(m, w);
    vec3 f = mix(layer_f, m.color + (1.0 - m.color) * w, m.metallic);
    vec3 diffuse = ((1.0 - m.metallic) * (1.0 - max3(layer_f)) * INV_PI * wi.z) * m.color;
    vec3 specular = f * (ggx_d(h, m.alpha) * ggx_g2(wo, wi, m.alpha) / (4.0 * wo.z));
    pdf = metal_rough_pdf_upper(m, wo, wi, h, p_specular);
    return diffuse + specular;
}

// glTF's metallic-roughness model: value and pdf for wo -> wi, and in rev_pdf the pdf of sampling
// wo from wi.
vec3 metal_rough_eval_both(BsdfParams m, vec3 wo, vec3 wi, out float pdf, out float rev_pdf) {
    pdf = 0.0;
    rev_pdf = 0.0;
    if (wo.z * wi.z <= 0.0) {
        return vec3(0.0);
    }
    float flip = wo.z < 0.0 ? -1.0 : 1.0;
    vec3 o = vec3(wo.xy, wo.z * flip);
    vec3 i = vec3(wi.xy, wi.z * flip);
    rev_pdf = metal_rough_pdf_upper(m, i, o, normalize(i + o), metal_rough_specular_probability(m, i.z));
    return metal_rough_eval_upper(m, o, i, metal_rough_specular_probability(m, o.z), pdf);
}

bool metal_rough_sample(BsdfParams m, vec3 wo, vec3 u, out BsdfSample s) {
    float flip = wo.z < 0.0 ? -1.0 : 1.0;
    vec3 o = vec3(wo.xy, wo.z * flip);
    float p_specular = metal_rough_specular_probability(m, o.z);
    vec3 i = u.z < p_specular
        ? reflect(-o, ggx_sample_visible(o, m.alpha, u.xy))
        : sample_cosine_hemisphere(u.xy);
    s.delta = false;
    s.pdf = 0.0;
    if (i.z <= 0.0) {
        return false;
    }
    vec3 f = metal_rough_eval_upper(m, o, i, p_specular, s.pdf);
    s.wi = vec3(i.xy, i.z * flip);
    s.weight = s.pdf > 0.0 ? f / s.pdf : vec3(0.0);
    return s.pdf > 0.0;
}

// ---- dispatch ----

// The BSDF's value for wo -> wi (cosine of wi included) and in pdf the pdf of sampling wi from
// wo; in rev_pdf the pdf of sampling wo from wi: what bidirectional MIS weights need, in one
// evaluation.
vec3 bsdf_eval_both(BsdfParams m, vec3 wo, vec3 wi, out float pdf, out float rev_pdf) {
    if (HAS_CONDUCTOR && m.kind == MATERIAL_CONDUCTOR) {
        return conductor_eval_both(m, wo, wi, pdf, rev_pdf);
    }
    if (HAS_DIELECTRIC && m.kind == MATERIAL_DIELECTRIC) {
        pdf = 0.0;
        rev_pdf = 0.0;
        if (!HAS_DIELECTRIC_ROUGH) {
            return vec3(0.0);
        }
        dielectric_eval(m, wi, wo, rev_pdf);
        return dielectric_eval(m, wo, wi, pdf);
    }
    if (HAS_METAL_ROUGH && m.kind == MATERIAL_METAL_ROUGH) {
        return metal_rough_eval_both(m, wo, wi, pdf, rev_pdf);
    }
    return diffuse_eval_both(m, wo, wi, pdf, rev_pdf);
}

vec3 bsdf_eval(BsdfParams m, vec3 wo, vec3 wi, out float pdf) {
    float rev_pdf;
    return bsdf_eval_both(m, wo, wi, pdf, rev_pdf);
}

// Samples wi for wo. Diffuse and conductors compute the reverse pdf from what their sample holds;
// the others evaluate it (a path tracer, which never reads it, drops that work).
bool bsdf_sample(BsdfParams m, vec3 wo, vec3 u, out BsdfSample s) {
    if (HAS_CONDUCTOR && m.kind == MATERIAL_CONDUCTOR) {
        return conductor_sample(m, wo, u.xy, s);
    }
    bool sampled;
    if (HAS_DIELECTRIC && m.kind == MATERIAL_DIELECTRIC) {
        if (!HAS_DIELECTRIC_ROUGH) {
            m.smooth_lobe = true;
        }
        sampled = dielectric_sample(m, wo, u, s);
    } else if (HAS_METAL_ROUGH && m.kind == MATERIAL_METAL_ROUGH) {
        sampled = metal_rough_sample(m, wo, u, s);
    } else {
        return diffuse_sample(m, wo, u.xy, s);
    }
    s.rev_pdf = 0.0;
    if (sampled && !s.delta) {
        bsdf_eval(m, s.wi, wo, s.rev_pdf);
    }
    return sampled;
}

// Whether the BSDF is a pure delta (no next-event estimation is useful).
bool bsdf_is_delta(BsdfParams m) {
    return (m.kind == MATERIAL_CONDUCTOR || m.kind == MATERIAL_DIELECTRIC) && m.smooth_lobe;
}

#endif
