//! GPU structs. Each mirrors a GLSL std430 struct documented on it; all
//! are `Pod` and have no implicit padding.

use bytemuck::{Pod, Zeroable};

/// Optional per-vertex attributes, 16 bytes, when some mesh has vertex colours or tangents.
/// ```glsl
/// uvec4 a; // packHalf2x16(r, g), packHalf2x16(b, alpha), octahedral tangent (snorm16x2),
///          // floatBitsToUint(bitangent sign)
/// ```
/// Missing colours are opaque white, missing tangents `+X` with sign 1.
pub type GpuVertexAttributes = [u32; 4];

/// A mesh vertex, 20 bytes (std430 stride 20: only scalar members).
/// ```glsl
/// struct Vertex {
///     float px, py, pz;
///     uint  normal; // octahedral, unpackSnorm2x16 (see encode_normal)
///     uint  uv;     // unpackHalf2x16
/// };
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuVertex {
    /// Object-space position.
    pub position: [f32; 3],
    /// Octahedral snorm16x2 shading normal.
    pub normal: u32,
    /// Half-float texture coordinates.
    pub uv: u32,
}

/// A triangle, 48 bytes, read as three `vec4` in GLSL: what ray intersection reads (first vertex,
/// second minus first, third minus first: contiguous reads instead of indices then vertices) in two
/// 16-byte loads, then the indices of its vertices (`triangle_vertices` in
/// `shaders/common/scene.glsl`), in the packed BLAS's order.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuTriangle {
    /// Object-space first vertex.
    pub p0: [f32; 3],
    /// Second vertex minus the first.
    pub e1: [f32; 3],
    /// Third vertex minus the first.
    pub e2: [f32; 3],
    /// Indices of the three vertices (absolute: in `GpuScene::vertices`).
    pub vertices: [u32; 3],
}

/// An instance, 112 bytes (std430 alignment 16).
/// ```glsl
/// struct Instance {
///     vec4 object_to_world[3]; // rows of a 3x4 affine matrix
///     vec4 world_to_object[3];
///     uint blas_root;          // the BLAS root: a child word (bvh_pack) or a wide node (wide)
///     uint material;           // material index; ~0u for the sphere instance
///     uint kind;               // 0 = triangles, 1 = spheres, 2 = flattened static triangles
///     uint scene_instance;     // Scene::instances index; ~0u for spheres
/// };
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuInstance {
    /// Rows of the object-to-world 3x4 matrix.
    pub object_to_world: [[f32; 4]; 3],
    /// Rows of the world-to-object 3x4 matrix.
    pub world_to_object: [[f32; 4]; 3],
    /// The instance's BLAS root (see [`super::PackedTree::root`]).
    pub blas_root: u32,
    /// Material of every triangle (`u32::MAX` for spheres, which carry
    /// their own).
    pub material: u32,
    /// [`INSTANCE_TRIANGLES`](super::INSTANCE_TRIANGLES), [`INSTANCE_SPHERES`](super::INSTANCE_SPHERES)
    /// or [`INSTANCE_FLATTENED`](super::INSTANCE_FLATTENED).
    pub kind: u32,
    /// Index into `Scene::instances` (`u32::MAX` for the sphere instance).
    pub scene_instance: u32,
}

/// An analytic sphere, 32 bytes.
/// ```glsl
/// struct Sphere { vec4 center_radius; uint material; uint scene_sphere; uint pad0, pad1; };
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuSphere {
    /// Centre (xyz) and radius (w), world space.
    pub center_radius: [f32; 4],
    /// Material index.
    pub material: u32,
    /// Index into `Scene::spheres`.
    pub scene_sphere: u32,
    /// Padding to 32 bytes.
    pub pad: [u32; 2],
}

/// Material kinds as stored in [`GpuMaterial::kind`].
pub mod material_kind {
    /// Lambertian diffuse.
    pub const DIFFUSE: u32 = 0;
    /// GGX conductor.
    pub const CONDUCTOR: u32 = 1;
    /// Smooth or rough dielectric.
    pub const DIELECTRIC: u32 = 2;
    /// glTF metallic-roughness: specular layer over diffuse, mixed with a conductor.
    pub const METAL_ROUGH: u32 = 3;
}

/// Bits of [`GpuMaterial::flags`].
pub mod material_flags {
    /// The material emits.
    pub const EMISSIVE: u32 = 1;
    /// GGX alpha below [`crate::scene::SMOOTH_ALPHA`].
    pub const SMOOTH: u32 = 2;
    /// Alpha mask: absent where opacity < `alpha_cutoff`.
    pub const ALPHA_MASK: u32 = 4;
    /// Alpha blend: present with probability `opacity`.
    pub const ALPHA_BLEND: u32 = 8;
}

