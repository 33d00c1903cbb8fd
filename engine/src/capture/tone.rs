//! Display encoding of linear images: exposure, tone curve, sRGB OETF.
//!
//! The owner of the display transform: the curves ([`ToneCurve`]), the encoding ([`PngEncoding`])
//! and their CPU implementation, the reference for PNG export and metrics. The GPU pass
//! (`lucid_passes::tonemap`, used by headless renders and by the window through `lucid_present`)
//! implements the same transform and is tested against this one.

use super::{srgb_encode, ImageData};
use rayon::prelude::*;

/// Inputs above this are treated as this, so that `+inf` maps to white and
/// the rational tone curves never divide infinity by infinity.
const MAX_SCENE_VALUE: f64 = 1.0e30;

/// How linear scene values are compressed into the displayable `[0, 1]`
/// range before sRGB encoding.
///
/// ```
/// use lucid_engine::capture::ToneCurve;
/// assert_eq!(ToneCurve::ALL.map(ToneCurve::label), ["ACES", "AgX", "clamp"]);
/// assert_eq!(ToneCurve::ALL.map(ToneCurve::short_name), ["aces", "agx", "clamp"]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ToneCurve {
    /// Clamp each channel to `[0, 1]`.
    #[default]
    Clamp,
    /// Krzysztof Narkowicz's per-channel fit of the ACES filmic curve,
    /// `x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14)` (without the fit's
    /// optional 0.6 pre-exposure; use [`PngEncoding::exposure`] for that).
    Aces,
    /// AgX-style curve: Troy Sobotka's AgX inset matrix, log2 encoding over
    /// [-12.47, 4.03] EV, Benjamin Wrensch's polynomial fit of the default
    /// contrast sigmoid, outset matrix, then the display 2.2 power back to
    /// linear.
    AgX,
}

/// AgX inset matrix (rows apply to linear Rec.709 RGB).
const AGX_INSET: [[f64; 3]; 3] = [
    [0.842479062253094, 0.0784335999999992, 0.0792237451477643],
    [0.0423282422610123, 0.878468636469772, 0.0791661274605434],
    [0.0423756549057051, 0.0784336, 0.879142973793104],
];

/// AgX outset matrix, the inverse of [`AGX_INSET`].
const AGX_OUTSET: [[f64; 3]; 3] = [
    [1.19687900512017, -0.0980208811401368, -0.0990297440797205],
    [-0.0528968517574562, 1.15190312990417, -0.0989611768448433],
    [-0.0529716355144438, -0.0980434501171241, 1.15107367264116],
];

/// Lower end of AgX's log2 encoding range: `log2(0.18) - 10`, ten stops
/// below middle grey.
const AGX_MIN_EV: f64 = -12.47393;
/// Upper end of AgX's log2 encoding range: `log2(0.18) + 6.5`.
const AGX_MAX_EV: f64 = 4.026069;

fn mul3(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2])
}

fn aces(x: f64) -> f64 {
    (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)
}

fn agx_sigmoid(x: f64) -> f64 {
    let x2 = x * x;
    let x4 = x2 * x2;
    15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x
        - 0.00232
}

fn agx(rgb: [f64; 3]) -> [f64; 3] {
    let range = AGX_MAX_EV - AGX_MIN_EV;
    let encoded = mul3(&AGX_INSET, rgb).map(|v| {
        let ev = v.max(1e-10).log2().clamp(AGX_MIN_EV, AGX_MAX_EV);
        agx_sigmoid((ev - AGX_MIN_EV) / range)
    });
    mul3(&AGX_OUTSET, encoded).map(|v| v.clamp(0.0, 1.0).powf(2.2))
}

impl ToneCurve {
    /// Every tone curve, in the order menus and the command line list them.
    pub const ALL: [ToneCurve; 3] = [ToneCurve::Aces, ToneCurve::AgX, ToneCurve::Clamp];

