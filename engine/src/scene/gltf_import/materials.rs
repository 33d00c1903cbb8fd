//! glTF metallic-roughness materials mapped onto Lucid's material kinds,
//! and base-colour textures.
//!
//! Mapping:
//! - `KHR_materials_transmission` with a factor > 0 → dielectric with the
//!   `KHR_materials_ior` index (default 1.5), tinted by the base colour;
//! - otherwise a metallic factor of 1 without a metallic-roughness texture → conductor with the
//!   base colour as metal colour (the model's metal half alone, smooth ones a perfect mirror);
//! - otherwise → the metallic-roughness model in full ([`MaterialKind::MetalRough`]): a GGX
//!   specular layer over Lambertian diffuse of the base colour, mixed with the metal by the
//!   metallic factor, the texture (linear, roughness in G, metal in B) scaling both per texel; the
//!   layer's reflectance follows `KHR_materials_ior` (default 1.5) and `KHR_materials_specular`'s
//!   factors (its textures are reported, not read).
//!
//! Roughness maps to GGX `alpha = roughness²`. Emission is
//! `emissiveFactor × KHR_materials_emissive_strength`, times the emissive texture (sRGB) when
//! there is one. The base-colour texture (sRGB, its alpha the opacity), the normal map and the
//! occlusion texture are kept for every kind. `alphaMode` and `alphaCutoff` carry over. Every
//! texture keeps its sampler's wrap modes and its `KHR_texture_transform`. What a material uses
//! beyond this (partial transmission, specular textures, texture coordinates other than
//! `TEXCOORD_0`) is reported once per feature per file ([`super::unsupported`]).

use std::collections::HashMap;
use std::path::Path;

use glam::Vec3;
use gltf::material::AlphaMode;
use gltf::Document;

use super::texture_slot::Slot;
use super::unsupported::{Feature, Unsupported};
use super::uri;
use crate::scene::{Material, MaterialKind, Scene, TexelData, Texture, TextureRef};

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
        let [r, g, b, a] = pbr.base_color_factor();
        let ext = self
            .doc
            .as_json()
            .materials
            .get(index)
            .and_then(|j| j.extensions.as_ref());
        let transmission_ext = ext.and_then(|e| e.transmission.as_ref());
        let transmission = transmission_ext.map_or(0.0, |t| t.transmission_factor.0);
        let ior = ext.and_then(|e| e.ior.as_ref()).map_or(1.5, |i| i.ior.0);
        let specular_ext = ext.and_then(|e| e.specular.as_ref());
        let strength = ext
            .and_then(|e| e.emissive_strength.as_ref())
            .map_or(1.0, |s| s.emissive_strength.0);
        let metallic = pbr.metallic_factor();
        let kind = if transmission > 0.0 {
            MaterialKind::Dielectric
        } else if metallic >= 1.0 && pbr.metallic_roughness_texture().is_none() {
            MaterialKind::Conductor
        } else {
            MaterialKind::MetalRough
        };
        let roughness = pbr.roughness_factor();
        let mut note =
            |feature| unsupported.note(feature, "materials", || format!("material `{name}`"));
        let partial_transmission = transmission_ext
            .is_some_and(|t| t.transmission_texture.is_some() || t.transmission_factor.0 < 1.0);
        if kind == MaterialKind::Dielectric && partial_transmission {
            note(Feature::PartialTransmission);
        }
        if kind == MaterialKind::Dielectric && pbr.metallic_roughness_texture().is_some() {
            note(Feature::MetallicRoughnessTexture);
        }
        if specular_ext
            .is_some_and(|s| s.specular_texture.is_some() || s.specular_color_texture.is_some())
        {
            note(Feature::SpecularTextures);
        }
        let alpha_mode = match m.alpha_mode() {
            AlphaMode::Opaque => crate::scene::AlphaMode::Opaque,
            AlphaMode::Mask => crate::scene::AlphaMode::Mask {
                cutoff: m.alpha_cutoff().unwrap_or(0.5),
            },
            AlphaMode::Blend => crate::scene::AlphaMode::Blend,
        };
        let doc = self.doc;
        let json = &doc.as_json().materials[index];
        let info = |i: &gltf::json::texture::Info| {
            let transform = i
                .extensions
                .as_ref()
                .and_then(|e| e.texture_transform.as_ref());
            Slot::new(doc, i.index, i.tex_coord, transform)
        };
        let pbr_json = &json.pbr_metallic_roughness;
        let base_color_texture = match &pbr_json.base_color_texture {
            Some(i) => Some(self.slot(scene, &info(i)?, true, &mut note)?),
            None => None,
        };
        let metallic_roughness_texture = match &pbr_json.metallic_roughness_texture {
            Some(i) if kind == MaterialKind::MetalRough => {
                Some(self.slot(scene, &info(i)?, false, &mut note)?)
            }
            _ => None,
        };
        let emission = Vec3::from(m.emissive_factor()) * strength;
        // An emissive texture multiplies the factor: without a factor it adds nothing.
        let emissive_texture = match &json.emissive_texture {
            Some(i) if emission.max_element() > 0.0 => {
                Some(self.slot(scene, &info(i)?, true, &mut note)?)
            }
            _ => None,
        };
        let normal_texture = match &json.normal_texture {
            Some(t) => {
                let others = t.extensions.as_ref().map(|e| &e.others);
                let slot = Slot::with_raw_extensions(doc, t.index, t.tex_coord, others)?;
                Some(self.slot(scene, &slot, false, &mut note)?)
            }
            None => None,
        };
        let occlusion_texture = match &json.occlusion_texture {
            Some(t) => {
                let others = t.extensions.as_ref().map(|e| &e.others);
                let slot = Slot::with_raw_extensions(doc, t.index, t.tex_coord, others)?;
                Some(self.slot(scene, &slot, false, &mut note)?)
            }
            None => None,
        };
        Ok(scene.add_material(Material {
            name,
            kind,
            base_color: Vec3::new(r, g, b),
            base_color_texture,
            alpha: roughness * roughness,
            metallic_roughness_texture,
            metallic,
            ior,
            specular: specular_ext.map_or(1.0, |s| s.specular_factor.0),
            specular_color: specular_ext
                .map_or(Vec3::ONE, |s| Vec3::from(s.specular_color_factor.0)),
            emission,
            emissive_texture,
            normal_texture,
            normal_scale: m.normal_texture().map_or(1.0, |t| t.scale()),
            occlusion_texture,
            occlusion_strength: m.occlusion_texture().map_or(1.0, |t| t.strength()),
            opacity: a,
            alpha_mode,
        }))
    }

    /// The scene texture of `slot`'s image (decoded once per colour space: `srgb` for colours,
    /// linear for data) with its sampler's wrap modes and `KHR_texture_transform`. Texture
    /// coordinates other than `TEXCOORD_0` are noted as unsupported.
    fn slot(
        &mut self,
        scene: &mut Scene,
        slot: &Slot,
        srgb: bool,
        note: &mut impl FnMut(Feature),
    ) -> Result<TextureRef, String> {
        if slot.tex_coord != 0 {
            note(Feature::OtherTexCoords);
        }
        Ok(TextureRef {
            texture: self.image(scene, slot.image, srgb)?,
            transform: slot.transform,
            wrap: slot.wrap,
        })
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
