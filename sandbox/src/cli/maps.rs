//! `lucid evaluate --maps`: where each method flickers and where it differs from the reference.
//! Per method, `maps/<method>.png`, its per-pixel temporal instability, and
//! `maps/<method>.flip.png`, its per-pixel FLIP averaged over the frames, in false colour
//! (viridis; each measure on one scale for every method, from 0 to the largest 99.5th percentile
//! among the methods, brighter pixels clipped to its top), and `maps/by_brightness.csv`, the share
//! of each method's instability and FLIP from the pixels of each band of the reference's
//! brightness (relative to its mean): flicker on bright pixels weighs more in a measure taken on
//! HDR luminance. The same file has, per band, how much of the reference's light the method keeps
//! (`light`: its luminance over the reference's, averaged over the frames): a denoiser that clamps
//! away a caustic that only rare paths find keeps much less than 1 in the brightest band.

use anyhow::Context as _;
use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder};
use lucid_engine::atomic_write::write_atomic;
use lucid_engine::capture::{ImageData, PngEncoding};
use lucid_engine::metrics::{flip_map, instability_map, light_map, BrightnessBand, PixelMap};
use plotters::prelude::ViridisRGB;
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Where the brightness bands split, in multiples of the reference's mean luminance.
pub const BRIGHTNESS_EDGES: [f64; 4] = [0.1, 0.5, 2.0, 8.0];

/// The quantile of the per-pixel measure, over all methods, that a colour scale tops at.
const SCALE_QUANTILE: f64 = 0.995;

/// One measure's map of one method, and its bands.
pub struct Measured {
    /// Per pixel.
    pub map: PixelMap,
    /// Its shares per brightness band (of [`BRIGHTNESS_EDGES`]).
    pub bands: Vec<BrightnessBand>,
}

impl Measured {
    fn new(map: PixelMap) -> Self {
        let bands = map.by_brightness(&BRIGHTNESS_EDGES);
        Self { map, bands }
    }

    /// The share of the measure from the pixels at least `from` times the mean brightness.
    pub fn share_from(&self, from: f64) -> f64 {
        self.bands
            .iter()
            .filter(|b| b.from >= from)
            .map(|b| b.share)
            .sum()
    }
}

/// One method's maps.
pub struct MethodMaps {
    /// The method.
    pub method: String,
    /// Its temporal instability.
    pub instability: Measured,
    /// Its FLIP.
    pub flip: Measured,
    /// Its luminance averaged over the frames, on the reference's brightness scale.
    pub light: Measured,
}

impl MethodMaps {
    /// The share of the reference's light the method keeps in the pixels at least `from` times the
    /// mean brightness (1 where the reference has none there).
    pub fn light_kept_from(&self, from: f64) -> f64 {
        light_kept(self.light.bands.iter().filter(|b| b.from >= from))
    }
}

/// The share of the reference's light that `bands` of a light map keep (1 where the reference has
/// none in them).
fn light_kept<'a>(bands: impl IntoIterator<Item = &'a BrightnessBand>) -> f64 {
    let (kept, reference) = bands.into_iter().fold((0.0, 0.0), |(kept, reference), b| {
        (
            kept + b.mean * b.pixels,
            reference + b.brightness * b.pixels,
        )
    });
    if reference > 0.0 {
        kept / reference
    } else {
        1.0
    }
}

