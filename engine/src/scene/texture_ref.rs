//! A material's use of a texture: which texture, how texture coordinates are transformed
//! (`KHR_texture_transform`) and how they wrap outside `[0, 1]` (the glTF sampler's wrap modes).

use glam::Vec2;

/// How a texture coordinate outside `[0, 1]` wraps (glTF sampler `wrapS` / `wrapT`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum WrapMode {
    /// The texture repeats (glTF's default).
    #[default]
    Repeat,
    /// Coordinates clamp to the edge texels.
    ClampToEdge,
    /// The texture repeats, every other copy mirrored.
    MirroredRepeat,
}

impl WrapMode {
    /// The GPU code of the mode (`TEXTURE_WRAP_*` in `shaders/common/scene.glsl`).
    pub fn code(self) -> u32 {
        match self {
            WrapMode::Repeat => 0,
            WrapMode::ClampToEdge => 1,
            WrapMode::MirroredRepeat => 2,
        }
    }
}

/// An affine transform of texture coordinates (`KHR_texture_transform`): scale, then rotate,
/// then offset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UvTransform {
    /// Added last.
    pub offset: Vec2,
    /// Radians; rotates the coordinates counter-clockwise (the image clockwise).
    pub rotation: f32,
    /// Multiplies the coordinates first.
    pub scale: Vec2,
}

impl Default for UvTransform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl UvTransform {
    /// Leaves coordinates as they are.
    pub const IDENTITY: Self = Self {
        offset: Vec2::ZERO,
        rotation: 0.0,
        scale: Vec2::ONE,
    };

    /// The two rows of the 2x3 matrix taking `(u, v, 1)` to the transformed coordinates. The
    /// rotation follows the extension's worked example (its quadrant example rotates the image
    /// clockwise): `u' = sx cos(r) u + sy sin(r) v + ox`, `v' = -sx sin(r) u + sy cos(r) v + oy`.
    pub fn rows(&self) -> [[f32; 3]; 2] {
        let (s, c) = self.rotation.sin_cos();
        [
            [self.scale.x * c, self.scale.y * s, self.offset.x],
            [-self.scale.x * s, self.scale.y * c, self.offset.y],
        ]
    }

    /// Applies the transform to `uv`.
    pub fn apply(&self, uv: Vec2) -> Vec2 {
        let [a, b] = self.rows();
        Vec2::new(
            a[0] * uv.x + a[1] * uv.y + a[2],
            b[0] * uv.x + b[1] * uv.y + b[2],
        )
    }

    /// Whether every parameter is finite.
    pub fn is_finite(&self) -> bool {
        self.offset.is_finite() && self.rotation.is_finite() && self.scale.is_finite()
    }
}

/// A texture as a material slot uses it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TextureRef {
    /// Index into `Scene::textures`.
    pub texture: u32,
    /// Transform of the texture coordinates before the lookup.
    pub transform: UvTransform,
    /// Wrap modes along u and v.
    pub wrap: [WrapMode; 2],
}

impl TextureRef {
    /// Texture `texture`, untransformed, repeating.
    pub fn new(texture: u32) -> Self {
        Self {
            texture,
            transform: UvTransform::IDENTITY,
            wrap: [WrapMode::Repeat; 2],
        }
    }

    /// Whether the lookup transforms coordinates or wraps other than by repeating (what
    /// `HAS_TEXTURE_TRANSFORMS` compiles in).
    pub fn is_transformed(&self) -> bool {
        self.transform != UvTransform::IDENTITY || self.wrap != [WrapMode::Repeat; 2]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_extensions_quadrant_example() {
        // KHR_texture_transform's example: offset (0, 1), a quarter turn, half scale "utilizes
        // only the lower left quadrant of the source image, rotated clockwise 90°".
        let t = UvTransform {
            offset: Vec2::new(0.0, 1.0),
            rotation: std::f32::consts::FRAC_PI_2,
            scale: Vec2::splat(0.5),
        };
        for (uv, want) in [
            (Vec2::new(0.0, 0.0), Vec2::new(0.0, 1.0)),
            (Vec2::new(1.0, 0.0), Vec2::new(0.0, 0.5)),
            (Vec2::new(0.0, 1.0), Vec2::new(0.5, 1.0)),
            (Vec2::new(1.0, 1.0), Vec2::new(0.5, 0.5)),
        ] {
            assert!(
                t.apply(uv).abs_diff_eq(want, 1e-6),
                "{uv} -> {}",
                t.apply(uv)
            );
        }
        assert_eq!(
            UvTransform::IDENTITY.apply(Vec2::new(0.3, 0.7)),
            Vec2::new(0.3, 0.7)
        );
    }
}
