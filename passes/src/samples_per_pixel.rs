//! Samples per pixel per frame, validated once where settings enter (command line, UI, embedding
//! code): a value of this type is never zero, so the passes and shaders use it as it is.

use std::fmt;
use std::num::NonZeroU32;

/// Samples per pixel per frame: at least one.
///
/// ```
/// use lucid_passes::renderer::SamplesPerPixel;
/// let spp = SamplesPerPixel::new(4).expect("not zero");
/// assert_eq!(spp.get(), 4);
/// assert_eq!(SamplesPerPixel::new(0), None);
/// assert_eq!(
///     SamplesPerPixel::try_from(0).unwrap_err().to_string(),
///     "samples per pixel must be at least 1"
/// );
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct SamplesPerPixel(NonZeroU32);

impl SamplesPerPixel {
    /// One sample per pixel (the default).
    pub const ONE: Self = Self(NonZeroU32::MIN);

    /// `count` samples per pixel, or `None` for 0.
    pub const fn new(count: u32) -> Option<Self> {
        match NonZeroU32::new(count) {
            Some(count) => Some(Self(count)),
            None => None,
        }
    }

    /// The count (at least 1).
    pub const fn get(self) -> u32 {
        self.0.get()
    }
}

impl Default for SamplesPerPixel {
    fn default() -> Self {
        Self::ONE
    }
}

impl TryFrom<u32> for SamplesPerPixel {
    type Error = ZeroSamplesPerPixel;

    fn try_from(count: u32) -> Result<Self, Self::Error> {
        Self::new(count).ok_or(ZeroSamplesPerPixel)
    }
}

impl fmt::Display for SamplesPerPixel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

/// The error of a sample count of 0.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error("samples per pixel must be at least 1")]
pub struct ZeroSamplesPerPixel;
