//! [`ImageData`]: a linear RGBA float image held in memory.

use super::CaptureError;

/// Rec.709 / sRGB relative-luminance weights for linear R, G and B.
const REC709_WEIGHTS: [f32; 3] = [0.2126, 0.7152, 0.0722];

/// Relative luminance of a linear RGBA pixel with Rec.709 weights; alpha is
/// ignored.
pub fn rec709_luminance(pixel: [f32; 4]) -> f32 {
    REC709_WEIGHTS[0] * pixel[0] + REC709_WEIGHTS[1] * pixel[1] + REC709_WEIGHTS[2] * pixel[2]
}

/// A linear (scene-referred) RGBA image, row-major with the top row first.
///
/// Pixel `(x, y)` lives at `pixels[y * width + x]`. The fields are public;
/// code that changes them must keep `pixels.len() == width * height`, which
/// every constructor guarantees.
#[derive(Debug, Clone, PartialEq)]
pub struct ImageData {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height` linear RGBA pixels, row-major, top row first.
    pub pixels: Vec<[f32; 4]>,
}

impl ImageData {
    /// An opaque black image (`[0, 0, 0, 1]` everywhere) of the given size.
    pub fn new(width: u32, height: u32) -> Self {
        let count = width as usize * height as usize;
        Self {
            width,
            height,
            pixels: vec![[0.0, 0.0, 0.0, 1.0]; count],
        }
    }

    /// Wraps an existing pixel buffer, checking that it holds exactly
    /// `width * height` pixels.
    pub fn from_pixels(
        width: u32,
        height: u32,
        pixels: Vec<[f32; 4]>,
    ) -> Result<Self, CaptureError> {
        let image = Self {
            width,
            height,
            pixels,
        };
        image.validate()?;
        Ok(image)
    }

    /// Checks that `pixels` holds exactly `width * height` pixels, which code
    /// editing the public fields could have broken.
    pub fn validate(&self) -> Result<(), CaptureError> {
        let expected = (self.width as usize).saturating_mul(self.height as usize);
        if self.pixels.len() == expected {
            return Ok(());
        }
        Err(CaptureError::PixelCountMismatch {
            width: self.width,
            height: self.height,
            expected,
            actual: self.pixels.len(),
        })
    }

    /// Number of pixels, `width * height`.
    pub fn pixel_count(&self) -> usize {
        self.pixels.len()
    }

    /// The pixel at `(x, y)`, or `None` outside the image.
    pub fn get(&self, x: u32, y: u32) -> Option<[f32; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.pixels
            .get(y as usize * self.width as usize + x as usize)
            .copied()
    }

    /// Rec.709 relative luminance of the pixel at `(x, y)`, or `None` outside
    /// the image.
    pub fn luminance(&self, x: u32, y: u32) -> Option<f32> {
        self.get(x, y).map(rec709_luminance)
    }

    /// Mean of the R, G and B channels over all pixels, accumulated in `f64`.
    /// An empty image yields zeros; non-finite pixels propagate.
    pub fn mean_rgb(&self) -> [f64; 3] {
        if self.pixels.is_empty() {
            return [0.0; 3];
        }
        let sum = self.pixels.iter().fold([0.0f64; 3], |acc, p| {
            [
                acc[0] + f64::from(p[0]),
                acc[1] + f64::from(p[1]),
                acc[2] + f64::from(p[2]),
            ]
        });
        let n = self.pixels.len() as f64;
        [sum[0] / n, sum[1] / n, sum[2] / n]
    }

    /// Whether any channel (alpha included) of any pixel is NaN or infinite.
    pub fn has_non_finite(&self) -> bool {
        self.pixels.iter().flatten().any(|v| !v.is_finite())
    }
}
