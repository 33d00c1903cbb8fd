//! Packs materials, textures, lights, camera, environment and sun.

use super::layout::{
    light_kind, material_flags, material_kind, texture_format, GpuAliasEntry, GpuCamera,
    GpuEnvironment, GpuLight, GpuMaterial, GpuSun, GpuTextureRecord,
};
use crate::scene::{
    AliasTable, AlphaMode, Camera, Environment, EnvironmentDistribution, Instance,
    LightDistribution, LightSource, MaterialKind, Mesh, PunctualLight, Scene, Sun, TexelData,
    Texture, TextureRef, WrapMode,
};
use glam::{Vec3, Vec3A};

/// Converts the scene materials; each texture a material uses gets its own record (the texels
/// of scene texture `t` are at `images[t]`, with that slot's transform and wrap modes). Returns
/// the materials and the records they index, an environment map's record last (repeating
/// around, clamped at the poles) with its index (`u32::MAX` without a map).
pub fn materials(
    scene: &Scene,
    images: &[GpuTextureRecord],
) -> (Vec<GpuMaterial>, Vec<GpuTextureRecord>, u32) {
    let mut records = Vec::new();
    let mut record = |slot: Option<TextureRef>| {
        let Some(slot) = slot else {
            return u32::MAX;
        };
        let [u, v] = slot.transform.rows();
        let code = |w: crate::scene::WrapMode| w.code() as f32;
        records.push(GpuTextureRecord {
            u_row: [u[0], u[1], u[2], code(slot.wrap[0])],
            v_row: [v[0], v[1], v[2], code(slot.wrap[1])],
            ..images[slot.texture as usize]
        });
        (records.len() - 1) as u32
    };
    let materials = scene
        .materials
        .iter()
        .map(|m| {
            let (alpha_flag, alpha_cutoff) = match m.alpha_mode {
                AlphaMode::Opaque => (0, 0.0),
                AlphaMode::Mask { cutoff } => (material_flags::ALPHA_MASK, cutoff),
                AlphaMode::Blend => (material_flags::ALPHA_BLEND, 0.0),
            };
            let smooth = m.alpha < crate::scene::SMOOTH_ALPHA;
            GpuMaterial {
                base_color: m.base_color.to_array(),
                kind: match m.kind {
                    MaterialKind::Diffuse => material_kind::DIFFUSE,
                    MaterialKind::Conductor => material_kind::CONDUCTOR,
                    MaterialKind::Dielectric => material_kind::DIELECTRIC,
                    MaterialKind::MetalRough => material_kind::METAL_ROUGH,
                },
                emission: m.emission.to_array(),
                alpha: m.alpha,
                ior: m.ior,
                texture: record(m.base_color_texture),
                flags: if m.is_emissive() {
                    material_flags::EMISSIVE
                } else {
                    0
                } | if smooth { material_flags::SMOOTH } else { 0 }
                    | alpha_flag,
                metal_roughness: record(m.metallic_roughness_texture),
                metallic: m.metallic,
                normal_texture: record(m.normal_texture),
                normal_scale: m.normal_scale,
                emissive_texture: record(m.emissive_texture),
                occlusion_texture: record(m.occlusion_texture),
                occlusion_strength: m.occlusion_strength,
                opacity: m.opacity,
                alpha_cutoff,
                specular_f0: m.specular_f0().to_array(),
                specular_weight: m.specular,
            }
        })
        .collect();
    let environment = match scene.environment {
        Environment::Map { texture } => record(Some(TextureRef {
            wrap: [WrapMode::Repeat, WrapMode::ClampToEdge],
            ..TextureRef::new(texture)
        })),
        _ => u32::MAX,
    };
    (materials, records, environment)
}

