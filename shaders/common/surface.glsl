// What a ray hit: position, geometric and shading normals, uv, material. Requires scene.glsl,
// traverse.glsl, bsdf.glsl.
#ifndef LUCID_SURFACE_GLSL
#define LUCID_SURFACE_GLSL

// Some used material has a normal map (tangents in b_vertex_attributes).
layout(constant_id = 114) const bool HAS_NORMAL_MAPS = true;
// Some used material has an occlusion texture (the denoisers' albedo only).
layout(constant_id = 115) const bool HAS_OCCLUSION = true;

struct Surface {
    vec3 p;
    vec3 ng;        // geometric normal, on the side of the shading normal (the "front")
    vec3 ns;        // shading normal (the normal map's, where the material has one)
    vec2 uv;
    vec3 color;     // interpolated vertex colour (white without HAS_VERTEX_COLORS)
    uint material;
    uint object_id; // scene instance, or 0x80000000 | sphere
    // Emitting-triangle data for MIS (world vertices); unused for spheres.
    vec3 p0;
    vec3 p1;
    vec3 p2;
    bool sphere;
    vec4 center_radius;
    // Half the log2 of the hit triangle's texture-coordinate area over its world area (of a
    // sphere's coordinates over its surface): the texel density for ray-cone texture filtering.
    float uv_density;
};

// The shading normal of surface s perturbed by tangent-space normal map `map` (scaled in x and y
// by `scale`), with world tangent t and bitangent along `bitangent`: the frame is made orthonormal
// about s.ns, and the result kept at least slightly on the front of the geometric normal (light
// transport offsets and visibility keep using s.ng).
vec3 normal_mapped(Surface s, uint map, float scale, vec3 t, vec3 bitangent) {
    vec3 n = sample_texture(map, s.uv).xyz * 2.0 - 1.0;
    n.xy *= scale;
    vec3 tangent = t - s.ns * dot(s.ns, t);
    float len = length(tangent);
    if (!(len > 1e-8)) {
        return s.ns;
    }
    tangent /= len;
    vec3 b = cross(s.ns, tangent);
    b = dot(b, bitangent) < 0.0 ? -b : b;
    vec3 mapped = tangent * n.x + b * n.y + s.ns * n.z;
    float front = dot(mapped, s.ng);
    if (front < 0.05) {
        mapped += s.ng * (0.05 - front);
    }
    float m = length(mapped);
    return m > 1e-8 ? mapped / m : s.ns;
}

// The material of what `hit` hit (the one surface_at finds), without the rest of the surface:
// the wavefront path tracer bins its hits by it.
uint hit_material(Hit hit) {
    Instance inst = b_instances.i[hit.instance];
    if (HAS_SPHERES && inst.kind == INSTANCE_SPHERES) {
        return b_spheres.s[hit.primitive].material;
    }
    return inst.kind == INSTANCE_FLATTENED ? b_triangle_ids.t[hit.primitive].x : inst.material;
}

