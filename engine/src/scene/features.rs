//! "Model no more than a scene needs": which shading features a scene
//! actually uses, exported as shader specialization constants.

use std::fmt;

use super::{Environment, MaterialKind, Scene};

/// Features used by a scene. Only materials referenced by placed geometry
/// count.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SceneFeatures {
    /// A Lambertian diffuse material is used.
    pub diffuse: bool,
    /// A conductor is used.
    pub conductor: bool,
    /// A smooth dielectric is used.
    pub dielectric_smooth: bool,
    /// A rough dielectric is used.
    pub dielectric_rough: bool,
    /// glTF's metallic-roughness model is used.
    pub metal_rough: bool,
    /// Some used material emits.
    pub emissive: bool,
    /// The scene has analytic spheres.
    pub spheres: bool,
    /// Some used material has a base-colour texture.
    pub textures: bool,
    /// Some placed mesh has vertex colours.
    pub vertex_colors: bool,
    /// Some used material has a normal map.
    pub normal_maps: bool,
    /// Some used emissive material has an emissive texture.
    pub emissive_textures: bool,
    /// Some used material is cut out (alpha mask or blend): traversal tests opacity.
    pub alpha_test: bool,
    /// Some used material has an occlusion texture.
    pub occlusion: bool,
    /// Some used texture slot transforms its coordinates or wraps other than by repeating.
    pub texture_transforms: bool,
    /// The environment is not black.
    pub environment: bool,
    /// The environment is a map, sampled by next-event estimation.
    pub environment_map: bool,
    /// A sun is present.
    pub sun: bool,
    /// Point or spot (delta) lights are present.
    pub delta_lights: bool,
}

impl SceneFeatures {
    /// Derives the features of a scene.
    pub fn from_scene(scene: &Scene) -> Self {
        let mut f = SceneFeatures {
            spheres: !scene.spheres.is_empty(),
            environment: !scene.environment.is_black(),
            environment_map: matches!(scene.environment, Environment::Map { .. }),
            sun: scene.sun.is_some(),
            delta_lights: !scene.punctual_lights.is_empty(),
            ..Default::default()
        };
        f.vertex_colors = scene
            .instances
            .iter()
            .any(|i| !scene.meshes[i.mesh as usize].colors.is_empty());
        let used = (0..scene.instances.len())
            .map(|i| scene.instance_material(i))
            .chain(scene.spheres.iter().map(|s| s.material));
        for id in used {
            let Some(m) = scene.materials.get(id as usize) else {
                continue;
            };
            match m.kind {
                MaterialKind::Diffuse => f.diffuse = true,
                MaterialKind::Conductor => f.conductor = true,
                MaterialKind::Dielectric if m.is_smooth_dielectric() => f.dielectric_smooth = true,
                MaterialKind::Dielectric => f.dielectric_rough = true,
                MaterialKind::MetalRough => f.metal_rough = true,
            }
            f.textures |=
                m.kind == MaterialKind::MetalRough && m.metallic_roughness_texture.is_some();
            f.emissive |= m.is_emissive();
            f.textures |= m.base_color_texture.is_some()
                || m.emissive_texture.is_some()
                || m.normal_texture.is_some()
                || m.occlusion_texture.is_some();
            f.normal_maps |= m.normal_texture.is_some();
            f.emissive_textures |= m.is_emissive() && m.emissive_texture.is_some();
            f.alpha_test |= m.is_cut_out();
            f.occlusion |= m.occlusion_texture.is_some();
            f.texture_transforms |= m.textures().any(|t| t.is_transformed());
        }
        // The map's lookup clamps at the poles.
        f.texture_transforms |= f.environment_map;
        f
    }

    /// The features as named boolean specialization constants, in a fixed
    /// order (`HAS_DIELECTRIC` is true if either dielectric kind is used).
    pub fn specialization_constants(&self) -> Vec<(&'static str, bool)> {
        vec![
            ("HAS_DIFFUSE", self.diffuse),
            ("HAS_CONDUCTOR", self.conductor),
            (
                "HAS_DIELECTRIC",
                self.dielectric_smooth || self.dielectric_rough,
            ),
            ("HAS_DIELECTRIC_SMOOTH", self.dielectric_smooth),
            ("HAS_DIELECTRIC_ROUGH", self.dielectric_rough),
            ("HAS_METAL_ROUGH", self.metal_rough),
            ("HAS_EMISSIVE", self.emissive),
            ("HAS_SPHERES", self.spheres),
            ("HAS_TEXTURES", self.textures),
            ("HAS_VERTEX_COLORS", self.vertex_colors),
            ("HAS_NORMAL_MAPS", self.normal_maps),
            ("HAS_EMISSIVE_TEXTURES", self.emissive_textures),
            ("HAS_ALPHA_TEST", self.alpha_test),
            ("HAS_OCCLUSION", self.occlusion),
            ("HAS_TEXTURE_TRANSFORMS", self.texture_transforms),
            ("HAS_ENVIRONMENT", self.environment),
            ("HAS_ENVIRONMENT_MAP", self.environment_map),
            ("HAS_SUN", self.sun),
            ("HAS_DELTA_LIGHTS", self.delta_lights),
        ]
    }
}

impl fmt::Display for SceneFeatures {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let on: Vec<&str> = self
            .specialization_constants()
            .into_iter()
            .filter(|(_, v)| *v)
            .map(|(k, _)| k)
            .collect();
        if on.is_empty() {
            write!(f, "(no features)")
        } else {
            write!(f, "{}", on.join(" "))
        }
    }
}
