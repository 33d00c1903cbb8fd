//! What the panels edit: renderer settings (handed to the frame source) and display settings
//! (applied by the app's tone-mapping pass). Algorithm, denoiser, samples per pixel and tone curve
//! are the renderer's and the engine's own types (with their panel labels), re-exported here.

pub use lucid_engine::capture::ToneCurve;
pub use lucid_passes::renderer::{Algorithm, Denoiser, EdgeEmission, SamplesPerPixel};

use lucid_engine::capture::PngEncoding;
use lucid_passes::light_transport::bdpt::{MisHeuristic, DEFAULT_CONNECTION_ROULETTE};
use std::num::NonZeroU32;

/// What the renderer is asked to do each frame.
///
/// ```
/// use lucid_sandbox::{Denoiser, RenderSettings, SamplesPerPixel};
/// assert_eq!(RenderSettings::default().denoiser, Denoiser::Svgf);
/// let settings = RenderSettings {
///     spp: SamplesPerPixel::new(4).unwrap(),
///     denoiser: Denoiser::None,
///     ..RenderSettings::default()
/// };
/// assert_eq!(settings.summary(), "path tracing, none, 4 spp, depth 8");
/// assert_eq!(settings.compared().summary(), "bidirectional, none, 4 spp, depth 8");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// The light-transport algorithm.
    pub algorithm: Algorithm,
    /// Samples per pixel per frame.
    pub spp: SamplesPerPixel,
    /// Maximum number of path vertices after the camera.
    pub max_depth: u32,
    /// Cached light vertices each BDPT camera vertex connects to.
    pub bdpt_connections: NonZeroU32,
    /// How BDPT's multiple importance sampling weighs its strategies.
    pub bdpt_mis: MisHeuristic,
    /// BDPT's connection roulette (`Settings::bdpt_connection_roulette`; 0: off).
    pub bdpt_connection_roulette: f32,
    /// The denoiser.
    pub denoiser: Denoiser,
    /// Whether the emission the denoiser adds back is supersampled at emitters' edges.
    pub edge_emission: EdgeEmission,
    /// Whether samples accumulate over frames while nothing changes.
    pub accumulate: bool,
    /// The image shown: final, or an intermediate of the frame.
    pub view: lucid_passes::debug::debug_view::View,
    /// SVGF's mode and parameters (used when `denoiser` is SVGF).
    pub svgf: lucid_passes::denoise::svgf::SvgfParams,
    /// What runs of the learned denoiser's weights (used when `denoiser` is the learned one).
    pub neural: lucid_passes::denoise::neural::NeuralParams,
}

impl RenderSettings {
    /// The split view's default second configuration: these settings with the other algorithm.
    pub fn compared(&self) -> Self {
        Self {
            algorithm: self.algorithm.other(),
            ..*self
        }
    }

    /// A short description for the split view's labels, e.g. `path tracing, SVGF, 1 spp, depth 8`.
    pub fn summary(&self) -> String {
        let mut text = format!(
            "{}, {}, {} spp, depth {}",
            self.algorithm.label(),
            self.denoiser.label(),
            self.spp,
            self.max_depth
        );
        if self.view != lucid_passes::debug::debug_view::View::Final {
            text.push_str(&format!(", {}", self.view.label()));
        }
        text
    }
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            algorithm: Algorithm::default(),
            spp: SamplesPerPixel::ONE,
            max_depth: 8,
            bdpt_connections: NonZeroU32::MIN,
            bdpt_mis: MisHeuristic::Power,
            bdpt_connection_roulette: DEFAULT_CONNECTION_ROULETTE,
            denoiser: Denoiser::Svgf,
            edge_emission: EdgeEmission::ByDenoiser,
            accumulate: true,
            view: lucid_passes::debug::debug_view::View::Final,
            svgf: lucid_passes::denoise::svgf::SvgfParams::default(),
            neural: lucid_passes::denoise::neural::NeuralParams::default(),
        }
    }
}

/// How the HDR output becomes display pixels.
///
/// ```
/// use lucid_sandbox::{DisplaySettings, ToneCurve};
/// assert_eq!(DisplaySettings::default().tone_curve, ToneCurve::Aces);
/// let display = DisplaySettings {
///     exposure: 1.0, // one stop brighter
///     tone_curve: ToneCurve::AgX,
/// };
/// assert_eq!(display.png_encoding().exposure, 1.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DisplaySettings {
    /// Exposure in stops.
    pub exposure: f32,
    /// The tone curve.
    pub tone_curve: ToneCurve,
}

impl Default for DisplaySettings {
    fn default() -> Self {
        Self {
            exposure: 0.0,
            tone_curve: ToneCurve::Aces,
        }
    }
}

impl DisplaySettings {
    /// The same transform as the engine's PNG encoding (for captures).
    pub fn png_encoding(&self) -> PngEncoding {
        PngEncoding {
            exposure: self.exposure,
            tone: self.tone_curve,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_compared_configuration_differs_only_in_the_algorithm() {
        let left = RenderSettings {
            spp: SamplesPerPixel::new(4).unwrap(),
            denoiser: Denoiser::None,
            ..RenderSettings::default()
        };
        let right = left.compared();
        assert_eq!(right.algorithm, Algorithm::Bidirectional);
        assert_eq!(right.compared(), left);
        assert_eq!(left.summary(), "path tracing, none, 4 spp, depth 8");
        let depth_view = RenderSettings {
            view: lucid_passes::debug::debug_view::View::Depth,
            ..right
        };
        assert_eq!(
            depth_view.summary(),
            "bidirectional, none, 4 spp, depth 8, depth"
        );
    }
}