Surface surface_at(Hit hit, vec3 origin, vec3 dir) {
    Surface s;
    Instance inst = b_instances.i[hit.instance];
    s.p = origin + dir * hit.t;
    s.sphere = HAS_SPHERES && inst.kind == INSTANCE_SPHERES;
    if (s.sphere) {
        Sphere sp = b_spheres.s[hit.primitive];
        vec3 c = transform_point(inst.object_to_world, sp.center_radius.xyz);
        s.center_radius = vec4(c, sp.center_radius.w);
        s.ng = normalize(s.p - c);
        s.ns = s.ng;
        vec3 n = s.ng;
        s.uv = vec2(atan(n.z, n.x) * (0.5 * INV_PI) + 0.5, acos(clamp(n.y, -1.0, 1.0)) * INV_PI);
        s.uv_density = 0.5 * log2(1.0 / (4.0 * PI * s.center_radius.w * s.center_radius.w));
        s.material = sp.material;
        s.object_id = 0x80000000u | sp.scene_sphere;
        s.color = vec3(1.0);
        return s;
    }
    uvec3 vertices = triangle_vertices(hit.primitive);
    uint i0 = vertices.x;
    uint i1 = vertices.y;
    uint i2 = vertices.z;
    Vertex v0 = b_vertices.v[i0];
    Vertex v1 = b_vertices.v[i1];
    Vertex v2 = b_vertices.v[i2];
    vec3 b = vec3(1.0 - hit.bary.x - hit.bary.y, hit.bary.x, hit.bary.y);
    s.p0 = vec3(v0.px, v0.py, v0.pz);
    s.p1 = vec3(v1.px, v1.py, v1.pz);
    s.p2 = vec3(v2.px, v2.py, v2.pz);
    vec3 ns = b.x * decode_normal(v0.normal) + b.y * decode_normal(v1.normal) + b.z * decode_normal(v2.normal);
    vec3 ns_object = ns;
    bool flattened = inst.kind == INSTANCE_FLATTENED; // already in world space
    if (!flattened) {
        s.p0 = transform_point(inst.object_to_world, s.p0);
        s.p1 = transform_point(inst.object_to_world, s.p1);
        s.p2 = transform_point(inst.object_to_world, s.p2);
        ns = transform_normal(inst.world_to_object, ns);
    }
    s.p = b.x * s.p0 + b.y * s.p1 + b.z * s.p2;
    s.ns = normalize(ns);
    s.ng = normalize(cross(s.p1 - s.p0, s.p2 - s.p0));
    if (dot(s.ng, s.ns) < 0.0) {
        s.ng = -s.ng;
    }
    s.uv = vec2(0.0);
    s.uv_density = NO_FOOTPRINT;
    if (HAS_TEXTURES) {
        vec2 uv0 = unpackHalf2x16(v0.uv);
        vec2 uv1 = unpackHalf2x16(v1.uv);
        vec2 uv2 = unpackHalf2x16(v2.uv);
        s.uv = b.x * uv0 + b.y * uv1 + b.z * uv2;
        vec2 e1 = uv1 - uv0;
        vec2 e2 = uv2 - uv0;
        float uv_area = abs(e1.x * e2.y - e1.y * e2.x);
        float world_area = length(cross(s.p1 - s.p0, s.p2 - s.p0));
        if (uv_area > 0.0 && world_area > 0.0) {
            s.uv_density = 0.5 * log2(uv_area / world_area);
        }
    }
    if (HAS_VERTEX_COLORS) {
        s.color = b.x * vertex_color(i0).rgb + b.y * vertex_color(i1).rgb + b.z * vertex_color(i2).rgb;
    } else {
        s.color = vec3(1.0);
    }
    if (flattened) {
        uvec2 ids = b_triangle_ids.t[hit.primitive];
        s.material = ids.x;
        s.object_id = ids.y;
    } else {
        s.material = inst.material;
        s.object_id = inst.scene_instance;
    }
    if (HAS_NORMAL_MAPS) {
        uint map = b_materials.m[s.material].normal_texture;
        if (map != NO_TEXTURE) {
            vec4 t0 = vertex_tangent(i0);
            vec3 t = b.x * t0.xyz + b.y * vertex_tangent(i1).xyz + b.z * vertex_tangent(i2).xyz;
            vec3 bitangent = cross(ns_object, t) * t0.w;
            if (!flattened) {
                t = transform_vector(inst.object_to_world, t);
                bitangent = transform_vector(inst.object_to_world, bitangent);
            }
            s.ns = normal_mapped(s, map, b_materials.m[s.material].normal_scale, t, bitangent);
        }
    }
    return s;
}



// The mip footprint (see sample_texture_lod) of a ray cone of width `width` meeting surface s
// along dir (Akenine-Möller et al. 2019, "Texture Level of Detail Strategies for Real-Time Ray
// Tracing"): log2 of the cone's width over the cosine of its incidence, plus the surface's
// texel density. NO_FOOTPRINT where the surface has no texture coordinates.
float cone_lod(Surface s, vec3 dir, float width) {
    float cos_in = abs(dot(s.ng, dir));
    float lod = s.uv_density + log2(width / max(cos_in, 1e-4));
    return isnan(lod) || s.uv_density <= NO_FOOTPRINT ? NO_FOOTPRINT : lod;
}

