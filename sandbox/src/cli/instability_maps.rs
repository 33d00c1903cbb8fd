//! `lucid evaluate --maps`: where each method flickers. Per method, `maps/<method>.png`, its
//! per-pixel temporal instability in false colour (viridis; every method on one scale, from 0 to
//! the largest 99.5th percentile among the methods, brighter pixels clipped to its top), and
//! `maps/by_brightness.csv`, the share of each method's instability from the pixels of each band
//! of the reference's brightness (relative to its mean): flicker on bright pixels weighs more in
//! a measure taken on HDR luminance.

use anyhow::Context as _;
use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder};
use lucid_engine::atomic_write::write_atomic;
use lucid_engine::capture::ImageData;
use lucid_engine::metrics::{instability_map, BrightnessBand, InstabilityMap};
use plotters::prelude::ViridisRGB;
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Where the brightness bands split, in multiples of the reference's mean luminance.
pub const BRIGHTNESS_EDGES: [f64; 4] = [0.1, 0.5, 2.0, 8.0];

/// The quantile of the per-pixel instability, over all methods, that the colour scale tops at.
const SCALE_QUANTILE: f64 = 0.995;

/// One method's map and bands.
pub struct MethodMap {
    /// The method.
    pub method: String,
    /// Its temporal instability, per pixel.
    pub map: InstabilityMap,
    /// Its shares per brightness band (of [`BRIGHTNESS_EDGES`]).
    pub bands: Vec<BrightnessBand>,
}

/// Computes every method's map against `reference` and writes `dir/maps/`; returns the maps and
/// the folder.
pub fn write(
    dir: &Path,
    methods: &[String],
    frames: &[Vec<ImageData>],
    reference: &[ImageData],
) -> anyhow::Result<(Vec<MethodMap>, PathBuf)> {
    let maps = methods
        .par_iter()
        .zip(frames)
        .map(|(method, frames)| {
            let map = instability_map(frames, reference)
                .with_context(|| format!("the instability map of {method}"))?;
            let bands = map.by_brightness(&BRIGHTNESS_EDGES);
            Ok(MethodMap {
                method: method.clone(),
                map,
                bands,
            })
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let folder = dir.join("maps");
    std::fs::create_dir_all(&folder).with_context(|| format!("creating {}", folder.display()))?;
    let top = maps
        .iter()
        .map(|m| quantile(&m.map.instability, SCALE_QUANTILE))
        .fold(0.0, f64::max)
        .max(1e-12);
    for m in &maps {
        let path = folder.join(format!("{}.png", m.method));
        write_atomic(&path, &false_colour_png(&m.map, top)?)
            .with_context(|| format!("writing {}", path.display()))?;
    }
    let csv = folder.join("by_brightness.csv");
    write_atomic(&csv, to_csv(&maps, top).as_bytes())
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
fn false_colour_png(map: &InstabilityMap, top: f64) -> anyhow::Result<Vec<u8>> {
    let rgb: Vec<u8> = map
        .instability
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

/// `method,from,to,pixels,instability_share,instability` per method and band (`instability` the
/// band's part of the method's mean), then the colour scale's top as a comment.
fn to_csv(maps: &[MethodMap], top: f64) -> String {
    let mut out = String::from("method,from,to,pixels,instability_share,instability\n");
    for m in maps {
        let mean = m.map.mean();
        for b in &m.bands {
            let _ = writeln!(
                out,
                "{},{},{},{:.6},{:.6},{:.6}",
                m.method,
                b.from,
                b.to,
                b.pixels,
                b.instability,
                b.instability * mean
            );
        }
    }
    let _ = writeln!(out, "# colour scale of the maps: 0 to {top:.6}");
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
