//! Surface materials and their range validation.

use glam::Vec3;

use super::{SceneError, TextureRef};

/// GGX `alpha` below which a surface is treated as perfectly smooth.
pub const SMOOTH_ALPHA: f32 = 1e-3;

/// The scattering model of a material.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MaterialKind {
    /// Lambertian diffuse reflection with albedo `base_color`.
    Diffuse,
    /// GGX microfacet conductor; `base_color` is the metal colour (F0).
    Conductor,
    /// Dielectric (glass) with index of refraction `ior`; smooth when
    /// `alpha < SMOOTH_ALPHA`, rough GGX otherwise. `base_color` tints
    /// transmission.
    Dielectric,
    /// glTF 2.0's metallic-roughness model: a dielectric (a GGX specular layer of IOR 1.5 over
    /// Lambertian diffuse of albedo `base_color`) and a GGX conductor of colour `base_color`,
    /// mixed by `metallic`; `metallic_roughness_texture` varies metal and roughness per texel.
    MetalRough,
}

/// How a material's opacity (base colour alpha × texture alpha × vertex colour alpha) applies
/// (glTF `alphaMode`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum AlphaMode {
    /// Opacity is ignored.
    #[default]
    Opaque,
    /// The surface is absent where the opacity is below `cutoff` (rays pass there).
    Mask {
        /// glTF `alphaCutoff` (0.5 by default).
        cutoff: f32,
    },
    /// Stochastic transparency: a ray meets the surface with probability equal to the opacity.
    Blend,
}

/// A surface material. Any material may also emit (`emission > 0`), which
/// turns its surfaces into area lights.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Name used in error messages and reports.
    pub name: String,
    /// Scattering model.
    pub kind: MaterialKind,
    /// Albedo / metal colour / transmission tint, linear RGB in `[0, 1]`.
    pub base_color: Vec3,
    /// Optional base-colour texture, multiplied with `base_color` (its alpha with `opacity`).
    pub base_color_texture: Option<TextureRef>,
    /// GGX roughness `alpha` (= perceptual roughness squared) in `[0, 1]`.
    pub alpha: f32,
    /// Optional metallic-roughness texture (linear; glTF's layout: roughness in G, metalness in
    /// B). On [`MaterialKind::MetalRough`] it scales the roughness by G (`alpha` by G²) and the
    /// metallic factor by B; other kinds ignore it.
    pub metallic_roughness_texture: Option<TextureRef>,
    /// Metallic factor in `[0, 1]` ([`MaterialKind::MetalRough`]: the conductor's share).
    pub metallic: f32,
    /// Index of refraction: a dielectric's (`>= 1`), or [`MaterialKind::MetalRough`]'s specular
    /// layer's (its Fresnel reflectance at normal incidence is `((ior - 1) / (ior + 1))²`).
    pub ior: f32,
    /// [`MaterialKind::MetalRough`]: the strength of the dielectric's specular layer in `[0, 1]`
    /// (glTF `KHR_materials_specular`'s `specularFactor`; 0 leaves Lambertian diffuse).
    pub specular: f32,
    /// [`MaterialKind::MetalRough`]: the colour scaling the specular layer's normal-incidence
    /// reflectance, `>= 0` (`specularColorFactor`).
    pub specular_color: Vec3,
    /// Emitted radiance, linear RGB, `>= 0`.
    pub emission: Vec3,
    /// Optional emissive texture (sRGB), multiplying `emission` per texel.
    pub emissive_texture: Option<TextureRef>,
    /// Optional tangent-space normal map (glTF `normalTexture`, linear); meshes using it carry
    /// tangents.
    pub normal_texture: Option<TextureRef>,
    /// Scale of the normal map's X and Y (glTF `normalTexture.scale`).
    pub normal_scale: f32,
    /// Optional ambient occlusion in R (glTF `occlusionTexture`, linear): darkens the albedo the
    /// G-buffer and the denoisers see, never the light transport.
    pub occlusion_texture: Option<TextureRef>,
    /// How much of the occlusion applies (glTF `occlusionTexture.strength`, `[0, 1]`).
    pub occlusion_strength: f32,
    /// Base opacity (glTF base colour alpha), `[0, 1]`.
    pub opacity: f32,
    /// How opacity applies.
    pub alpha_mode: AlphaMode,
}