// The BSDF of `material` at texture coordinates `uv`, its textures looked up at mip footprint
// `footprint` (cone_lod; NO_FOOTPRINT for level 0); with `look_up_base`, its base colour is the
// material's times its base colour texture's times `color` (the vertex colour, white when the
// scene has none), otherwise `color` itself.
BsdfParams material_params_from(uint material, vec2 uv, vec3 color, float footprint, bool look_up_base) {
    Material m = b_materials.m[material];
    BsdfParams p;
    p.kind = m.kind;
    p.color = look_up_base ? m.base_color : color;
    if (look_up_base && HAS_TEXTURES && m.texture != 0xffffffffu) {
        p.color *= sample_texture_lod(m.texture, uv, footprint).rgb;
    }
    if (look_up_base && HAS_VERTEX_COLORS) {
        p.color *= color;
    }
    p.alpha = max(m.alpha, 1e-4);
    p.ior = m.ior;
    p.smooth_lobe = (m.flags & MATERIAL_FLAG_SMOOTH) != 0u;
    p.occlusion = 1.0;
    if (HAS_OCCLUSION && m.occlusion_texture != NO_TEXTURE) {
        float ao = sample_texture_lod(m.occlusion_texture, uv, footprint).r;
        p.occlusion = 1.0 + m.occlusion_strength * (ao - 1.0);
    }
    p.metallic = m.metallic;
    p.specular_f0 = m.specular_f0;
    p.specular_weight = m.specular_weight;
    if (HAS_METAL_ROUGH && m.kind == MATERIAL_METAL_ROUGH) {
        // glTF's metallic-roughness texture: roughness in G (alpha scales by its square), metal
        // in B. Never a delta lobe: alpha stays at or above the smooth threshold.
        if (HAS_TEXTURES && m.metal_roughness != NO_TEXTURE) {
            vec4 mr = sample_texture_lod(m.metal_roughness, uv, footprint);
            p.alpha = m.alpha * mr.g * mr.g;
            p.metallic *= mr.b;
        }
        p.alpha = max(p.alpha, 1e-3);
        p.smooth_lobe = false;
    }
    return p;
}

// The BSDF of `material` at texture coordinates `uv` with vertex colour `vertex_color` (white when
// the scene has none), which multiplies the base colour; its textures are looked up at mip
// footprint `footprint` (cone_lod; NO_FOOTPRINT for level 0).
BsdfParams material_params_lod(uint material, vec2 uv, vec3 vertex_color, float footprint) {
    return material_params_from(material, uv, vertex_color, footprint, true);
}

// material_params_lod at level 0 of every texture.
BsdfParams material_params(uint material, vec2 uv, vec3 vertex_color) {
    return material_params_lod(material, uv, vertex_color, NO_FOOTPRINT);
}

// The BSDF of `material` at texture coordinates `uv` whose base colour, the material's with its
// texture and vertex colour, is `base_color` already; its other textures at level 0.
BsdfParams material_params_with_base(uint material, vec2 uv, vec3 base_color) {
    return material_params_from(material, uv, base_color, NO_FOOTPRINT, false);
}

// The colour a denoiser divides radiance by (and multiplies back): the material's base colour for
// diffuse and conductors, white for dielectrics; times the occlusion texture's (which light
// transport does not use: it only guides the denoisers).
vec3 demodulation_albedo(BsdfParams m) {
    return (m.kind == MATERIAL_DIELECTRIC ? vec3(1.0) : m.color) * m.occlusion;
}

// The G-buffer's roughness: GGX alpha of the specular lobe, 1 for diffuse; metallic-roughness
// surfaces blend towards 1 as their metal share falls (their dielectric layer reflects little).
float gbuffer_roughness(BsdfParams m) {
    if (m.kind == MATERIAL_DIFFUSE) {
        return 1.0;
    }
    return m.kind == MATERIAL_METAL_ROUGH ? mix(1.0, m.alpha, m.metallic) : m.alpha;
}

// Radiance emitted from the surface towards -dir (one-sided: front only).
vec3 surface_emission(Surface s, vec3 dir) {
    Material m = b_materials.m[s.material];
    if ((m.flags & MATERIAL_FLAG_EMISSIVE) == 0u || dot(s.ng, dir) >= 0.0) {
        return vec3(0.0);
    }
    return material_emission(m, s.uv);
}

// The NEE pdf of having sampled this emitting surface point from `from` (for MIS).
float surface_light_pdf(Surface s, vec3 from) {
    vec3 emission = b_materials.m[s.material].emission;
    if (s.sphere) {
        return sphere_light_pdf(from, s.center_radius, emission);
    }
    return triangle_light_pdf(from, s.p, s.ng, s.p0, s.p1, s.p2, emission);
}

#endif
