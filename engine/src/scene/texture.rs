//! Base-colour textures stored as plain texel arrays.

use super::SceneError;

/// Texel storage of a texture, row-major from the top-left texel.
#[derive(Clone, Debug, PartialEq)]
pub enum TexelData {
    /// 8-bit RGBA texels.
    Rgba8(Vec<[u8; 4]>),
    /// 32-bit float RGBA texels.
    RgbaF32(Vec<[f32; 4]>),
}

impl TexelData {
    /// Number of texels.
    pub fn len(&self) -> usize {
        match self {
            TexelData::Rgba8(t) => t.len(),
            TexelData::RgbaF32(t) => t.len(),
        }
    }

    /// Whether there are no texels.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A 2D texture.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Name used in messages.
    pub name: String,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Whether 8-bit texels are sRGB encoded (float texels are linear).
    pub srgb: bool,
    /// The texels.
    pub texels: TexelData,
}

impl Texture {
    /// Checks that the texel count matches the dimensions.
    pub fn validate(&self) -> Result<(), SceneError> {
        let expected = self.width as u64 * self.height as u64;
        if expected == 0 || expected != self.texels.len() as u64 {
            return Err(SceneError::InvalidTexture {
                name: self.name.clone(),
                reason: format!(
                    "{}x{} texture holds {} texels",
                    self.width,
                    self.height,
                    self.texels.len()
                ),
            });
        }
        Ok(())
    }
}
