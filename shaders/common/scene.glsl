// The scene buffers, mirroring lucid_engine::scene::gpu (std430). Bound by name: b_vertices,
// b_blas, b_tlas, b_instances, b_spheres, b_materials, b_lights, b_light_table,
// b_texels, b_textures, b_scene, b_triangle_ids, b_triangles, b_vertex_attributes. Bindings 0 and 2-11
// and 13-15 (12 is the frame constants); passes use 16 and up for their own resources.
#ifndef LUCID_SCENE_GLSL
#define LUCID_SCENE_GLSL

struct Vertex { float px, py, pz; uint normal; uint uv; };
// An interior node of the binary BVH layout: both children's boxes and child words
// (lucid_engine::scene::gpu::bvh_pack), unpacked from four uvec4 of b_blas / b_tlas.
struct BvhNode {
    vec3 left_min; uint left;
    vec3 left_max; uint right;
    vec3 right_min; uint pad0;
    vec3 right_max; uint pad1;
};
struct Instance {
    vec4 object_to_world[3];
    vec4 world_to_object[3];
    uint blas_root;
    uint material;
    uint kind;
    uint scene_instance;
};
struct Sphere { vec4 center_radius; uint material; uint scene_sphere; uint pad0; uint pad1; };
// Texture fields index b_textures (NO_TEXTURE: none).
struct Material {
    vec3 base_color; uint kind;
    vec3 emission; float alpha;
    float ior; uint texture; uint flags; uint metal_roughness;
    float metallic; uint normal_texture; float normal_scale; uint emissive_texture;
    uint occlusion_texture; float occlusion_strength; float opacity; float alpha_cutoff;
    vec3 specular_f0; float specular_weight;
};
// material: a triangle light's material (emissive texture, opacity), ~0u for other lights.
struct Light { uint kind; uint index; uint instance; uint material; vec4 p0; vec4 p1; vec4 p2; vec4 emission; };
struct LightTableEntry { float threshold; uint alias; float pdf; float cdf; };
// A texture as one material slot samples it: texels, then the coordinate transform's rows with the
// wrap mode along each axis in w (TEXTURE_WRAP_*).
struct TextureRecord { uint offset; uint width; uint height; uint format; vec4 u_row; vec4 v_row; };
struct Camera { vec4 position_aperture; vec4 right_focus; vec4 up_tan_half_fov; vec4 forward; };
// kind 0: constant (zenith), 1: sky gradient, 2: equirectangular map (texture record map_record,
// its sampling distribution of cells_x x cells_y cells in b_light_table after the lights).
struct Environment { uint kind; uint map_record; uint cells_x; uint cells_y; vec4 zenith; vec4 horizon; vec4 ground; };
struct Sun { vec4 direction_cos; vec4 radiance_enabled; };
struct SceneParams {
    Camera camera;
    Environment environment;
    Sun sun;
    uvec4 counts0; // triangles, instances, spheres, lights
    uvec4 counts1; // materials, textures, tlas root word, blas nodes
    vec4 light;    // total NEE light power
    vec4 bounds_min; // a box around the whole scene, a little larger (xyz)
    vec4 bounds_max;
};

#include "common/material_kinds.glsl"
const uint MATERIAL_FLAG_EMISSIVE = 1u;
const uint MATERIAL_FLAG_SMOOTH = 2u;
const uint MATERIAL_FLAG_ALPHA_MASK = 4u;  // absent where opacity < alpha_cutoff
const uint MATERIAL_FLAG_ALPHA_BLEND = 8u; // present with probability opacity
const uint NO_TEXTURE = 0xffffffffu;
const uint LIGHT_TRIANGLE = 0u;
const uint LIGHT_SPHERE = 1u;
const uint LIGHT_POINT = 2u;
const uint LIGHT_SPOT = 3u;
const uint INSTANCE_TRIANGLES = 0u;
const uint INSTANCE_SPHERES = 1u;
const uint INSTANCE_FLATTENED = 2u; // static instances merged in world space: ids per triangle
const uint TEXTURE_RGBA8_SRGB = 0u;
const uint TEXTURE_RGBA8_LINEAR = 1u;
const uint TEXTURE_RGBA32F = 2u;
const uint TEXTURE_WRAP_REPEAT = 0u;
const uint TEXTURE_WRAP_CLAMP = 1u;
const uint TEXTURE_WRAP_MIRROR = 2u;

