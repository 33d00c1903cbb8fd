//! The scene container.

use glam::{Affine3A, Vec3};

use super::{
    Camera, CameraPath, Environment, Instance, Material, MaterialKind, Mesh, PunctualLight,
    SceneError, SceneFeatures, Sphere, Sun, Texture,
};
use crate::bvh::Aabb;

/// A complete scene description: geometry, materials, lights and camera.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Scene name (built-in name or file name).
    pub name: String,
    /// Triangle meshes in object space.
    pub meshes: Vec<Mesh>,
    /// Placements of meshes (one mesh may be instanced many times).
    pub instances: Vec<Instance>,
    /// Analytic spheres in world space.
    pub spheres: Vec<Sphere>,
    /// Materials referenced by meshes, instances and spheres.
    pub materials: Vec<Material>,
    /// Base-colour textures referenced by materials.
    pub textures: Vec<Texture>,
    /// Point and spot lights.
    pub punctual_lights: Vec<PunctualLight>,
    /// Optional directional sun.
    pub sun: Option<Sun>,
    /// Environment light (black for none).
    pub environment: Environment,
    /// Default camera.
    pub camera: Camera,
    /// Default camera animation, if any.
    pub camera_path: Option<CameraPath>,
    /// Non-fatal problems found while building or importing (for example
    /// clamped material parameters or a scene without any light).
    pub warnings: Vec<String>,
    /// What an importer supplied because the input lacked it (a default camera or sky), for the
    /// user to know why the image looks as it does.
    pub notes: Vec<String>,
}

/// Closed-form pixel values of a furnace-like scene (see
/// [`Scene::analytic_radiance`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnalyticRadiance {
    /// Radiance of pixels that see the environment.
    pub background: Vec3,
    /// Radiance of pixels that see the object.
    pub object: Vec3,
}

