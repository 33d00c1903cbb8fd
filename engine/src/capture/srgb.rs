//! The sRGB transfer functions (IEC 61966-2-1).

/// Linear → sRGB-encoded (the OETF). Input is clamped to `[0, 1]`; NaN maps
/// to 0.
pub fn srgb_encode(linear: f32) -> f32 {
    let v = if linear.is_nan() {
        0.0
    } else {
        linear.clamp(0.0, 1.0)
    };
    if v <= 0.003_130_8 {
        12.92 * v
    } else {
        1.055 * v.powf(1.0 / 2.4) - 0.055
    }
}

/// sRGB-encoded → linear (the inverse of [`srgb_encode`]). Input is clamped to
/// `[0, 1]`; NaN maps to 0.
pub fn srgb_decode(encoded: f32) -> f32 {
    let v = if encoded.is_nan() {
        0.0
    } else {
        encoded.clamp(0.0, 1.0)
    };
    if v <= 0.040_45 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}