// Some material uses a base-colour or other texture (else texture coordinates are not even
// interpolated).
layout(constant_id = 107) const bool HAS_TEXTURES = true;
// Some mesh has vertex colours (and alphas) in b_vertex_attributes.
layout(constant_id = 110) const bool HAS_VERTEX_COLORS = true;
// Some texture slot transforms its coordinates (KHR_texture_transform) or does not repeat.
layout(constant_id = 111) const bool HAS_TEXTURE_TRANSFORMS = true;

layout(set = 0, binding = 0, std430) readonly buffer Vertices { Vertex v[]; } b_vertices;
// BVH nodes in the scene's layout (traverse.glsl's WIDE_BVH): a binary node is four uvec4 (BvhNode),
// a wide node five (lucid_engine::scene::gpu::wide::WideNode).
layout(set = 0, binding = 2, std430) readonly buffer BlasNodes { uvec4 n[]; } b_blas;
layout(set = 0, binding = 3, std430) readonly buffer TlasNodes { uvec4 n[]; } b_tlas;
layout(set = 0, binding = 4, std430) readonly buffer Instances { Instance i[]; } b_instances;
layout(set = 0, binding = 5, std430) readonly buffer Spheres { Sphere s[]; } b_spheres;
layout(set = 0, binding = 6, std430) readonly buffer Materials { Material m[]; } b_materials;
layout(set = 0, binding = 7, std430) readonly buffer Lights { Light l[]; } b_lights;
layout(set = 0, binding = 8, std430) readonly buffer LightTable { LightTableEntry e[]; } b_light_table;
layout(set = 0, binding = 9, std430) readonly buffer Texels { uint t[]; } b_texels;
layout(set = 0, binding = 10, std430) readonly buffer Textures { TextureRecord r[]; } b_textures;
layout(set = 0, binding = 11, std430) readonly buffer ScenePayload { SceneParams p; } b_scene;
// Per triangle of the flattened instance: material, original scene instance.
layout(set = 0, binding = 13, std430) readonly buffer TriangleIds { uvec2 t[]; } b_triangle_ids;
// Per triangle, in the packed BLASes' order, three vec4 (GpuTriangle): first vertex, p1 - p0 and
// p2 - p0 (what ray intersection reads, in the first two and a lane of the third), then the indices
// of the three vertices in b_vertices (triangle_vertices).
layout(set = 0, binding = 14, std430) readonly buffer Triangles { vec4 t[]; } b_triangles;
// Per vertex (as b_vertices), when the scene has vertex colours or tangents (HAS_VERTEX_COLORS,
// HAS_NORMAL_MAPS): packHalf2x16(r, g), packHalf2x16(b, alpha), the octahedral tangent and the
// bitangent's sign as float bits. One unread element otherwise.
layout(set = 0, binding = 15, std430) readonly buffer VertexAttributes { uvec4 a[]; } b_vertex_attributes;

// RGB and alpha.
vec4 vertex_color(uint index) {
    uvec4 a = b_vertex_attributes.a[index];
    return vec4(unpackHalf2x16(a.x), unpackHalf2x16(a.y));
}

vec3 decode_normal(uint bits);

// Unit tangent (xyz) and the bitangent's sign (w).
vec4 vertex_tangent(uint index) {
    uvec4 a = b_vertex_attributes.a[index];
    return vec4(decode_normal(a.z), uintBitsToFloat(a.w));
}

vec3 vertex_position(uint index) {
    Vertex v = b_vertices.v[index];
    return vec3(v.px, v.py, v.pz);
}

vec3 decode_normal(uint bits) {
    vec2 e = max(unpackSnorm2x16(bits), vec2(-1.0));
    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (n.z < 0.0) {
        vec2 s = vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
        n.xy = (1.0 - abs(n.yx)) * s;
    }
    return normalize(n);
}

// The indices in b_vertices of global triangle `prim`'s vertices.
uvec3 triangle_vertices(uint prim) {
    return floatBitsToUint(b_triangles.t[3u * prim + 2u].yzw);
}

vec3 transform_point(vec4 m[3], vec3 p) {
    return vec3(dot(m[0].xyz, p) + m[0].w, dot(m[1].xyz, p) + m[1].w, dot(m[2].xyz, p) + m[2].w);
}

vec3 transform_vector(vec4 m[3], vec3 v) {
    return vec3(dot(m[0].xyz, v), dot(m[1].xyz, v), dot(m[2].xyz, v));
}

// Transforms a normal with the inverse transpose, given the inverse (world_to_object) rows.
vec3 transform_normal(vec4 inv[3], vec3 n) {
    return inv[0].xyz * n.x + inv[1].xyz * n.y + inv[2].xyz * n.z;
}

