//! Node hierarchy traversal: mesh instances with world transforms,
//! cameras and `KHR_lights_punctual` lights.

use std::collections::HashMap;

use glam::{Affine3A, Mat4, Vec3};
use gltf::camera::Projection;
use gltf::json::extensions::scene::khr_lights_punctual::Type as LightType;
use gltf::json::validation::Checked;
use gltf::{Document, Node};

use super::materials::MaterialImporter;
use super::meshes::{self, MAX_COORDINATE};
use super::unsupported::{Feature, Unsupported};
use crate::scene::{Camera, PunctualLight, Scene, Sun, LUMENS_PER_WATT};

/// Walks one glTF scene into a Lucid scene.
pub struct NodeImporter<'a> {
    /// The document.
    pub doc: &'a Document,
    /// Loaded buffers.
    pub buffers: &'a [Vec<u8>],
    /// Material conversion (shared so images decode once).
    pub materials: MaterialImporter<'a>,
    /// Scene mesh ids of each `(mesh, primitive)` already converted.
    pub mesh_cache: HashMap<(usize, usize), Option<u32>>,
    /// Scene material id of each glTF material (`None` = default).
    pub material_cache: HashMap<Option<usize>, u32>,
    /// Whether a camera was found.
    pub camera_found: bool,
    /// What the file uses that is not rendered.
    pub unsupported: Unsupported,
}

