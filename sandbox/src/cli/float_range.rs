//! The parser of every floating-point option: a finite number in a range, so `NaN` or `inf` is
//! refused with the option's name and range instead of rendering a black image.

/// Parses a finite `f32` from `min` to `max` (inclusive).
pub fn finite_f32(
    min: f32,
    max: f32,
) -> impl Fn(&str) -> Result<f32, String> + Clone + Send + Sync + 'static {
    move |text| {
        let expected = || format!("must be a finite number from {min} to {max}");
        match text.trim().parse::<f32>() {
            Ok(v) if v.is_finite() && (min..=max).contains(&v) => Ok(v),
            _ => Err(expected()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::finite_f32;

    #[test]
    fn only_finite_numbers_in_range_pass() {
        let parse = finite_f32(-64.0, 64.0);
        assert_eq!(parse("-2.5"), Ok(-2.5));
        assert_eq!(parse("64"), Ok(64.0));
        for bad in [
            "NaN", "nan", "inf", "-inf", "infinity", "65", "-1e9", "", "two",
        ] {
            assert_eq!(
                parse(bad),
                Err("must be a finite number from -64 to 64".to_string()),
                "{bad}"
            );
        }
    }
}
