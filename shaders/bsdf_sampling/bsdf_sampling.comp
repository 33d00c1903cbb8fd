#version 460
// Samples and evaluates the BSDFs (common/bsdf.glsl) for a buffer of cases, one an invocation, so
// that a test can check the sampling against the evaluation: that each sample's pdf, reverse pdf
// and weight are what evaluating the BSDF for its two directions gives.
#include "common/math.glsl"
#include "common/bsdf.glsl"

layout(local_size_x = 64) in;

// One case (lucid_passes::debug::bsdf_sampling::BsdfCase).
struct BsdfCase {
    vec4 color_alpha;   // base colour, GGX alpha
    vec4 wo_ior;        // wo in the shading frame (unit), index of refraction
    vec4 u_metallic;    // the sample's three numbers, metallic share
    uvec4 kind_smooth;  // MATERIAL_*, delta lobe (0 or 1)
};

// What sampling and evaluating gave (lucid_passes::debug::bsdf_sampling::BsdfOutcome).
struct BsdfOutcome {
    vec4 wi_sampled;    // the sampled direction, 1 where sampling succeeded (else 0)
    vec4 weight_pdf;    // BsdfSample's weight and pdf
    vec4 rev_delta;     // BsdfSample's rev_pdf, 1 for a delta lobe, bsdf_eval_both's pdf and rev_pdf
    vec4 value;         // bsdf_eval_both's value for wo -> wi (cosine included)
};

layout(set = 0, binding = 0, std430) readonly buffer Cases { BsdfCase c[]; } b_cases;
layout(set = 0, binding = 1, std430) writeonly buffer Outcomes { BsdfOutcome o[]; } b_outcomes;

layout(push_constant) uniform Params {
    uint count;  // cases in b_cases
} params;

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= params.count) {
        return;
    }
    BsdfCase c = b_cases.c[index];
    BsdfParams m;
    m.kind = c.kind_smooth.x;
    m.color = c.color_alpha.rgb;
    m.alpha = c.color_alpha.a;
    m.metallic = c.u_metallic.w;
    m.specular_f0 = vec3(0.04);
    m.specular_weight = 1.0;
    m.ior = c.wo_ior.w;
    m.smooth_lobe = c.kind_smooth.y != 0u;
    m.occlusion = 1.0;
    vec3 wo = c.wo_ior.xyz;
    BsdfSample s;
    bool sampled = bsdf_sample(m, wo, c.u_metallic.xyz, s);
    BsdfOutcome o;
    o.wi_sampled = vec4(s.wi, sampled ? 1.0 : 0.0);
    o.weight_pdf = vec4(s.weight, s.pdf);
    float pdf = 0.0;
    float rev_pdf = 0.0;
    vec3 value = vec3(0.0);
    if (sampled && !s.delta) {
        value = bsdf_eval_both(m, wo, s.wi, pdf, rev_pdf);
    }
    o.rev_delta = vec4(s.rev_pdf, s.delta ? 1.0 : 0.0, pdf, rev_pdf);
    o.value = vec4(value, 0.0);
    b_outcomes.o[index] = o;
}
