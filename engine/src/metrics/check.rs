//! Input validation shared by the metrics.

use super::MetricsError;
use crate::capture::ImageData;

/// Checks that `image` is consistent (buffer length matches its size) and
/// has at least one pixel.
pub(super) fn check_image(image: &ImageData) -> Result<(), MetricsError> {
    if image.validate().is_err() {
        return Err(MetricsError::MalformedImage {
            width: image.width,
            height: image.height,
            actual: image.pixels.len(),
        });
    }
    if image.pixels.is_empty() {
        return Err(MetricsError::EmptyImage {
            width: image.width,
            height: image.height,
        });
    }
    Ok(())
}

/// Checks that `test` has the reference's `(width, height)`.
pub(super) fn check_size(
    test: &ImageData,
    (reference_width, reference_height): (u32, u32),
) -> Result<(), MetricsError> {
    if (test.width, test.height) != (reference_width, reference_height) {
        return Err(MetricsError::SizeMismatch {
            test_width: test.width,
            test_height: test.height,
            reference_width,
            reference_height,
        });
    }
    Ok(())
}

/// Checks both images with [`check_image`] and that their sizes agree.
pub(super) fn check_pair(test: &ImageData, reference: &ImageData) -> Result<(), MetricsError> {
    check_size(test, (reference.width, reference.height))?;
    check_image(test)?;
    check_image(reference)
}

/// Checks that a parameter is finite and satisfies `valid`.
pub(super) fn check_parameter(
    name: &'static str,
    value: f64,
    valid: bool,
    requirement: &'static str,
) -> Result<(), MetricsError> {
    if value.is_finite() && valid {
        Ok(())
    } else {
        Err(MetricsError::InvalidParameter {
            name,
            value,
            requirement,
        })
    }
}