    /// The short name used on the command line (`aces`, `agx`, `clamp`).
    pub fn short_name(self) -> &'static str {
        match self {
            ToneCurve::Clamp => "clamp",
            ToneCurve::Aces => "aces",
            ToneCurve::AgX => "agx",
        }
    }

    /// The name shown in user interfaces (`ACES`, `AgX`, `clamp`).
    pub fn label(self) -> &'static str {
        match self {
            ToneCurve::Clamp => "clamp",
            ToneCurve::Aces => "ACES",
            ToneCurve::AgX => "AgX",
        }
    }

    /// Maps linear, non-negative scene RGB to linear display RGB in `[0, 1]`.
    /// Negative values and NaN count as 0, `+inf` as very bright.
    pub fn apply(self, rgb: [f32; 3]) -> [f32; 3] {
        let scene = rgb.map(|v| {
            if v.is_nan() {
                0.0
            } else {
                f64::from(v).clamp(0.0, MAX_SCENE_VALUE)
            }
        });
        let display = match self {
            ToneCurve::Clamp => scene,
            ToneCurve::Aces => scene.map(aces),
            ToneCurve::AgX => agx(scene),
        };
        display.map(|v| v.clamp(0.0, 1.0) as f32)
    }
}

/// How a linear image becomes an 8-bit display image: scale by
/// `2^exposure`, apply `tone`, encode with the sRGB OETF.
///
/// The default (0 EV, [`ToneCurve::Clamp`]) keeps values already in `[0, 1]`
/// as they are, so PNG round trips lose only quantisation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PngEncoding {
    /// Exposure adjustment in stops: pixels are multiplied by `2^exposure`.
    pub exposure: f32,
    /// The tone curve applied after exposure.
    pub tone: ToneCurve,
}

impl PngEncoding {
    /// One linear pixel after exposure and tone curve: linear display light
    /// in `[0, 1]`, alpha 1.
    pub fn tone_map_pixel(&self, pixel: [f32; 4]) -> [f32; 4] {
        self.tone_map_scaled(pixel, self.exposure.exp2())
    }

    /// [`Self::tone_map_pixel`] with the exposure's scale `2^exposure` given (computed once per
    /// image).
    fn tone_map_scaled(&self, pixel: [f32; 4], scale: f32) -> [f32; 4] {
        let [r, g, b] = self
            .tone
            .apply([pixel[0] * scale, pixel[1] * scale, pixel[2] * scale]);
        [r, g, b, 1.0]
    }

    /// One linear pixel fully display-encoded: [`Self::tone_map_pixel`]
    /// followed by the sRGB OETF (alpha stays 1). These are the values a PNG
    /// stores, before 8-bit quantisation.
    pub fn encode_pixel(&self, pixel: [f32; 4]) -> [f32; 4] {
        let [r, g, b, a] = self.tone_map_pixel(pixel);
        [srgb_encode(r), srgb_encode(g), srgb_encode(b), a]
    }

    /// The whole image through [`Self::tone_map_pixel`]: linear display light
    /// in `[0, 1]`, the input expected by [`crate::metrics::flip`] for HDR
    /// frames.
    pub fn tone_map(&self, image: &ImageData) -> ImageData {
        let scale = self.exposure.exp2();
        map_image(image, |p| self.tone_map_scaled(p, scale))
    }

    /// The whole image through [`Self::encode_pixel`]: sRGB-encoded `[0, 1]`
    /// values, as stored in a PNG and as compared by display-referred SSIM.
    pub fn to_display(&self, image: &ImageData) -> ImageData {
        let scale = self.exposure.exp2();
        map_image(image, |p| {
            let [r, g, b, a] = self.tone_map_scaled(p, scale);
            [srgb_encode(r), srgb_encode(g), srgb_encode(b), a]
        })
    }
}

fn map_image(image: &ImageData, f: impl Fn([f32; 4]) -> [f32; 4] + Sync) -> ImageData {
    ImageData {
        width: image.width,
        height: image.height,
        pixels: image.pixels.par_iter().map(|&p| f(p)).collect(),
    }
}