/// A material, 96 bytes. Texture fields index [`GpuTextureRecord`]s (`~0u`: none).
/// ```glsl
/// struct Material {
///     vec3  base_color; uint kind;    // kind: material_kind
///     vec3  emission;   float alpha;  // GGX alpha
///     float ior; uint texture;        // base-colour texture
///     uint  flags;                    // material_flags
///     uint  metal_roughness;          // metallic-roughness texture (G roughness, B metal)
///     float metallic; uint normal_texture; float normal_scale; uint emissive_texture;
///     uint  occlusion_texture; float occlusion_strength; float opacity; float alpha_cutoff;
///     vec3  specular_f0; float specular_weight; // metallic-roughness's specular layer
/// };
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuMaterial {
    /// Albedo / metal colour / transmission tint.
    pub base_color: [f32; 3],
    /// See [`material_kind`].
    pub kind: u32,
    /// Emitted radiance.
    pub emission: [f32; 3],
    /// GGX alpha.
    pub alpha: f32,
    /// Index of refraction.
    pub ior: f32,
    /// Base-colour texture record or `u32::MAX`.
    pub texture: u32,
    /// See [`material_flags`].
    pub flags: u32,
    /// Metallic-roughness texture record or `u32::MAX`.
    pub metal_roughness: u32,
    /// Metallic factor (times the metallic-roughness texture's B).
    pub metallic: f32,
    /// Normal-map texture record or `u32::MAX`.
    pub normal_texture: u32,
    /// Normal-map scale.
    pub normal_scale: f32,
    /// Emissive texture record or `u32::MAX`.
    pub emissive_texture: u32,
    /// Occlusion texture record or `u32::MAX`.
    pub occlusion_texture: u32,
    /// Occlusion strength.
    pub occlusion_strength: f32,
    /// Base opacity (base colour alpha).
    pub opacity: f32,
    /// Alpha-mask cutoff.
    pub alpha_cutoff: f32,
    /// Metallic-roughness: the specular layer's reflectance at normal incidence.
    pub specular_f0: [f32; 3],
    /// Metallic-roughness: the specular layer's strength (`specularFactor`).
    pub specular_weight: f32,
}

/// Light kinds as stored in [`GpuLight::kind`].
pub mod light_kind {
    /// Emissive triangle.
    pub const TRIANGLE: u32 = 0;
    /// Emissive sphere.
    pub const SPHERE: u32 = 1;
    /// Point light (delta).
    pub const POINT: u32 = 2;
    /// Spot light (delta).
    pub const SPOT: u32 = 3;
}

/// One NEE light, 80 bytes.
/// ```glsl
/// struct Light {
///     uint kind;      // see light_kind
///     uint index;     // triangle: global triangle index; sphere: index in spheres
///     uint instance;  // triangle: index in instances; otherwise ~0u
///     uint material;  // triangle: its material (emissive textures, alpha); otherwise ~0u
///     vec4 p0;        // triangle: world v0, area | sphere: centre, radius | point/spot: position, 0
///     vec4 p1;        // triangle: world v1, emitting side (+1: winding normal, -1: opposite) | spot: unit direction, cos(outer angle)
///     vec4 p2;        // triangle: world v2 | spot: cos(inner angle), 0, 0, 0
///     vec4 emission;  // rgb radiance (area) or intensity (W/sr, delta); w = power
/// };
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuLight {
    /// See [`light_kind`].
    pub kind: u32,
    /// Primitive index (see the GLSL comment).
    pub index: u32,
    /// Instance index for triangles.
    pub instance: u32,
    /// Material of a triangle (`u32::MAX` otherwise).
    pub material: u32,
    /// First geometry vector.
    pub p0: [f32; 4],
    /// Second geometry vector.
    pub p1: [f32; 4],
    /// Third geometry vector.
    pub p2: [f32; 4],
    /// Emission (rgb) and power (w).
    pub emission: [f32; 4],
}

/// One column of the light alias table with the pdf and CDF, 16 bytes.
/// ```glsl
/// struct LightSample { float threshold; uint alias; float pdf; float cdf; };
/// ```
/// Sampling: `i = min(uint(u * n), n - 1)`, keep `i` if
/// `fract(u * n) < threshold`, else take `alias`; the chosen light's
/// selection probability is its `pdf`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuAliasEntry {
    /// Probability of keeping this column.
    pub threshold: f32,
    /// Alternative light index.
    pub alias: u32,
    /// Selection probability of light `i`.
    pub pdf: f32,
    /// Inclusive CDF up to light `i`.
    pub cdf: f32,
}

/// Texture formats as stored in [`GpuTextureRecord::format`].
pub mod texture_format {
    /// One `u32` per texel, RGBA8 sRGB: alpha by `unpackUnorm4x8`, the colour's bytes decoded
    /// through the table the texel buffer then opens with (the linear value of each of the 256
    /// codes as `f32` bits).
    pub const RGBA8_SRGB: u32 = 0;
    /// One `u32` per texel, RGBA8 linear.
    pub const RGBA8_LINEAR: u32 = 1;
    /// Four `u32` per texel holding `f32` bits (`uintBitsToFloat`).
    pub const RGBA32F: u32 = 2;
}

