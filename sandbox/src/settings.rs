//! What the panels edit: renderer settings (handed to the frame source) and display settings
//! (applied by the app's tone-mapping pass).

use lucid_engine::capture::{PngEncoding, ToneCurve};

/// The light-transport algorithm.
///
/// ```
/// use lucid_sandbox::Algorithm;
/// for algorithm in Algorithm::ALL {
///     println!("{}", algorithm.label()); // "path tracing", "bidirectional"
/// }
/// assert_eq!(Algorithm::PathTracing.other(), Algorithm::Bidirectional);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Algorithm {
    /// Unidirectional path tracing with next-event estimation.
    #[default]
    PathTracing,
    /// Bidirectional path tracing.
    Bidirectional,
}

impl Algorithm {
    /// Every algorithm, in the order the panel lists them.
    pub const ALL: [Self; 2] = [Self::PathTracing, Self::Bidirectional];

    /// The name shown in the panel.
    pub fn label(self) -> &'static str {
        match self {
            Self::PathTracing => "path tracing",
            Self::Bidirectional => "bidirectional",
        }
    }

    /// The other algorithm (what the split view compares with by default).
    pub fn other(self) -> Self {
        match self {
            Self::PathTracing => Self::Bidirectional,
            Self::Bidirectional => Self::PathTracing,
        }
    }

    /// The renderer's algorithm.
    pub fn renderer(self) -> lucid_passes::renderer::Algorithm {
        match self {
            Self::PathTracing => lucid_passes::renderer::Algorithm::PathTracing,
            Self::Bidirectional => lucid_passes::renderer::Algorithm::Bidirectional,
        }
    }
}

/// The denoiser applied to the noisy frame.
///
/// ```
/// use lucid_sandbox::Denoiser;
/// assert_eq!(Denoiser::default(), Denoiser::Svgf);
/// assert_eq!(Denoiser::None.label(), "none");
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Denoiser {
    /// The raw estimate.
    None,
    /// Spatiotemporal variance-guided filtering.
    #[default]
    Svgf,
    /// The learned recurrent denoiser.
    Neural,
}

impl Denoiser {
    /// Every denoiser, in the order the panel lists them.
    pub const ALL: [Self; 3] = [Self::None, Self::Svgf, Self::Neural];

    /// The name shown in the panel.
    pub fn label(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Svgf => "SVGF",
            Self::Neural => "learned",
        }
    }
}

/// What the renderer is asked to do each frame.
///
/// ```
/// use lucid_sandbox::{Denoiser, RenderSettings};
/// let settings = RenderSettings {
///     spp: 4,
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
    pub spp: u32,
    /// Maximum number of path vertices after the camera.
    pub max_depth: u32,
    /// The denoiser.
    pub denoiser: Denoiser,
    /// Whether samples accumulate over frames while nothing changes.
    pub accumulate: bool,
    /// The image shown: final, or an intermediate of the frame.
    pub view: lucid_passes::debug::debug_view::View,
    /// SVGF's mode and parameters (used when `denoiser` is SVGF).
    pub svgf: lucid_passes::denoise::svgf::SvgfParams,
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
            spp: 1,
            max_depth: 8,
            denoiser: Denoiser::default(),
            accumulate: true,
            view: lucid_passes::debug::debug_view::View::Final,
            svgf: lucid_passes::denoise::svgf::SvgfParams::default(),
        }
    }
}

/// The tone curve of the display transform.
///
/// ```
/// use lucid_sandbox::ToneMapper;
/// assert_eq!(ToneMapper::AgX.curve(), lucid_engine::capture::ToneCurve::AgX);
/// assert_eq!(ToneMapper::ALL.map(ToneMapper::label), ["ACES", "AgX", "clamp"]);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ToneMapper {
    /// The ACES filmic fit.
    #[default]
    Aces,
    /// AgX.
    AgX,
    /// Clamp to `[0, 1]`.
    Clamp,
}

impl ToneMapper {
    /// Every tone mapper, in the order the panel lists them.
    pub const ALL: [Self; 3] = [Self::Aces, Self::AgX, Self::Clamp];

    /// The name shown in the panel.
    pub fn label(self) -> &'static str {
        match self {
            Self::Aces => "ACES",
            Self::AgX => "AgX",
            Self::Clamp => "clamp",
        }
    }

    /// The engine's curve of the same name (used for PNG captures).
    pub fn curve(self) -> ToneCurve {
        match self {
            Self::Aces => ToneCurve::Aces,
            Self::AgX => ToneCurve::AgX,
            Self::Clamp => ToneCurve::Clamp,
        }
    }
}

/// How the HDR output becomes display pixels.
///
/// ```
/// use lucid_sandbox::{DisplaySettings, ToneMapper};
/// let display = DisplaySettings {
///     exposure: 1.0, // one stop brighter
///     tone_mapper: ToneMapper::AgX,
/// };
/// assert_eq!(display.png_encoding().exposure, 1.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DisplaySettings {
    /// Exposure in stops.
    pub exposure: f32,
    /// The tone curve.
    pub tone_mapper: ToneMapper,
}

impl DisplaySettings {
    /// The same transform as the engine's PNG encoding (for captures).
    pub fn png_encoding(&self) -> PngEncoding {
        PngEncoding {
            exposure: self.exposure,
            tone: self.tone_mapper.curve(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_compared_configuration_differs_only_in_the_algorithm() {
        let left = RenderSettings {
            spp: 4,
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
