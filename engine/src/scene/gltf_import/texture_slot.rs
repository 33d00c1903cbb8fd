//! One texture reference of a glTF material (`textureInfo`, `normalTextureInfo` or
//! `occlusionTextureInfo`): its image, texture coordinate set, sampler wrap modes and
//! `KHR_texture_transform`.

use glam::Vec2;
use gltf::json::extensions::texture::TextureTransform;
use gltf::json::Index;
use gltf::texture::WrappingMode;
use gltf::Document;
use serde_json::{Map, Value};

use crate::scene::{UvTransform, WrapMode};

/// A material's texture reference, resolved against the document.
pub struct Slot {
    /// glTF image index.
    pub image: usize,
    /// The `TEXCOORD_n` set it reads (the transform's `texCoord` when it has one).
    pub tex_coord: u32,
    /// `KHR_texture_transform` (identity without it).
    pub transform: UvTransform,
    /// The sampler's `wrapS` and `wrapT`.
    pub wrap: [WrapMode; 2],
}

impl Slot {
    /// Resolves texture `index` read through `TEXCOORD_<tex_coord>` with an optional
    /// `KHR_texture_transform`.
    pub fn new(
        doc: &Document,
        index: Index<gltf::json::Texture>,
        tex_coord: u32,
        transform: Option<&TextureTransform>,
    ) -> Result<Self, String> {
        let texture = doc
            .textures()
            .nth(index.value())
            .ok_or_else(|| format!("texture {} does not exist", index.value()))?;
        let sampler = texture.sampler();
        Ok(Self {
            image: texture.source().index(),
            tex_coord: transform.and_then(|t| t.tex_coord).unwrap_or(tex_coord),
            transform: transform.map_or(UvTransform::IDENTITY, |t| UvTransform {
                offset: Vec2::from(t.offset.0),
                rotation: t.rotation.0,
                scale: Vec2::from(t.scale.0),
            }),
            wrap: [sampler.wrap_s(), sampler.wrap_t()].map(wrap_mode),
        })
    }

    /// Resolves a `normalTextureInfo` or `occlusionTextureInfo`, whose extensions the `gltf` crate
    /// leaves as raw JSON (`others`).
    pub fn with_raw_extensions(
        doc: &Document,
        index: Index<gltf::json::Texture>,
        tex_coord: u32,
        others: Option<&Map<String, Value>>,
    ) -> Result<Self, String> {
        let transform = match others.and_then(|o| o.get("KHR_texture_transform")) {
            Some(v) => Some(
                serde_json::from_value::<TextureTransform>(v.clone()).map_err(|e| {
                    format!("texture {}: KHR_texture_transform: {e}", index.value())
                })?,
            ),
            None => None,
        };
        Self::new(doc, index, tex_coord, transform.as_ref())
    }
}

fn wrap_mode(w: WrappingMode) -> WrapMode {
    match w {
        WrappingMode::Repeat => WrapMode::Repeat,
        WrappingMode::ClampToEdge => WrapMode::ClampToEdge,
        WrappingMode::MirroredRepeat => WrapMode::MirroredRepeat,
    }
}