/// A texture as one material slot samples it, 48 bytes: where its texels live, its texture
/// coordinate transform and its wrap modes.
/// ```glsl
/// struct TextureRecord {
///     uint offset; uint width; uint height; uint format;
///     vec4 u_row; // u' = dot(u_row.xyz, vec3(uv, 1)); w: wrap mode along u (WrapMode::code)
///     vec4 v_row; // v' = dot(v_row.xyz, vec3(uv, 1)); w: wrap mode along v
/// };
/// ```
/// `offset` counts `u32` words; texel `(x, y)` starts at
/// `offset + (y * width + x) * words_per_texel`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuTextureRecord {
    /// First word in the texel buffer.
    pub offset: u32,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// See [`texture_format`].
    pub format: u32,
    /// First row of the coordinate transform, and the wrap mode along u.
    pub u_row: [f32; 4],
    /// Second row of the coordinate transform, and the wrap mode along v.
    pub v_row: [f32; 4],
}

/// Camera parameters, 64 bytes.
/// ```glsl
/// struct Camera {
///     vec4 position_aperture; // eye, aperture radius (0 = pinhole)
///     vec4 right_focus;       // unit right, focus distance
///     vec4 up_tan_half_fov;   // unit up, tan(vfov / 2)
///     vec4 forward;           // unit view direction, 0
/// };
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuCamera {
    /// Eye position and aperture radius.
    pub position_aperture: [f32; 4],
    /// Right vector and focus distance.
    pub right_focus: [f32; 4],
    /// Up vector and tangent of half the vertical FOV.
    pub up_tan_half_fov: [f32; 4],
    /// View direction.
    pub forward: [f32; 4],
}

/// Environment parameters, 64 bytes.
/// ```glsl
/// struct Environment {
///     uint kind; uint pad0, pad1, pad2; // 0 = constant (zenith), 1 = sky
///     vec4 zenith; vec4 horizon; vec4 ground;
/// };
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuEnvironment {
    /// 0 = constant radiance `zenith`, 1 = sky gradient.
    pub kind: u32,
    /// Padding.
    pub pad: [u32; 3],
    /// Zenith (or constant) radiance.
    pub zenith: [f32; 4],
    /// Horizon radiance.
    pub horizon: [f32; 4],
    /// Ground radiance.
    pub ground: [f32; 4],
}

/// Sun parameters, 32 bytes.
/// ```glsl
/// struct Sun { vec4 direction_cos; vec4 radiance_enabled; };
/// ```
/// `direction_cos`: unit direction to the sun, cosine of its angular
/// radius. `radiance_enabled`: disc radiance, 1 if a sun exists else 0.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuSun {
    /// Direction to the sun and cos(angular radius).
    pub direction_cos: [f32; 4],
    /// Radiance and an enabled flag.
    pub radiance_enabled: [f32; 4],
}

/// Per-scene constants, 240 bytes (valid as std140 and std430).
/// ```glsl
/// struct SceneParams {
///     Camera camera; Environment environment; Sun sun;
///     uvec4 counts0;  // triangles, instances, spheres, lights
///     uvec4 counts1;  // materials, textures, tlas root word, blas nodes
///     vec4  light;    // total NEE light power, uniform selection, power scale, 0
///     vec4  bounds_min; // a box around the whole scene, a little larger (xyz)
///     vec4  bounds_max;
/// };
/// ```
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct GpuSceneParams {
    /// Camera.
    pub camera: GpuCamera,
    /// Environment.
    pub environment: GpuEnvironment,
    /// Sun.
    pub sun: GpuSun,
    /// Triangles, instances, spheres, lights.
    pub counts0: [u32; 4],
    /// Materials, textures, the TLAS root ([`super::PackedTree::root`]; `u32::MAX` without instances),
    /// BLAS nodes.
    pub counts1: [u32; 4],
    /// Total power of the light table (x), and the selection constants `uniform` (y) and
    /// `power_scale` (z) of [`crate::scene::Selection`]: a BSDF-sampled hit on an emitter has
    /// selection probability `power * power_scale + uniform`, with power computed as in
    /// `LightDistribution`, so no reverse lookup is needed.
    pub light: [f32; 4],
    /// The smallest corner of a box around everything rays can hit, a little larger than the
    /// top level's (xyz; w 0): shadow rays towards the sun and the environment map are walked from
    /// where they leave it.
    pub bounds_min: [f32; 4],
    /// The largest corner of that box (xyz; w 0).
    pub bounds_max: [f32; 4],
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::mem::size_of;

    #[test]
    fn sizes_match_documented_std430_layouts() {
        assert_eq!(size_of::<GpuVertex>(), 20);
        assert_eq!(size_of::<GpuInstance>(), 112);
        assert_eq!(size_of::<GpuSphere>(), 32);
        assert_eq!(size_of::<GpuMaterial>(), 96);
        assert_eq!(size_of::<GpuLight>(), 80);
        assert_eq!(size_of::<GpuAliasEntry>(), 16);
        assert_eq!(size_of::<GpuTextureRecord>(), 48);
        assert_eq!(size_of::<GpuCamera>(), 64);
        assert_eq!(size_of::<GpuEnvironment>(), 64);
        assert_eq!(size_of::<GpuSun>(), 32);
        assert_eq!(size_of::<GpuSceneParams>(), 240);
    }
}
