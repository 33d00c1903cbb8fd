//! Comma-separated lists on the command line (`--algos pt,bdpt`, `--spp 1,2,4`): not empty, no
//! entry twice, each entry checked.

use clap::ValueEnum;
use lucid_passes::renderer::SamplesPerPixel;

/// A comma-separated list given on the command line: not empty, no entry twice.
#[derive(Clone, Debug, PartialEq)]
pub struct List<T>(pub Vec<T>);

/// Parses a comma-separated list of `what`s, each by `parse`: an empty list, an empty entry or an
/// entry given twice is an error.
fn list<T: PartialEq>(
    what: &'static str,
    parse: impl Fn(&str) -> Result<T, String>,
) -> impl Fn(&str) -> Result<List<T>, String> {
    move |text| {
        let mut items = Vec::new();
        if text.trim().is_empty() {
            return Err(format!("the list is empty: give at least one {what}"));
        }
        for entry in text.split(',').map(str::trim) {
            if entry.is_empty() {
                return Err(format!("an empty {what} in {text:?}"));
            }
            let item = parse(entry)?;
            if items.contains(&item) {
                return Err(format!("{what} {entry:?} is listed twice"));
            }
            items.push(item);
        }
        Ok(List(items))
    }
}

/// Parses a list of a `clap::ValueEnum`'s names (any case).
pub fn value_list<T: ValueEnum + PartialEq + Clone + Send + Sync + 'static>(
    what: &'static str,
) -> impl Fn(&str) -> Result<List<T>, String> + Clone + Send + Sync + 'static {
    move |text| {
        list(what, |entry| {
            T::from_str(entry, true).map_err(|_| {
                let names: Vec<String> = T::value_variants()
                    .iter()
                    .filter_map(|v| v.to_possible_value())
                    .map(|v| v.get_name().to_string())
                    .collect();
                format!("unknown {what} {entry:?} (expected {})", names.join(", "))
            })
        })(text)
    }
}

/// Parses `--spp`: a list of sample counts from 1 to 65536.
pub fn spp_list() -> impl Fn(&str) -> Result<List<SamplesPerPixel>, String> + Clone + Send + Sync {
    move |text| {
        list("sample count", |entry| {
            entry
                .parse::<u32>()
                .ok()
                .filter(|n| (1..=65536).contains(n))
                .and_then(SamplesPerPixel::new)
                .ok_or_else(|| format!("{entry:?} is not a sample count from 1 to 65536"))
        })(text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lucid_passes::renderer::{Algorithm, Denoiser};

    #[test]
    fn lists_are_checked() {
        let algos = value_list::<Algorithm>("algorithm");
        assert_eq!(
            algos("pt, BDPT"),
            Ok(List(vec![Algorithm::PathTracing, Algorithm::Bidirectional]))
        );
        assert_eq!(
            algos("pt,mlt").unwrap_err(),
            "unknown algorithm \"mlt\" (expected pt, bdpt, pt-wavefront, pt-wavefront-binned)"
        );
        assert!(algos("").unwrap_err().contains("empty"));
        assert!(algos("pt,,bdpt").unwrap_err().contains("empty"));
        assert!(algos("pt,pt").unwrap_err().contains("twice"));
        let spp = spp_list();
        assert_eq!(
            spp("1,4")
                .unwrap()
                .0
                .iter()
                .map(|s| s.get())
                .collect::<Vec<_>>(),
            [1, 4]
        );
        for bad in ["0", "1,0", "-1", "x", "65537"] {
            assert!(spp(bad).is_err(), "{bad}");
        }
        let denoisers = value_list::<Denoiser>("denoiser");
        assert!(denoisers("none,oidn")
            .unwrap_err()
            .contains("none, svgf, neural"));
    }
}