/// Flattens all textures into one texel buffer, each with its mip levels after level 0
/// ([`crate::scene::Texture::mip_levels`]); returns it and where each texture's texels are
/// (records with an identity transform, repeating). When a texture is stored as sRGB, the buffer
/// opens with [`srgb_table`].
pub fn textures(scene: &Scene) -> (Vec<u32>, Vec<GpuTextureRecord>) {
    let srgb = scene
        .textures
        .iter()
        .any(|t| format_of(t) == texture_format::RGBA8_SRGB);
    let mut texels = if srgb { srgb_table() } else { Vec::new() };
    let mut records = Vec::with_capacity(scene.textures.len());
    let push = |data: &TexelData, texels: &mut Vec<u32>| match data {
        TexelData::Rgba8(d) => texels.extend(d.iter().map(|&p| u32::from_le_bytes(p))),
        TexelData::RgbaF32(d) => texels.extend(d.iter().flatten().map(|f| f.to_bits())),
    };
    for t in &scene.textures {
        let offset = texels.len() as u32;
        let format = format_of(t);
        push(&t.texels, &mut texels);
        for level in t.mip_levels() {
            push(&level, &mut texels);
        }
        records.push(GpuTextureRecord {
            offset,
            width: t.width,
            height: t.height,
            format,
            u_row: [1.0, 0.0, 0.0, 0.0],
            v_row: [0.0, 1.0, 0.0, 0.0],
        });
    }
    (texels, records)
}

/// How the GPU reads texture `t`'s texels ([`texture_format`]).
fn format_of(t: &Texture) -> u32 {
    match &t.texels {
        TexelData::Rgba8(_) if t.srgb => texture_format::RGBA8_SRGB,
        TexelData::Rgba8(_) => texture_format::RGBA8_LINEAR,
        TexelData::RgbaF32(_) => texture_format::RGBA32F,
    }
}

/// The linear value of each 8-bit sRGB code as `f32` bits: the shaders decode an sRGB texel's
/// colour channels by reading this table at its bytes (texel words 0-255 of the buffer), the same
/// decoding as [`crate::capture::srgb_decode`] and cheaper than its power on the GPU.
pub fn srgb_table() -> Vec<u32> {
    (0..=u8::MAX)
        .map(|code| crate::capture::srgb_decode(f32::from(code) / 255.0).to_bits())
        .collect()
}

/// Index remappings from scene order to GPU order needed by the lights.
pub struct LightRemap<'a> {
    /// GPU instance index of each scene instance (`u32::MAX` if culled).
    pub instance: &'a [u32],
    /// Global GPU triangle index of `(scene instance, triangle of its mesh)`.
    pub triangle: &'a dyn Fn(u32, u32) -> u32,
    /// GPU sphere index of each scene sphere.
    pub sphere: &'a [u32],
}

/// Converts the light distribution into GPU lights and the alias table.
pub fn lights(
    scene: &Scene,
    dist: &LightDistribution,
    remap: &LightRemap,
) -> (Vec<GpuLight>, Vec<GpuAliasEntry>) {
    let lights = dist
        .entries
        .iter()
        .map(|e| {
            let emission = e.emission.extend(e.power).to_array();
            match e.source {
                LightSource::Triangle { instance, triangle } => {
                    let inst = &scene.instances[instance as usize];
                    let mesh = &scene.meshes[inst.mesh as usize];
                    let [a, b, c] = mesh
                        .triangle(triangle as usize)
                        .map(|p| inst.transform.transform_point3(p));
                    let geometric = (b - a).cross(c - a);
                    let area = 0.5 * geometric.length();
                    GpuLight {
                        kind: light_kind::TRIANGLE,
                        index: (remap.triangle)(instance, triangle),
                        instance: remap.instance[instance as usize],
                        material: scene.instance_material(instance as usize),
                        p0: a.extend(area).to_array(),
                        p1: b
                            .extend(emitting_side(mesh, inst, triangle, geometric))
                            .to_array(),
                        p2: c.extend(0.0).to_array(),
                        emission,
                    }
                }
                LightSource::Sphere { sphere } => {
                    let s = &scene.spheres[sphere as usize];
                    GpuLight {
                        kind: light_kind::SPHERE,
                        index: remap.sphere[sphere as usize],
                        instance: u32::MAX,
                        material: u32::MAX,
                        p0: s.center.extend(s.radius).to_array(),
                        emission,
                        ..Default::default()
                    }
                }
                LightSource::Punctual { light } => match scene.punctual_lights[light as usize] {
                    PunctualLight::Point { position, .. } => GpuLight {
                        kind: light_kind::POINT,
                        index: light,
                        instance: u32::MAX,
                        material: u32::MAX,
                        p0: position.extend(0.0).to_array(),
                        emission,
                        ..Default::default()
                    },
                    PunctualLight::Spot {
                        position,
                        direction,
                        inner_angle,
                        outer_angle,
                        ..
                    } => GpuLight {
                        kind: light_kind::SPOT,
                        index: light,
                        instance: u32::MAX,
                        material: u32::MAX,
                        p0: position.extend(0.0).to_array(),
                        p1: direction.extend(outer_angle.cos()).to_array(),
                        p2: [inner_angle.cos(), 0.0, 0.0, 0.0],
                        emission,
                    },
                },
            }
        })
        .collect();
    let table = alias_entries(&dist.table, 0);
    (lights, table)
}