impl NodeImporter<'_> {
    /// Visits the roots of a scene depth first (iteratively). A node that
    /// is reached twice (a cycle or a shared child) is an error.
    pub fn walk(&mut self, scene: &mut Scene, roots: Vec<Node>) -> Result<(), String> {
        let mut seen = vec![false; self.doc.nodes().len()];
        let mut stack: Vec<(Node, Mat4)> = roots
            .into_iter()
            .rev()
            .map(|n| (n, Mat4::IDENTITY))
            .collect();
        while let Some((node, parent)) = stack.pop() {
            let i = node.index();
            if std::mem::replace(&mut seen[i], true) {
                return Err(format!(
                    "node {i} is reached twice: the node hierarchy has a cycle or a shared node"
                ));
            }
            let local = Mat4::from_cols_array_2d(&node.transform().matrix());
            let world = parent * local;
            if !world.is_finite() {
                return Err(format!("node {i}: transform is not finite"));
            }
            self.visit(scene, &node, &world)?;
            stack.extend(
                node.children()
                    .map(|c| (c, world))
                    .collect::<Vec<_>>()
                    .into_iter()
                    .rev(),
            );
        }
        Ok(())
    }

    fn visit(&mut self, scene: &mut Scene, node: &Node, world: &Mat4) -> Result<(), String> {
        let i = node.index();
        if node.skin().is_some() {
            self.unsupported
                .note(Feature::Skins, "nodes", || format!("node {i}"));
        }
        if let Some(mesh) = node.mesh() {
            let affine = Affine3A::from_mat4(*world);
            if affine.matrix3.determinant().abs() < 1e-30 {
                return Err(format!("node {i}: transform is singular"));
            }
            for prim in mesh.primitives() {
                let key = (mesh.index(), prim.index());
                let id = match self.mesh_cache.get(&key) {
                    Some(&id) => id,
                    None => {
                        let material = self.material(scene, prim.material().index())?;
                        let id = meshes::primitive(
                            scene,
                            (&mesh, &prim),
                            self.buffers,
                            material,
                            &mut self.unsupported,
                        )?;
                        self.mesh_cache.insert(key, id);
                        id
                    }
                };
                if let Some(id) = id {
                    check_world_extent(scene, node, id, &affine)?;
                    scene.add_instance(id, affine, None);
                }
            }
        }
        if let Some(cam) = node.camera() {
            match cam.projection() {
                Projection::Perspective(p) if !self.camera_found => {
                    let (_, rotation, position) = world.to_scale_rotation_translation();
                    let vfov = p.yfov();
                    if !(vfov > 0.0 && vfov < std::f32::consts::PI && rotation.is_finite()) {
                        return Err(format!(
                            "camera {}: field of view {vfov} rad is out of range",
                            cam.index()
                        ));
                    }
                    scene.camera = Camera {
                        position,
                        orientation: rotation.normalize(),
                        vfov,
                        aperture_radius: 0.0,
                        focus_distance: 1.0,
                    };
                    self.camera_found = true;
                }
                Projection::Perspective(_) => {}
                Projection::Orthographic(_) => {
                    self.unsupported
                        .note(Feature::OrthographicCamera, "cameras", || {
                            format!("camera {}", cam.index())
                        })
                }
            }
        }
        self.light(scene, i, world)
    }

    fn material(&mut self, scene: &mut Scene, index: Option<usize>) -> Result<u32, String> {
        if let Some(&m) = self.material_cache.get(&index) {
            return Ok(m);
        }
        let id = match index {
            Some(k) => self.materials.import(scene, k, &mut self.unsupported)?,
            None => {
                scene.add_material(crate::scene::Material::diffuse("default", Vec3::splat(0.8)))
            }
        };
        self.material_cache.insert(index, id);
        Ok(id)
    }

    fn light(&mut self, scene: &mut Scene, node: usize, world: &Mat4) -> Result<(), String> {
        let json = self.doc.as_json();
        let Some(index) = json.nodes[node]
            .extensions
            .as_ref()
            .and_then(|e| e.khr_lights_punctual.as_ref())
            .map(|l| l.light.value())
        else {
            return Ok(());
        };
        let light = json
            .extensions
            .as_ref()
            .and_then(|e| e.khr_lights_punctual.as_ref())
            .and_then(|l| l.lights.get(index))
            .ok_or_else(|| format!("node {node}: light {index} does not exist"))?;
        // Candela (point, spot) and lux (directional) to W/sr and W/m² per channel.
        let color = Vec3::from(light.color) * light.intensity / LUMENS_PER_WATT;
        if light.range.is_some() {
            self.unsupported
                .note(Feature::LightRange, "lights", || format!("light {index}"));
        }
        let position = world.w_axis.truncate();
        let axis = world.transform_vector3(Vec3::NEG_Z).normalize_or_zero();
        if !color.is_finite() || color.min_element() < 0.0 || axis == Vec3::ZERO {
            return Err(format!(
                "light {index}: colour, intensity or orientation out of range"
            ));
        }
        match light.type_ {
            Checked::Valid(LightType::Point) => scene.punctual_lights.push(PunctualLight::Point {
                position,
                intensity: color,
            }),
            Checked::Valid(LightType::Spot) => {
                let (inner, outer) = light
                    .spot
                    .as_ref()
                    .map_or((0.0, std::f32::consts::FRAC_PI_4), |s| {
                        (s.inner_cone_angle, s.outer_cone_angle)
                    });
                if !(0.0 <= inner && inner <= outer && outer <= std::f32::consts::FRAC_PI_2) {
                    return Err(format!(
                        "light {index}: spot cone angles {inner}, {outer} are out of range"
                    ));
                }
                scene.punctual_lights.push(PunctualLight::Spot {
                    position,
                    direction: axis,
                    intensity: color,
                    inner_angle: inner,
                    outer_angle: outer,
                });
            }
            Checked::Valid(LightType::Directional) => {
                if scene.sun.is_some() {
                    self.unsupported
                        .note(Feature::ExtraDirectionalLight, "lights", || {
                            format!("light {index}")
                        });
                } else {
                    scene.sun = Some(Sun {
                        direction: -axis,
                        irradiance: color,
                        angular_radius: 0.00465,
                    });
                }
            }
            Checked::Invalid => return Err(format!("light {index}: unknown light type")),
        }
        Ok(())
    }
}

/// Checks that mesh `id` placed by `node` with `transform` stays within [`MAX_COORDINATE`]
/// (a huge scale or translation), naming the node and the mesh.
fn check_world_extent(
    scene: &Scene,
    node: &Node,
    id: u32,
    transform: &Affine3A,
) -> Result<(), String> {
    let mesh = &scene.meshes[id as usize];
    let bounds = mesh.bounds().transformed(transform);
    if bounds.is_empty() {
        return Ok(());
    }
    let reach = bounds.min.abs().max(bounds.max.abs()).max_element();
    if reach <= MAX_COORDINATE {
        return Ok(());
    }
    let node_name = node
        .name()
        .map_or_else(String::new, |n| format!(" (`{n}`)"));
    Err(format!(
        "node {}{node_name}: mesh `{}` reaches {reach:e} in world space, beyond the supported \
         ±{MAX_COORDINATE:e} (check the node's scale and translation)",
        node.index(),
        mesh.name
    ))
}
