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

/// Parses a finite `f64` from `min` to `max` (inclusive), for options that are written out again
/// (an error target in a report: `0.1` stays `0.1`, not `0.10000000149011612`).
pub fn finite_f64(
    min: f64,
    max: f64,
) -> impl Fn(&str) -> Result<f64, String> + Clone + Send + Sync + 'static {
    move |text| match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && (min..=max).contains(&v) => Ok(v),
        _ => Err(format!("must be a finite number from {min} to {max}")),
    }
}

#[cfg(test)]
mod tests {
    use super::{finite_f32, finite_f64};

    #[test]
    fn finite_f64_keeps_the_written_value() {
        let parse = finite_f64(0.0, 1e6);
        assert_eq!(parse("0.1"), Ok(0.1));
        for bad in ["NaN", "inf", "-0.5", "2e6", ""] {
            assert!(parse(bad).is_err(), "{bad}");
        }
    }

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