// Texel index i of a row or column of n texels under wrap mode `mode`.
int wrap_texel(int i, int n, uint mode) {
    if (mode == TEXTURE_WRAP_CLAMP) {
        return clamp(i, 0, n - 1);
    }
    if (mode == TEXTURE_WRAP_MIRROR) {
        int k = ((i % (2 * n)) + 2 * n) % (2 * n);
        return k < n ? k : 2 * n - 1 - k;
    }
    return ((i % n) + n) % n;
}

vec4 fetch_texel(TextureRecord r, int x, int y, uvec2 wrap) {
    x = wrap_texel(x, int(r.width), wrap.x);
    y = wrap_texel(y, int(r.height), wrap.y);
    if (r.format == TEXTURE_RGBA32F) {
        uint o = r.offset + (uint(y) * r.width + uint(x)) * 4u;
        return uintBitsToFloat(uvec4(b_texels.t[o], b_texels.t[o + 1u], b_texels.t[o + 2u], b_texels.t[o + 3u]));
    }
    uint word = b_texels.t[r.offset + uint(y) * r.width + uint(x)];
    vec4 c = unpackUnorm4x8(word);
    if (r.format == TEXTURE_RGBA8_SRGB) {
        // The texel buffer opens with the linear value of every sRGB code (params::srgb_table).
        c.rgb = uintBitsToFloat(uvec3(b_texels.t[word & 0xffu], b_texels.t[(word >> 8u) & 0xffu],
                                      b_texels.t[(word >> 16u) & 0xffu]));
    }
    return c;
}

// Level `level` of record r's mip chain: every texture has a full one after its level 0, each
// level halving both sides (odd sides rounding down, never below 1) down to 1x1.
TextureRecord texture_level(TextureRecord r, uint level) {
    uint words = r.format == TEXTURE_RGBA32F ? 4u : 1u;
    for (uint l = 0u; l < level; ++l) {
        r.offset += r.width * r.height * words;
        r.width = max(r.width / 2u, 1u);
        r.height = max(r.height / 2u, 1u);
    }
    return r;
}

vec4 bilinear(TextureRecord r, vec2 uv, uvec2 wrap) {
    vec2 st = uv * vec2(r.width, r.height) - 0.5;
    ivec2 i = ivec2(floor(st));
    vec2 f = st - vec2(i);
    vec4 a = mix(fetch_texel(r, i.x, i.y, wrap), fetch_texel(r, i.x + 1, i.y, wrap), f.x);
    vec4 b = mix(fetch_texel(r, i.x, i.y + 1, wrap), fetch_texel(r, i.x + 1, i.y + 1, wrap), f.x);
    return mix(a, b, f.y);
}

// Trilinear lookup of texture record `texture_index` at uv, after its coordinate transform and
// with its wrap modes (repeating, untransformed without HAS_TEXTURE_TRANSFORMS), for a footprint
// of mip level `footprint` on a one-texel texture (cone_lod in surface.glsl): the level is that
// plus half the log2 of the texture's texel count, clamped to its chain (0: bilinear on level 0).
vec4 sample_texture_lod(uint texture_index, vec2 uv, float footprint) {
    TextureRecord r = b_textures.r[texture_index];
    float lod = footprint + 0.5 * log2(float(r.width) * float(r.height));
    uvec2 wrap = uvec2(TEXTURE_WRAP_REPEAT);
    if (HAS_TEXTURE_TRANSFORMS) {
        uv = vec2(dot(r.u_row.xyz, vec3(uv, 1.0)), dot(r.v_row.xyz, vec3(uv, 1.0)));
        wrap = uvec2(r.u_row.w, r.v_row.w);
    }
    float top = float(findMSB(max(r.width, r.height)));
    lod = min(lod, top);
    if (!(lod > 0.0)) {
        return bilinear(r, uv, wrap);
    }
    uint level = min(uint(lod), uint(top));
    vec4 fine = bilinear(texture_level(r, level), uv, wrap);
    if (float(level) >= top) {
        return fine;
    }
    return mix(fine, bilinear(texture_level(r, level + 1u), uv, wrap), fract(lod));
}

// No footprint: level 0 of every texture.
const float NO_FOOTPRINT = -1e30;

// Bilinear lookup of the full texture.
vec4 sample_texture(uint texture_index, vec2 uv) {
    return sample_texture_lod(texture_index, uv, NO_FOOTPRINT);
}

#endif
