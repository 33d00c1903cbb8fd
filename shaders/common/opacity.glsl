// Cut-out surfaces (glTF alphaMode MASK and BLEND): a material's opacity at a triangle point and
// whether a ray meets the surface there, which the BVH traversal asks of every candidate hit on a
// cut-out material (primary, bounce and shadow rays alike). Requires scene.glsl.
#ifndef LUCID_OPACITY_GLSL
#define LUCID_OPACITY_GLSL

#include "common/rng.glsl"

// Some used material is cut out: traversal tests opacity (else every hit counts).
layout(constant_id = 112) const bool HAS_ALPHA_TEST = true;

const uint MATERIAL_CUT_OUT = MATERIAL_FLAG_ALPHA_MASK | MATERIAL_FLAG_ALPHA_BLEND;

// Texture coordinates and vertex alpha at the point of global triangle `prim` with vertex weights
// `w` (for its first, second and third vertex).
void triangle_uv_alpha(uint prim, vec3 w, out vec2 uv, out float alpha) {
    uvec3 vertices = triangle_vertices(prim);
    uint i0 = vertices.x;
    uint i1 = vertices.y;
    uint i2 = vertices.z;
    uv = w.x * unpackHalf2x16(b_vertices.v[i0].uv) + w.y * unpackHalf2x16(b_vertices.v[i1].uv)
        + w.z * unpackHalf2x16(b_vertices.v[i2].uv);
    alpha = 1.0;
    if (HAS_VERTEX_COLORS) {
        alpha = w.x * vertex_color(i0).a + w.y * vertex_color(i1).a + w.z * vertex_color(i2).a;
    }
}

// Opacity of material m at uv with vertex alpha `vertex_alpha`: base alpha x texture alpha x
// vertex alpha.
float material_opacity(Material m, vec2 uv, float vertex_alpha) {
    float a = m.opacity * vertex_alpha;
    if (HAS_TEXTURES && m.texture != NO_TEXTURE) {
        a *= sample_texture(m.texture, uv).a;
    }
    return a;
}

// How much of a cut-out surface of material m is there, on average, where its opacity is
// `opacity`: 0 or 1 for a mask, the opacity for blending.
float surface_coverage(Material m, float opacity) {
    if ((m.flags & MATERIAL_FLAG_ALPHA_MASK) != 0u) {
        return opacity >= m.alpha_cutoff ? 1.0 : 0.0;
    }
    return opacity;
}

// Whether the candidate hit at barycentrics `bary` on global triangle `prim` of material
// `material`, along the ray (o, d), counts. Opaque materials always do; a mask where the opacity
// reaches the cutoff; blending with probability equal to the opacity (stochastic transparency),
// decided by a hash of the ray and the triangle, so frames still repeat bit for bit.
bool hit_counts(uint material, uint prim, vec2 bary, vec3 o, vec3 d) {
    Material m = b_materials.m[material];
    if ((m.flags & MATERIAL_CUT_OUT) == 0u) {
        return true;
    }
    vec2 uv;
    float vertex_alpha;
    triangle_uv_alpha(prim, vec3(1.0 - bary.x - bary.y, bary), uv, vertex_alpha);
    float opacity = material_opacity(m, uv, vertex_alpha);
    if ((m.flags & MATERIAL_FLAG_ALPHA_MASK) != 0u) {
        return opacity >= m.alpha_cutoff;
    }
    uvec3 ob = floatBitsToUint(o);
    uvec3 db = floatBitsToUint(d);
    uint h = pcg_hash(prim ^ pcg_hash(ob.x ^ pcg_hash(ob.y ^ pcg_hash(ob.z ^ pcg_hash(db.x ^ pcg_hash(db.y ^ pcg_hash(db.z)))))));
    return float(h >> 8u) * (1.0 / 16777216.0) < opacity;
}

#endif
