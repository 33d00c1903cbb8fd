//! The error type of the metrics module.

/// Why a metric could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MetricsError {
    /// The two images do not have the same dimensions.
    #[error("image sizes differ: test is {test_width}x{test_height}, reference is {reference_width}x{reference_height}")]
    SizeMismatch {
        /// Width of the test image.
        test_width: u32,
        /// Height of the test image.
        test_height: u32,
        /// Width of the reference image.
        reference_width: u32,
        /// Height of the reference image.
        reference_height: u32,
    },
    /// An image has no pixels, so no mean exists.
    #[error("image is empty ({width}x{height})")]
    EmptyImage {
        /// Width of the empty image.
        width: u32,
        /// Height of the empty image.
        height: u32,
    },
    /// An image's pixel buffer does not hold `width * height` pixels.
    #[error("image claims {width}x{height} but holds {actual} pixels")]
    MalformedImage {
        /// Claimed width.
        width: u32,
        /// Claimed height.
        height: u32,
        /// Length of the pixel buffer.
        actual: usize,
    },
    /// Test and reference sequences have different numbers of frames.
    #[error("sequence lengths differ: test has {test} frames, reference has {reference}")]
    FrameCountMismatch {
        /// Frames in the test sequence.
        test: usize,
        /// Frames in the reference sequence.
        reference: usize,
    },
    /// A temporal metric needs at least two frames.
    #[error("temporal metrics need at least 2 frames, got {count}")]
    TooFewFrames {
        /// Frames supplied.
        count: usize,
    },
    /// A numeric parameter is outside its valid range.
    #[error("invalid parameter {name} = {value}: {requirement}")]
    InvalidParameter {
        /// Parameter name.
        name: &'static str,
        /// Value supplied.
        value: f64,
        /// What the value must satisfy.
        requirement: &'static str,
    },
    /// The reference's mean luminance, used to normalise a relative metric,
    /// is not a positive finite number.
    #[error(
        "reference mean luminance is {mean}, but a positive finite value is needed to normalise"
    )]
    DegenerateReference {
        /// The reference's mean luminance.
        mean: f64,
    },
}