impl Scene {
    /// An empty scene with a black environment and a camera at the origin
    /// looking down `-Z`.
    pub fn new(name: &str) -> Self {
        Self {
            name: name.to_owned(),
            meshes: Vec::new(),
            instances: Vec::new(),
            spheres: Vec::new(),
            materials: Vec::new(),
            textures: Vec::new(),
            punctual_lights: Vec::new(),
            sun: None,
            environment: Environment::Constant(Vec3::ZERO),
            camera: Camera::look_at(Vec3::ZERO, Vec3::NEG_Z, Vec3::Y, 45.0),
            camera_path: None,
            warnings: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// Adds a material and returns its index.
    pub fn add_material(&mut self, m: Material) -> u32 {
        self.materials.push(m);
        (self.materials.len() - 1) as u32
    }

    /// Adds a texture and returns its index.
    pub fn add_texture(&mut self, t: Texture) -> u32 {
        self.textures.push(t);
        (self.textures.len() - 1) as u32
    }

    /// Lights the scene with an equirectangular environment map ([`super::environment_map::load`]
    /// reads one) in place of its environment; returns the map's texture index.
    pub fn set_environment_map(&mut self, map: Texture) -> u32 {
        let texture = self.add_texture(map);
        self.environment = Environment::Map { texture };
        texture
    }

    /// Lights the scene with the equirectangular map in `path` (`.hdr` or `.exr`), saying so in
    /// [`Scene::notes`] (in place of a note that a default sky lights it).
    pub fn light_with_environment_file(
        &mut self,
        path: &std::path::Path,
    ) -> Result<(), SceneError> {
        let map = super::environment_map::load(path)?;
        self.set_environment_map(map);
        self.notes.retain(|n| !n.contains("default sky"));
        self.notes.push(format!(
            "{} lights the scene (an equirectangular environment map)",
            path.display()
        ));
        Ok(())
    }

    /// Adds a mesh (without instancing it) and returns its index.
    pub fn add_mesh(&mut self, m: Mesh) -> u32 {
        self.meshes.push(m);
        (self.meshes.len() - 1) as u32
    }

    /// Places mesh `mesh` with `transform`, optionally overriding its
    /// material, and returns the instance index.
    pub fn add_instance(&mut self, mesh: u32, transform: Affine3A, material: Option<u32>) -> u32 {
        let name = format!(
            "{}#{}",
            self.meshes[mesh as usize].name,
            self.instances.len()
        );
        self.instances.push(Instance {
            name,
            mesh,
            transform,
            material,
        });
        (self.instances.len() - 1) as u32
    }

    /// Adds a mesh and one identity instance of it; returns the mesh index.
    pub fn add_mesh_instance(&mut self, m: Mesh) -> u32 {
        let id = self.add_mesh(m);
        self.add_instance(id, Affine3A::IDENTITY, None);
        id
    }

    /// Adds an analytic sphere and returns its index.
    pub fn add_sphere(&mut self, center: Vec3, radius: f32, material: u32) -> u32 {
        self.spheres.push(Sphere {
            center,
            radius,
            material,
        });
        (self.spheres.len() - 1) as u32
    }

    /// The material used by instance `i` (its override or the mesh's).
    pub fn instance_material(&self, i: usize) -> u32 {
        let inst = &self.instances[i];
        inst.material
            .unwrap_or(self.meshes[inst.mesh as usize].material)
    }

    /// Total number of triangles after instancing.
    pub fn triangle_count(&self) -> usize {
        self.instances
            .iter()
            .map(|i| self.meshes[i.mesh as usize].triangle_count())
            .sum()
    }

    /// Number of stored (unique) triangles.
    pub fn unique_triangle_count(&self) -> usize {
        self.meshes.iter().map(Mesh::triangle_count).sum()
    }

    /// World bounds of all instances and spheres.
    pub fn bounds(&self) -> Aabb {
        let meshes: Vec<Aabb> = self.meshes.iter().map(Mesh::bounds).collect();
        let inst = self
            .instances
            .iter()
            .map(|i| meshes[i.mesh as usize].transformed(&i.transform));
        let spheres = self
            .spheres
            .iter()
            .map(|s| Aabb::new(s.center - s.radius, s.center + s.radius));
        inst.chain(spheres).fold(Aabb::EMPTY, Aabb::union)
    }

    /// Whether anything emits light: emissive geometry that is actually
    /// placed, punctual lights, a sun or a non-black environment.
    pub fn has_light(&self) -> bool {
        let emissive = |m: u32| {
            self.materials
                .get(m as usize)
                .is_some_and(Material::is_emissive)
        };
        (0..self.instances.len()).any(|i| emissive(self.instance_material(i)))
            || self.spheres.iter().any(|s| emissive(s.material))
            || !self.punctual_lights.is_empty()
            || self.sun.is_some()
            || !self.environment.is_black()
    }

    /// The rendering features this scene needs.
    pub fn features(&self) -> SceneFeatures {
        SceneFeatures::from_scene(self)
    }

    /// Validates the whole scene: material ranges (clamping with a warning
    /// or rejecting, see [`Material::sanitize`]), meshes, textures, all
    /// cross references, spheres, lights and camera. Adds a warning if the
    /// scene has no light at all.
    pub fn validate(&mut self) -> Result<(), SceneError> {
        let invalid = |m: String| Err(SceneError::Invalid(m));
        for m in &mut self.materials {
            let w = m.sanitize()?;
            self.warnings.extend(w);
        }
        for m in &self.materials {
            for t in m.textures().map(|t| t.texture) {
                if t as usize >= self.textures.len() {
                    return invalid(format!("material `{}` uses missing texture {t}", m.name));
                }
            }
        }
        for t in &self.textures {
            t.validate()?;
        }
        if let Environment::Map { texture } = self.environment {
            if texture as usize >= self.textures.len() {
                return invalid(format!("the environment map is missing texture {texture}"));
            }
        }
        let limit = crate::scene::gpu::bvh_pack::MAX_PRIMITIVES as usize;
        let counts = [
            ("triangles", self.triangle_count()),
            ("spheres", self.spheres.len()),
            ("instances", self.instances.len()),
        ];
        if let Some((what, n)) = counts.iter().find(|(_, n)| *n >= limit) {
            return invalid(format!(
                "{n} {what}: the GPU layout indexes fewer than {limit}"
            ));
        }
        let nm = self.materials.len();
        for m in &self.meshes {
            m.validate()?;
            if m.material as usize >= nm {
                return invalid(format!(
                    "mesh `{}` uses missing material {}",
                    m.name, m.material
                ));
            }
        }
        for i in &self.instances {
            if i.mesh as usize >= self.meshes.len() {
                return invalid(format!(
                    "instance `{}` uses missing mesh {}",
                    i.name, i.mesh
                ));
            }
            if i.material.is_some_and(|m| m as usize >= nm) {
                return invalid(format!("instance `{}` uses a missing material", i.name));
            }
            if !i.transform.is_finite() || i.transform.matrix3.determinant() == 0.0 {
                return invalid(format!(
                    "instance `{}` has a singular or non-finite transform",
                    i.name
                ));
            }
        }
        for (k, s) in self.spheres.iter().enumerate() {
            if !(s.center.is_finite() && s.radius.is_finite() && s.radius > 0.0) {
                return invalid(format!(
                    "sphere {k} needs a finite centre and positive radius"
                ));
            }
            if s.material as usize >= nm {
                return invalid(format!("sphere {k} uses missing material {}", s.material));
            }
        }
        for (k, l) in self.punctual_lights.iter().enumerate() {
            let ok = match *l {
                PunctualLight::Point {
                    position,
                    intensity,
                } => {
                    position.is_finite() && intensity.is_finite() && intensity.min_element() >= 0.0
                }
                PunctualLight::Spot {
                    position,
                    direction,
                    intensity,
                    inner_angle,
                    outer_angle,
                } => {
                    position.is_finite()
                        && direction.is_normalized()
                        && intensity.is_finite()
                        && intensity.min_element() >= 0.0
                        && (0.0..=outer_angle).contains(&inner_angle)
                        && outer_angle <= std::f32::consts::FRAC_PI_2
                }
            };
            if !ok {
                return invalid(format!("punctual light {k} has out-of-range parameters"));
            }
        }
        if let Some(s) = &self.sun {
            let ok = s.direction.is_normalized()
                && s.irradiance.is_finite()
                && s.irradiance.min_element() >= 0.0
                && s.angular_radius > 0.0
                && s.angular_radius < 0.5;
            if !ok {
                return invalid("sun has out-of-range parameters".into());
            }
        }
        let c = &self.camera;
        if !(c.position.is_finite()
            && c.orientation.is_finite()
            && c.vfov > 0.0
            && c.vfov < std::f32::consts::PI)
        {
            return invalid("camera has out-of-range parameters".into());
        }
        if !self.has_light() {
            self.warnings.push(format!(
                "scene `{}` has no light: it will render black",
                self.name
            ));
        }
        Ok(())
    }

    /// A 64-bit FNV-1a hash over all geometry, materials, textures, lights
    /// and the camera; equal for scenes built identically.
    pub fn content_hash(&self) -> u64 {
        let mut h = Fnv::default();
        h.str(&self.name);
        for m in &self.meshes {
            h.str(&m.name);
            h.bytes(bytemuck::cast_slice(&m.positions));
            h.bytes(bytemuck::cast_slice(&m.normals));
            h.bytes(bytemuck::cast_slice(&m.uvs));
            h.bytes(bytemuck::cast_slice(&m.colors));
            h.bytes(bytemuck::cast_slice(&m.alphas));
            h.bytes(bytemuck::cast_slice(&m.tangents));
            h.bytes(bytemuck::cast_slice(&m.indices));
            h.u32(m.material);
        }
        for i in &self.instances {
            h.u32(i.mesh);
            h.bytes(bytemuck::cast_slice(&i.transform.to_cols_array()));
            h.u32(i.material.map_or(u32::MAX, |m| m));
        }
        for s in &self.spheres {
            h.bytes(bytemuck::cast_slice(&[
                s.center.x, s.center.y, s.center.z, s.radius,
            ]));
            h.u32(s.material);
        }
        for m in &self.materials {
            h.str(&m.name);
            h.str(&format!("{:?}", m.kind));
            h.bytes(bytemuck::cast_slice(&[m.base_color, m.emission]));
            h.bytes(bytemuck::cast_slice(&[m.alpha, m.ior]));
            h.str(&format!(
                "{:?} {:?} {:?} {:?} {:?} {:?}",
                m.base_color_texture,
                m.metallic_roughness_texture,
                m.emissive_texture,
                m.normal_texture,
                m.occlusion_texture,
                m.alpha_mode
            ));
            h.bytes(bytemuck::cast_slice(&[
                m.metallic,
                m.normal_scale,
                m.occlusion_strength,
                m.opacity,
            ]));
        }
        for t in &self.textures {
            h.u32(t.width);
            h.u32(t.height);
            match &t.texels {
                super::TexelData::Rgba8(d) => h.bytes(bytemuck::cast_slice(d)),
                super::TexelData::RgbaF32(d) => h.bytes(bytemuck::cast_slice(d)),
            }
        }
        h.str(&format!(
            "{:?}{:?}{:?}{:?}",
            self.punctual_lights, self.sun, self.environment, self.camera
        ));
        h.0
    }

    /// Closed-form radiance for a white-furnace configuration: exactly one
    /// non-emissive, untextured Lambertian sphere of albedo `a` and nothing
    /// else but a constant environment `L`. Then every pixel seeing the
    /// environment is `L`, and every pixel seeing the sphere is `a · L`:
    /// outgoing radiance is `∫ (a/π) L cosθ dω = a L`, and because a
    /// sphere is convex every scattered ray escapes straight to the
    /// environment, so indirect bounces add nothing. Returns `None` for any
    /// other scene.
    pub fn analytic_radiance(&self) -> Option<AnalyticRadiance> {
        let Environment::Constant(l) = self.environment else {
            return None;
        };
        let [s] = self.spheres.as_slice() else {
            return None;
        };
        let m = self.materials.get(s.material as usize)?;
        let plain = self.instances.is_empty()
            && self.punctual_lights.is_empty()
            && self.sun.is_none()
            && m.kind == MaterialKind::Diffuse
            && !m.is_emissive()
            && m.base_color_texture.is_none();
        plain.then_some(AnalyticRadiance {
            background: l,
            object: m.base_color * l,
        })
    }
}

/// 64-bit FNV-1a.
struct Fnv(u64);

impl Default for Fnv {
    fn default() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
}

impl Fnv {
    fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 = (self.0 ^ x as u64).wrapping_mul(0x0100_0000_01b3);
        }
        self.u32(b.len() as u32);
    }

    fn u32(&mut self, v: u32) {
        for x in v.to_le_bytes() {
            self.0 = (self.0 ^ x as u64).wrapping_mul(0x0100_0000_01b3);
        }
    }

    fn str(&mut self, s: &str) {
        self.bytes(s.as_bytes());
    }
}
