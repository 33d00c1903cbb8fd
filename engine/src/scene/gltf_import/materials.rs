//! glTF metallic-roughness materials mapped onto Lucid's material kinds,
//! and base-colour textures.
//!
//! Mapping:
//! - `KHR_materials_transmission` with a factor > 0 → dielectric with the
//!   `KHR_materials_ior` index (default 1.5), tinted by the base colour;
//! - otherwise metallic > 0.5 → conductor with the base colour as metal
//!   colour;
//! - otherwise → Lambertian diffuse with the base colour as albedo.
//!
//! Roughness maps to GGX `alpha = roughness²`. Emission is
//! `emissiveFactor × KHR_materials_emissive_strength`. The base-colour
//! texture (sRGB, `TEXCOORD_0`) is kept for every kind; a metal's
//! metallic-roughness texture (linear, roughness in G, metal in B) scales its
//! roughness per texel and makes the texels where `metallic × B < 0.5` diffuse. What a material uses beyond this
//! (textures other than base colour, alpha modes, partial metal or transmission, other texture
//! coordinates or wrap modes) is reported once per feature per file ([`super::unsupported`]).

use std::collections::HashMap;
use std::path::Path;

use glam::Vec3;
use gltf::material::AlphaMode;
use gltf::texture::WrappingMode;
use gltf::Document;

use super::unsupported::{Feature, Unsupported};
use super::uri;
use crate::scene::{Material, MaterialKind, Scene, TexelData, Texture};

/// Converts materials and the textures they use.
pub struct MaterialImporter<'a> {
    doc: &'a Document,
    buffers: &'a [Vec<u8>],
    base: Option<&'a Path>,
    /// Scene texture index of each decoded glTF image and colour space (sRGB or not).
    images: HashMap<(usize, bool), u32>,
}

impl<'a> MaterialImporter<'a> {
    /// An importer over a validated document and its loaded buffers.
    pub fn new(doc: &'a Document, buffers: &'a [Vec<u8>], base: Option<&'a Path>) -> Self {
        Self {
            doc,
            buffers,
            base,
            images: HashMap::new(),
        }
    }

    /// Adds glTF material `index` to the scene and returns its index; what it uses that Lucid
    /// does not render goes to `unsupported`.
    pub fn import(
        &mut self,
        scene: &mut Scene,
        index: usize,
        unsupported: &mut Unsupported,
    ) -> Result<u32, String> {
        let m = self
            .doc
            .materials()
            .nth(index)
            .ok_or_else(|| format!("material {index} does not exist"))?;
        let name = m
            .name()
            .map_or_else(|| format!("material {index}"), str::to_owned);
        let pbr = m.pbr_metallic_roughness();
        let [r, g, b, _] = pbr.base_color_factor();
        let ext = self
            .doc
            .as_json()
            .materials
            .get(index)
            .and_then(|j| j.extensions.as_ref());
        let transmission_ext = ext.and_then(|e| e.transmission.as_ref());
        let transmission = transmission_ext.map_or(0.0, |t| t.transmission_factor.0);
        let ior = ext.and_then(|e| e.ior.as_ref()).map_or(1.5, |i| i.ior.0);
        let strength = ext
            .and_then(|e| e.emissive_strength.as_ref())
            .map_or(1.0, |s| s.emissive_strength.0);
        let kind = if transmission > 0.0 {
            MaterialKind::Dielectric
        } else if pbr.metallic_factor() > 0.5 {
            MaterialKind::Conductor
        } else {
            MaterialKind::Diffuse
        };
        let roughness = pbr.roughness_factor();
        let mut note =
            |feature| unsupported.note(feature, "materials", || format!("material `{name}`"));
        let metallic = pbr.metallic_factor();
        if kind != MaterialKind::Dielectric && metallic > 0.0 && metallic < 1.0 {
            note(Feature::PartialMetal);
        }
        let partial_transmission = transmission_ext
            .is_some_and(|t| t.transmission_texture.is_some() || t.transmission_factor.0 < 1.0);
        if kind == MaterialKind::Dielectric && partial_transmission {
            note(Feature::PartialTransmission);
        }
        if kind == MaterialKind::Dielectric && pbr.metallic_roughness_texture().is_some() {
            note(Feature::MetallicRoughnessTexture);
        }
        if m.normal_texture().is_some() {
            note(Feature::NormalMap);
        }
        if m.occlusion_texture().is_some() {
            note(Feature::Occlusion);
        }
        if m.emissive_texture().is_some() {
            note(Feature::EmissiveTexture);
        }
        match m.alpha_mode() {
            AlphaMode::Opaque => {}
            AlphaMode::Mask => note(Feature::AlphaMask),
            AlphaMode::Blend => note(Feature::AlphaBlend),
        }
        let mut check = |info: &gltf::texture::Info| {
            if info.tex_coord() != 0 {
                note(Feature::OtherTexCoords);
            }
            let sampler = info.texture().sampler();
            if [sampler.wrap_s(), sampler.wrap_t()]
                .iter()
                .any(|&w| w != WrappingMode::Repeat)
            {
                note(Feature::WrapMode);
            }
            info.texture().source().index()
        };
        let texture = match pbr.base_color_texture() {
            Some(info) => Some(self.image(scene, check(&info), true)?),
            None => None,
        };
        // Metal and roughness per texel matter only to a metal: below a metallic factor of 0.5
        // every texel is diffuse, and Lambertian reflection has no roughness.
        let metallic_roughness = match pbr.metallic_roughness_texture() {
            Some(info) if kind == MaterialKind::Conductor => {
                Some(self.image(scene, check(&info), false)?)
            }
            _ => None,
        };
        Ok(scene.add_material(Material {
            name,
            kind,
            base_color: Vec3::new(r, g, b),
            base_color_texture: texture,
            alpha: roughness * roughness,
            metallic_roughness_texture: metallic_roughness,
            metallic,
            ior,
            emission: Vec3::from(m.emissive_factor()) * strength,
        }))
    }