/// Computes every method's maps against `reference` (FLIP on the frames display-mapped by
/// `display`) and writes `dir/maps/`; returns the maps and the folder.
pub fn write(
    dir: &Path,
    methods: &[String],
    frames: &[Vec<ImageData>],
    reference: &[ImageData],
    display: &PngEncoding,
) -> anyhow::Result<(Vec<MethodMaps>, PathBuf)> {
    let maps = methods
        .par_iter()
        .zip(frames)
        .map(|(method, frames)| {
            let instability = instability_map(frames, reference)
                .with_context(|| format!("the instability map of {method}"))?;
            let flip = flip_map(frames, reference, display)
                .with_context(|| format!("the FLIP map of {method}"))?;
            let light = light_map(frames, reference)
                .with_context(|| format!("the light map of {method}"))?;
            Ok(MethodMaps {
                method: method.clone(),
                instability: Measured::new(instability),
                flip: Measured::new(flip),
                light: Measured::new(light),
            })
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let folder = dir.join("maps");
    std::fs::create_dir_all(&folder).with_context(|| format!("creating {}", folder.display()))?;
    let top = |measure: fn(&MethodMaps) -> &Measured| {
        maps.iter()
            .map(|m| quantile(&measure(m).map.values, SCALE_QUANTILE))
            .fold(0.0, f64::max)
            .max(1e-12)
    };
    let tops = (top(|m| &m.instability), top(|m| &m.flip));
    for m in &maps {
        for (name, measured, top) in [
            (format!("{}.png", m.method), &m.instability, tops.0),
            (format!("{}.flip.png", m.method), &m.flip, tops.1),
        ] {
            let path = folder.join(name);
            write_atomic(&path, &false_colour_png(&measured.map, top)?)
                .with_context(|| format!("writing {}", path.display()))?;
        }
    }
    let csv = folder.join("by_brightness.csv");
    write_atomic(&csv, to_csv(&maps, tops).as_bytes())
        .with_context(|| format!("writing {}", csv.display()))?;
    Ok((maps, folder))
}

/// The `q` quantile of `values` (0 for none).
fn quantile(values: &[f64], q: f64) -> f64 {
    let mut sorted: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if sorted.is_empty() {
        return 0.0;
    }
    sorted.sort_by(f64::total_cmp);
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

/// The map as a PNG, 0 to `top` in viridis.
fn false_colour_png(map: &PixelMap, top: f64) -> anyhow::Result<Vec<u8>> {
    let rgb: Vec<u8> = map
        .values
        .iter()
        .flat_map(|&v| {
            let c = ViridisRGB::get_color((v / top).clamp(0.0, 1.0));
            [c.0, c.1, c.2]
        })
        .collect();
    let mut png = Vec::new();
    PngEncoder::new(&mut png).write_image(&rgb, map.width, map.height, ExtendedColorType::Rgb8)?;
    Ok(png)
}

/// `method,from,to,pixels,instability_share,instability,flip_share,flip,light` per method and
/// band (`instability` and `flip` the band's parts of the method's means, `light` the share of the
/// band's reference light the method keeps), then the colour scales' tops as a comment.
fn to_csv(maps: &[MethodMaps], tops: (f64, f64)) -> String {
    let mut out =
        String::from("method,from,to,pixels,instability_share,instability,flip_share,flip,light\n");
    for m in maps {
        let (instability, flip) = (m.instability.map.mean(), m.flip.map.mean());
        for ((b, f), l) in m
            .instability
            .bands
            .iter()
            .zip(&m.flip.bands)
            .zip(&m.light.bands)
        {
            let _ = writeln!(
                out,
                "{},{},{},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6}",
                m.method,
                b.from,
                b.to,
                b.pixels,
                b.share,
                b.share * instability,
                f.share,
                f.share * flip,
                light_kept([l])
            );
        }
    }
    let _ = writeln!(
        out,
        "# colour scales of the maps: instability 0 to {:.6}, FLIP 0 to {:.6}",
        tops.0, tops.1
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_pick_from_the_sorted_finite_values() {
        let values = [3.0, f64::NAN, 1.0, 2.0, 4.0, 0.0];
        assert_eq!(quantile(&values, 0.0), 0.0);
        assert_eq!(quantile(&values, 0.5), 2.0);
        assert_eq!(quantile(&values, 1.0), 4.0);
        assert_eq!(quantile(&[], 0.5), 0.0);
    }
}
