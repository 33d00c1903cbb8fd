// The scene buffers, mirroring lucid_engine::scene::gpu (std430). Bound by name: b_vertices,
// b_indices, b_blas, b_tlas, b_instances, b_spheres, b_materials, b_lights, b_light_table,
// b_texels, b_textures, b_scene, b_triangle_ids, b_triangles, b_vertex_colors. Bindings 0-11 and
// 13-15 (12 is the frame constants); passes use 16 and up for their own resources.
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
struct Material {
    vec3 base_color; uint kind;
    vec3 emission; float alpha;
    float ior; uint texture; uint flags; uint metal_roughness;
    float metallic; uint pad0; uint pad1; uint pad2;
};
struct Light { uint kind; uint index; uint instance; uint pad; vec4 p0; vec4 p1; vec4 p2; vec4 emission; };
struct LightTableEntry { float threshold; uint alias; float pdf; float cdf; };
struct TextureRecord { uint offset; uint width; uint height; uint format; };
struct Camera { vec4 position_aperture; vec4 right_focus; vec4 up_tan_half_fov; vec4 forward; };
struct Environment { uint kind; uint pad0; uint pad1; uint pad2; vec4 zenith; vec4 horizon; vec4 ground; };
struct Sun { vec4 direction_cos; vec4 radiance_enabled; };
struct SceneParams {
    Camera camera;
    Environment environment;
    Sun sun;
    uvec4 counts0; // triangles, instances, spheres, lights
    uvec4 counts1; // materials, textures, tlas root word, blas nodes
    vec4 light;    // total NEE light power
};

const uint MATERIAL_DIFFUSE = 0u;
const uint MATERIAL_CONDUCTOR = 1u;
const uint MATERIAL_DIELECTRIC = 2u;
const uint MATERIAL_FLAG_EMISSIVE = 1u;
const uint MATERIAL_FLAG_SMOOTH = 2u;
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

layout(set = 0, binding = 0, std430) readonly buffer Vertices { Vertex v[]; } b_vertices;
layout(set = 0, binding = 1, std430) readonly buffer Indices { uint i[]; } b_indices;
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
// Per triangle (in b_indices order), nine floats: first vertex, p1 - p0, p2 - p0 (what ray
// intersection reads, contiguous).
layout(set = 0, binding = 14, std430) readonly buffer Triangles { float t[]; } b_triangles;
// Per vertex (as b_vertices), when the scene has vertex colours (HAS_VERTEX_COLORS in surface.glsl):
// RGB as half floats, packHalf2x16(r, g) and packHalf2x16(b, 0). One unread element otherwise.
layout(set = 0, binding = 15, std430) readonly buffer VertexColors { uvec2 c[]; } b_vertex_colors;

vec3 vertex_color(uint index) {
    uvec2 c = b_vertex_colors.c[index];
    return vec3(unpackHalf2x16(c.x), unpackHalf2x16(c.y).x);
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

vec4 fetch_texel(TextureRecord r, int x, int y) {
    x = int(uint(x) % r.width);
    y = int(uint(y) % r.height);
    if (r.format == TEXTURE_RGBA32F) {
        uint o = r.offset + (uint(y) * r.width + uint(x)) * 4u;
        return uintBitsToFloat(uvec4(b_texels.t[o], b_texels.t[o + 1u], b_texels.t[o + 2u], b_texels.t[o + 3u]));
    }
    vec4 c = unpackUnorm4x8(b_texels.t[r.offset + uint(y) * r.width + uint(x)]);
    if (r.format == TEXTURE_RGBA8_SRGB) {
        bvec3 low = lessThanEqual(c.rgb, vec3(0.04045));
        c.rgb = mix(pow((c.rgb + 0.055) / 1.055, vec3(2.4)), c.rgb / 12.92, low);
    }
    return c;
}

// Bilinear, repeating lookup of a texture record at uv.
vec4 sample_texture(uint texture_index, vec2 uv) {
    TextureRecord r = b_textures.r[texture_index];
    vec2 st = uv * vec2(r.width, r.height) - 0.5;
    ivec2 i = ivec2(floor(st));
    vec2 f = st - vec2(i);
    vec4 a = mix(fetch_texel(r, i.x, i.y), fetch_texel(r, i.x + 1, i.y), f.x);
    vec4 b = mix(fetch_texel(r, i.x, i.y + 1), fetch_texel(r, i.x + 1, i.y + 1), f.x);
    return mix(a, b, f.y);
}

#endif