    /// Decodes glTF image `index` once per colour space (`srgb` for colours, linear for data)
    /// and returns its scene texture.
    fn image(&mut self, scene: &mut Scene, index: usize, srgb: bool) -> Result<u32, String> {
        if let Some(&t) = self.images.get(&(index, srgb)) {
            return Ok(t);
        }
        // Read the raw JSON: `gltf::Image::source` panics on an image with
        // neither (or both) of `uri` and `bufferView`.
        let json = self
            .doc
            .as_json()
            .images
            .get(index)
            .ok_or_else(|| format!("image {index} does not exist"))?;
        let (label, bytes) = match (&json.uri, json.buffer_view) {
            (Some(u), None) => (
                format!("image {index} (`{}`)", uri::shorten(u)),
                uri::read(u, self.base).map_err(|e| format!("image {index}: {e}"))?,
            ),
            (None, Some(v)) => {
                let view = self.doc.views().nth(v.value()).ok_or_else(|| {
                    format!("image {index}: buffer view {} does not exist", v.value())
                })?;
                let buf = &self.buffers[view.buffer().index()];
                let bytes = view
                    .offset()
                    .checked_add(view.length())
                    .and_then(|end| buf.get(view.offset()..end))
                    .ok_or_else(|| {
                        format!(
                            "image {index}: buffer view {} lies outside its buffer",
                            view.index()
                        )
                    })?;
                (format!("image {index}"), bytes.to_vec())
            }
            _ => {
                return Err(format!(
                    "image {index}: needs exactly one of `uri` and `bufferView`"
                ))
            }
        };
        let decoded =
            image::load_from_memory(&bytes).map_err(|e| format!("{label}: cannot decode: {e}"))?;
        let rgba = decoded.to_rgba8();
        let (width, height) = rgba.dimensions();
        let texels = rgba.pixels().map(|p| p.0).collect();
        let t = scene.add_texture(Texture {
            name: json
                .name
                .clone()
                .unwrap_or_else(|| format!("image {index}")),
            width,
            height,
            srgb,
            texels: TexelData::Rgba8(texels),
        });
        self.images.insert((index, srgb), t);
        Ok(t)
    }
}