impl Material {
    fn base(name: &str, kind: MaterialKind, base_color: Vec3) -> Self {
        Self {
            name: name.to_owned(),
            kind,
            base_color,
            base_color_texture: None,
            alpha: 0.0,
            metallic_roughness_texture: None,
            metallic: if kind == MaterialKind::Conductor {
                1.0
            } else {
                0.0
            },
            ior: 1.5,
            specular: 1.0,
            specular_color: Vec3::ONE,
            emission: Vec3::ZERO,
            emissive_texture: None,
            normal_texture: None,
            normal_scale: 1.0,
            occlusion_texture: None,
            occlusion_strength: 1.0,
            opacity: 1.0,
            alpha_mode: AlphaMode::Opaque,
        }
    }

    /// A Lambertian diffuse material.
    pub fn diffuse(name: &str, albedo: Vec3) -> Self {
        Self::base(name, MaterialKind::Diffuse, albedo)
    }

    /// A rough (or, with `alpha = 0`, mirror) conductor.
    pub fn conductor(name: &str, metal_color: Vec3, alpha: f32) -> Self {
        Self {
            alpha,
            ..Self::base(name, MaterialKind::Conductor, metal_color)
        }
    }

    /// glTF's metallic-roughness material: `metallic` of a conductor of colour `base_color`, the
    /// rest a specular layer over diffuse of albedo `base_color`, both of roughness `alpha`.
    pub fn metal_rough(name: &str, base_color: Vec3, metallic: f32, alpha: f32) -> Self {
        Self {
            alpha,
            metallic,
            ..Self::base(name, MaterialKind::MetalRough, base_color)
        }
    }

    /// A smooth (`alpha = 0`) or rough dielectric.
    pub fn dielectric(name: &str, ior: f32, alpha: f32) -> Self {
        Self {
            alpha,
            ior,
            ..Self::base(name, MaterialKind::Dielectric, Vec3::ONE)
        }
    }

    /// A diffuse emitter: black albedo with the given emitted radiance.
    pub fn emissive(name: &str, radiance: Vec3) -> Self {
        Self::diffuse(name, Vec3::ZERO).with_emission(radiance)
    }

    /// This material with emitted radiance `radiance`.
    pub fn with_emission(mut self, radiance: Vec3) -> Self {
        self.emission = radiance;
        self
    }

    /// [`MaterialKind::MetalRough`]: the specular layer's Fresnel reflectance at normal incidence
    /// per channel, `((ior - 1) / (ior + 1))² × specular_color`, at most 1.
    pub fn specular_f0(&self) -> Vec3 {
        let r = (self.ior - 1.0) / (self.ior + 1.0);
        (r * r * self.specular_color).min(Vec3::ONE)
    }

    /// Whether the material emits light.
    pub fn is_emissive(&self) -> bool {
        self.emission.max_element() > 0.0
    }

    /// Whether rays may pass through the surface (an alpha mask or blending).
    pub fn is_cut_out(&self) -> bool {
        self.alpha_mode != AlphaMode::Opaque
    }

    /// The textures the material uses, slot by slot.
    pub fn textures(&self) -> impl Iterator<Item = TextureRef> {
        [
            self.base_color_texture,
            self.metallic_roughness_texture,
            self.emissive_texture,
            self.normal_texture,
            self.occlusion_texture,
        ]
        .into_iter()
        .flatten()
    }

    /// Whether the material is a perfectly smooth dielectric.
    pub fn is_smooth_dielectric(&self) -> bool {
        self.kind == MaterialKind::Dielectric && self.alpha < SMOOTH_ALPHA
    }

