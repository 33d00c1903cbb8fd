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

impl Texture {
    /// The texture's mip levels below level 0, halving each side (odd sides round down, never
    /// below 1) down to 1x1: each texel is the mean of the up to four texels it covers, averaged
    /// in linear space (8-bit sRGB texels are decoded and encoded again). The shaders find a
    /// level's texels after the previous level's by this rule.
    pub fn mip_levels(&self) -> Vec<TexelData> {
        let (mut w, mut h) = (self.width as usize, self.height as usize);
        let mut level: Vec<[f32; 4]> = (0..self.texels.len()).map(|i| self.linear(i)).collect();
        let mut levels = Vec::new();
        while w > 1 || h > 1 {
            let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
            let mut next = vec![[0.0f32; 4]; nw * nh];
            for y in 0..nh {
                for x in 0..nw {
                    let mut sum = [0.0f32; 4];
                    let (xs, ys) = ((2 * x)..(2 * x + 2).min(w), (2 * y)..(2 * y + 2).min(h));
                    let n = (xs.len() * ys.len()) as f32;
                    for yy in ys {
                        for xx in xs.clone() {
                            let t = level[yy * w + xx];
                            for c in 0..4 {
                                sum[c] += t[c] / n;
                            }
                        }
                    }
                    next[y * nw + x] = sum;
                }
            }
            levels.push(match self.texels {
                TexelData::RgbaF32(_) => TexelData::RgbaF32(next.clone()),
                TexelData::Rgba8(_) => {
                    TexelData::Rgba8(next.iter().map(|t| self.encode(*t)).collect())
                }
            });
            (level, w, h) = (next, nw, nh);
        }
        levels
    }

    /// Texel `i` (row-major) as linear RGBA: 8-bit texels scaled to `[0, 1]` and, when sRGB,
    /// decoded.
    pub(crate) fn linear(&self, i: usize) -> [f32; 4] {
        match &self.texels {
            TexelData::RgbaF32(t) => t[i],
            TexelData::Rgba8(t) => self.decode(t[i]),
        }
    }

    fn decode(&self, p: [u8; 4]) -> [f32; 4] {
        let f = |v: u8| v as f32 / 255.0;
        let c = |v: u8| {
            if self.srgb {
                crate::capture::srgb_decode(f(v))
            } else {
                f(v)
            }
        };
        [c(p[0]), c(p[1]), c(p[2]), f(p[3])]
    }

    fn encode(&self, t: [f32; 4]) -> [u8; 4] {
        let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        let c = |v: f32| {
            if self.srgb {
                q(crate::capture::srgb_encode(v))
            } else {
                q(v)
            }
        };
        [c(t[0]), c(t[1]), c(t[2]), q(t[3])]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mip_levels_halve_down_to_one_texel_and_average_in_linear_space() {
        // A 5x2 sRGB checker of black and white: 2x1, then 1x1; grey levels average to linear 0.5.
        let texels = (0..10)
            .map(|i| {
                if (i % 5 + i / 5) % 2 == 0 {
                    [0, 0, 0, 255]
                } else {
                    [255; 4]
                }
            })
            .collect();
        let t = Texture {
            name: "checker".into(),
            width: 5,
            height: 2,
            srgb: true,
            texels: TexelData::Rgba8(texels),
        };
        let levels = t.mip_levels();
        assert_eq!(
            levels.iter().map(TexelData::len).collect::<Vec<_>>(),
            [2, 1]
        );
        let TexelData::Rgba8(first) = &levels[0] else {
            panic!("8-bit levels stay 8-bit")
        };
        let linear = crate::capture::srgb_decode(first[0][0] as f32 / 255.0);
        assert!((linear - 0.5).abs() < 0.01, "{first:?}");
        let float = Texture {
            texels: TexelData::RgbaF32(vec![[2.0, 0.0, 0.0, 1.0], [0.0; 4]]),
            width: 2,
            height: 1,
            srgb: false,
            name: "f".into(),
        };
        assert_eq!(
            float.mip_levels(),
            [TexelData::RgbaF32(vec![[1.0, 0.0, 0.0, 0.5]])]
        );
    }
}
