//! Facts about the texel formats Lucid uses, and conversion of read-back texels to linear RGBA.

use ash::vk;

/// Size and channel layout of a texel format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FormatInfo {
    /// Bytes per texel.
    pub bytes: u32,
    /// Channels per texel.
    pub channels: u32,
    /// The storage of each channel.
    pub channel: ChannelType,
}

/// How one channel is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ChannelType {
    /// 32-bit float.
    F32,
    /// 16-bit float.
    F16,
    /// 8-bit unsigned normalised.
    Unorm8,
    /// 32-bit unsigned integer.
    U32,
}

impl FormatInfo {
    /// The info for `format`, or `None` when Lucid does not use that format.
    pub fn of(format: vk::Format) -> Option<Self> {
        use ChannelType::*;
        let (bytes, channels, channel) = match format {
            vk::Format::R32G32B32A32_SFLOAT => (16, 4, F32),
            vk::Format::R32G32_SFLOAT => (8, 2, F32),
            vk::Format::R32_SFLOAT => (4, 1, F32),
            vk::Format::R16G16B16A16_SFLOAT => (8, 4, F16),
            vk::Format::R16G16_SFLOAT => (4, 2, F16),
            vk::Format::R16_SFLOAT => (2, 1, F16),
            vk::Format::R8G8B8A8_UNORM | vk::Format::B8G8R8A8_UNORM => (4, 4, Unorm8),
            vk::Format::R32_UINT => (4, 1, U32),
            vk::Format::R32G32_UINT => (8, 2, U32),
            vk::Format::R32G32B32A32_UINT => (16, 4, U32),
            _ => return None,
        };
        Some(Self {
            bytes,
            channels,
            channel,
        })
    }
}

/// Converts tightly packed texels of `format` into RGBA f32 (missing channels: 0, alpha: 1;
/// integer channels are converted to float values; BGRA is swizzled to RGBA).
pub fn texels_to_rgba(format: vk::Format, bytes: &[u8]) -> Option<Vec<[f32; 4]>> {
    let info = FormatInfo::of(format)?;
    let size = info.bytes as usize;
    let channel_bytes = size / info.channels as usize;
    let read = |texel: &[u8], c: usize| -> f32 {
        let b = &texel[c * channel_bytes..(c + 1) * channel_bytes];
        match info.channel {
            ChannelType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]),
            ChannelType::F16 => half::f16::from_le_bytes([b[0], b[1]]).to_f32(),
            ChannelType::Unorm8 => b[0] as f32 / 255.0,
            ChannelType::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f32,
        }
    };
    Some(
        bytes
            .chunks_exact(size)
            .map(|texel| {
                let mut out = [0.0, 0.0, 0.0, 1.0];
                for (c, slot) in out.iter_mut().enumerate().take(info.channels as usize) {
                    *slot = read(texel, c);
                }
                if format == vk::Format::B8G8R8A8_UNORM {
                    out.swap(0, 2);
                }
                out
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn converts_half_and_float_texels() {
        let h: Vec<u8> = [1.5f32, -2.0, 0.25, 1.0]
            .iter()
            .flat_map(|&v| half::f16::from_f32(v).to_le_bytes())
            .collect();
        assert_eq!(
            texels_to_rgba(vk::Format::R16G16B16A16_SFLOAT, &h).unwrap(),
            vec![[1.5, -2.0, 0.25, 1.0]]
        );
        let f: Vec<u8> = 3.0f32.to_le_bytes().to_vec();
        assert_eq!(
            texels_to_rgba(vk::Format::R32_SFLOAT, &f).unwrap(),
            vec![[3.0, 0.0, 0.0, 1.0]]
        );
    }

    #[test]
    fn swizzles_bgra() {
        let out = texels_to_rgba(vk::Format::B8G8R8A8_UNORM, &[255, 0, 0, 255]).unwrap();
        assert_eq!(out, vec![[0.0, 0.0, 1.0, 1.0]]);
    }
}
