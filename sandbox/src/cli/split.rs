//! `lucid view --split ALGO/DENOISER[/SPP[/DEPTH]]`: the configuration of the split view's right
//! half, e.g. `bdpt/none` or `pt/svgf/4/12`; what it leaves out is the left half's.

use clap::ValueEnum;
use lucid_sandbox::{Algorithm, Denoiser, RenderSettings, SamplesPerPixel};

/// The parsed `--split` value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SplitSpec {
    algo: Algorithm,
    denoise: Denoiser,
    spp: Option<SamplesPerPixel>,
    max_depth: Option<u32>,
}

impl std::str::FromStr for SplitSpec {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let parts: Vec<&str> = s.split('/').map(str::trim).collect();
        let usage = "ALGO/DENOISER[/SPP[/DEPTH]], e.g. bdpt/none or pt/svgf/4/12";
        if !(2..=4).contains(&parts.len()) {
            return Err(format!("{s:?} is not {usage}"));
        }
        let algo = Algorithm::from_str(parts[0], true)
            .map_err(|_| format!("{:?} in {s:?} is not an algorithm (pt or bdpt)", parts[0]))?;
        let denoise = Denoiser::from_str(parts[1], true)
            .map_err(|_| format!("{:?} in {s:?} is not a denoiser (none or svgf)", parts[1]))?;
        let number = |i: usize, what: &str, max: u32| -> Result<Option<u32>, String> {
            parts
                .get(i)
                .map(|v| {
                    v.parse::<u32>()
                        .ok()
                        .filter(|n| (1..=max).contains(n))
                        .ok_or_else(|| format!("{v:?} in {s:?} is not {what} from 1 to {max}"))
                })
                .transpose()
        };
        Ok(Self {
            algo,
            denoise,
            spp: number(2, "a sample count", 1024)?.and_then(SamplesPerPixel::new),
            max_depth: number(3, "a path length", 64)?,
        })
    }
}

impl SplitSpec {
    /// The right half's settings: `left`'s with what the spec gives replaced.
    pub fn apply(&self, left: &RenderSettings) -> RenderSettings {
        RenderSettings {
            algorithm: self.algo,
            denoiser: self.denoise,
            spp: self.spp.unwrap_or(left.spp),
            max_depth: self.max_depth.unwrap_or(left.max_depth),
            ..*left
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_specs_and_fills_in_the_left_half() {
        let left = RenderSettings {
            spp: SamplesPerPixel::new(2).unwrap(),
            max_depth: 5,
            ..RenderSettings::default()
        };
        let short: SplitSpec = "BDPT/none".parse().unwrap();
        let right = short.apply(&left);
        assert_eq!(right.algorithm, Algorithm::Bidirectional);
        assert_eq!(right.denoiser, Denoiser::None);
        assert_eq!((right.spp.get(), right.max_depth), (2, 5));
        let full: SplitSpec = "pt/svgf/4/12".parse().unwrap();
        let right = full.apply(&left);
        assert_eq!(
            (right.algorithm, right.denoiser),
            (Algorithm::PathTracing, Denoiser::Svgf)
        );
        assert_eq!((right.spp.get(), right.max_depth), (4, 12));
    }

    #[test]
    fn rejects_bad_specs_with_the_reason() {
        for (spec, reason) in [
            ("bdpt", "is not ALGO/DENOISER"),
            ("pt/svgf/1/2/3", "is not ALGO/DENOISER"),
            ("vcm/none", "\"vcm\" in \"vcm/none\" is not an algorithm"),
            ("pt/oidn", "\"oidn\" in \"pt/oidn\" is not a denoiser"),
            ("pt/none/0", "\"0\" in \"pt/none/0\" is not a sample count"),
            (
                "pt/none/4/x",
                "\"x\" in \"pt/none/4/x\" is not a path length",
            ),
        ] {
            let error = spec.parse::<SplitSpec>().unwrap_err();
            assert!(error.contains(reason), "{spec}: {error}");
        }
    }
}