/// +1 when the emitting (front) side of a triangle is that of its winding normal `geometric`
/// (world space), -1 otherwise: the front is the side its shading normals point to.
fn emitting_side(mesh: &Mesh, inst: &Instance, triangle: u32, geometric: Vec3) -> f32 {
    let Some(idx) = mesh.indices.get(triangle as usize) else {
        return 1.0;
    };
    let normal = |i: u32| mesh.normals.get(i as usize).copied().unwrap_or(Vec3::ZERO);
    let shading = normal(idx.x) + normal(idx.y) + normal(idx.z);
    let world = inst.transform.matrix3.inverse().transpose() * Vec3A::from(shading);
    if Vec3::from(world).dot(geometric) < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// Converts the camera.
pub fn camera(c: &Camera) -> GpuCamera {
    GpuCamera {
        position_aperture: c.position.extend(c.aperture_radius).to_array(),
        right_focus: c.right().extend(c.focus_distance).to_array(),
        up_tan_half_fov: c.up().extend((0.5 * c.vfov).tan()).to_array(),
        forward: c.forward().extend(0.0).to_array(),
    }
}

/// Converts the environment; a map's texture record is `record`, its distribution's cells
/// `cells` (across, down).
pub fn environment(e: &Environment, record: u32, cells: [u32; 2]) -> GpuEnvironment {
    match *e {
        Environment::Constant(c) => GpuEnvironment {
            kind: 0,
            zenith: c.extend(0.0).to_array(),
            horizon: c.extend(0.0).to_array(),
            ground: c.extend(0.0).to_array(),
            ..Default::default()
        },
        Environment::Sky {
            zenith,
            horizon,
            ground,
        } => GpuEnvironment {
            kind: 1,
            zenith: zenith.extend(0.0).to_array(),
            horizon: horizon.extend(0.0).to_array(),
            ground: ground.extend(0.0).to_array(),
            ..Default::default()
        },
        Environment::Map { .. } => GpuEnvironment {
            kind: 2,
            pad: [record, cells[0], cells[1]],
            ..Default::default()
        },
    }
}

/// The alias table of an environment map's distribution, its aliases offset by `offset` (where
/// it starts in the light table).
pub fn environment_table(dist: &EnvironmentDistribution, offset: u32) -> Vec<GpuAliasEntry> {
    alias_entries(&dist.table, offset)
}

/// `table` as GPU entries, its aliases offset by `offset` (where it starts in its buffer).
fn alias_entries(table: &AliasTable, offset: u32) -> Vec<GpuAliasEntry> {
    table
        .entries
        .iter()
        .zip(&table.pdf)
        .zip(&table.cdf)
        .map(|((e, &pdf), &cdf)| GpuAliasEntry {
            threshold: e.threshold,
            alias: e.alias + offset,
            pdf,
            cdf,
        })
        .collect()
}

/// Converts the optional sun.
pub fn sun(s: Option<&Sun>) -> GpuSun {
    s.map_or_else(GpuSun::default, |s| GpuSun {
        direction_cos: s.direction.extend(s.angular_radius.cos()).to_array(),
        radiance_enabled: s.radiance().extend(1.0).to_array(),
    })
}