    /// Whether the material is a rough dielectric.
    pub fn is_rough_dielectric(&self) -> bool {
        self.kind == MaterialKind::Dielectric && self.alpha >= SMOOTH_ALPHA
    }

    /// Brings parameters into range. Non-finite values, a negative
    /// emission or an IOR below 1 are rejected with an error naming the
    /// material; colours outside `[0, 1]` and roughness outside `[0, 1]`
    /// are clamped, and a warning naming the material is returned for each.
    pub fn sanitize(&mut self) -> Result<Vec<String>, SceneError> {
        let reject = |reason: String| SceneError::InvalidMaterial {
            name: self.name.clone(),
            reason,
        };
        let finite = self.base_color.is_finite()
            && self.emission.is_finite()
            && self.alpha.is_finite()
            && self.ior.is_finite()
            && self.specular.is_finite()
            && self.specular_color.is_finite()
            && self.metallic.is_finite()
            && self.normal_scale.is_finite()
            && self.occlusion_strength.is_finite()
            && self.opacity.is_finite()
            && self.textures().all(|t| t.transform.is_finite())
            && match self.alpha_mode {
                AlphaMode::Mask { cutoff } => cutoff.is_finite(),
                _ => true,
            };
        if !finite {
            return Err(reject(
                "parameters must be finite (found NaN or infinity)".into(),
            ));
        }
        if self.emission.min_element() < 0.0 {
            return Err(reject(format!("negative emission {}", self.emission)));
        }
        if self.kind == MaterialKind::Dielectric && self.ior < 1.0 {
            return Err(reject(format!(
                "index of refraction {} is below 1",
                self.ior
            )));
        }
        let mut warnings = Vec::new();
        let clamped = self.base_color.clamp(Vec3::ZERO, Vec3::ONE);
        if clamped != self.base_color {
            warnings.push(format!(
                "material `{}`: base colour {} clamped to [0, 1]",
                self.name, self.base_color
            ));
            self.base_color = clamped;
        }
        self.metallic = self.metallic.clamp(0.0, 1.0);
        self.specular = self.specular.clamp(0.0, 1.0);
        self.specular_color = self.specular_color.max(Vec3::ZERO);
        self.occlusion_strength = self.occlusion_strength.clamp(0.0, 1.0);
        self.opacity = self.opacity.clamp(0.0, 1.0);
        let alpha = self.alpha.clamp(0.0, 1.0);
        if alpha != self.alpha {
            warnings.push(format!(
                "material `{}`: roughness alpha {} clamped to [0, 1]",
                self.name, self.alpha
            ));
            self.alpha = alpha;
        }
        Ok(warnings)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sanitize_clamps_and_rejects() {
        let mut m = Material::diffuse("bright", Vec3::new(1.5, -0.1, 0.5));
        let w = m.sanitize().unwrap();
        assert_eq!(m.base_color, Vec3::new(1.0, 0.0, 0.5));
        assert!(w[0].contains("bright"));

        let mut nan = Material::conductor("nanmetal", Vec3::ONE, f32::NAN);
        let e = nan.sanitize().unwrap_err().to_string();
        assert!(e.contains("nanmetal") && e.contains("finite"), "{e}");

        let mut glass = Material::dielectric("badglass", 0.8, 0.0);
        let e = glass.sanitize().unwrap_err().to_string();
        assert!(e.contains("badglass") && e.contains("below 1"), "{e}");

        let mut neg = Material::emissive("neglight", Vec3::splat(-1.0));
        assert!(neg.sanitize().unwrap_err().to_string().contains("neglight"));

        let mut rough = Material::dielectric("frosted", 1.5, 2.0);
        rough.sanitize().unwrap();
        assert_eq!(rough.alpha, 1.0);
        assert!(rough.is_rough_dielectric() && !rough.is_smooth_dielectric());
    }
}
