//! Another renderer's images for `lucid converge --external NAME=FILE`: a series of (samples per
//! pixel, time, image) rendered elsewhere (e.g. Mitsuba 3 by `bench/mitsuba/converge_cornell.py`),
//! measured with the same metrics against the same reference as Lucid's configurations, so both
//! renderers share the error-against-time charts.
//!
//! `FILE` is JSON: `{"renderer": "...", "device": "...", "time": "wall", "points": [{"spp": 16,
//! "ms": 12.5, "image": "mitsuba_16.exr"}, ...]}`, image paths relative to the file; other keys
//! are ignored.

use anyhow::{bail, ensure, Context as _};
use lucid_engine::capture::{self, ImageData};
use lucid_engine::metrics::PreparedReference;
use lucid_passes::tradeoff::Measurement;
use serde::Deserialize;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// `NAME=FILE`: the series' name in the charts and its JSON file.
#[derive(Clone, Debug)]
pub struct ExternalArg {
    /// The name in the legend and the tables.
    pub name: String,
    /// The series' JSON file.
    pub file: PathBuf,
}

impl FromStr for ExternalArg {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.split_once('=') {
            Some((name, file)) if !name.trim().is_empty() && !file.is_empty() => Ok(Self {
                name: name.trim().to_string(),
                file: PathBuf::from(file),
            }),
            _ => Err(format!(
                "expected NAME=FILE (e.g. \"Mitsuba 3\"=series.json), got {s:?}"
            )),
        }
    }
}

/// The series file as written.
#[derive(Deserialize)]
struct SeriesFile {
    renderer: String,
    #[serde(default)]
    device: Option<String>,
    #[serde(default)]
    time: Option<String>,
    points: Vec<PointFile>,
}

#[derive(Deserialize)]
struct PointFile {
    spp: u32,
    ms: f64,
    image: PathBuf,
}

/// An external series as read: its images loaded and checked.
pub struct ExternalSeries {
    arg: ExternalArg,
    file: SeriesFile,
    images: Vec<ImageData>,
}

/// One image of an external series and its errors.
#[derive(Clone, Debug)]
pub struct ExternalPoint {
    /// Samples per pixel of the image.
    pub spp: u32,
    /// Its time (`ms`, also `frame_ms`) and errors; `frame` is 1 and `target_ms` none: each
    /// image is one render.
    pub measurement: Measurement,
}

/// An external series, measured.
#[derive(Clone, Debug)]
pub struct ExternalResult {
    /// The name given on the command line.
    pub name: String,
    /// The series file.
    pub file: PathBuf,
    /// The renderer as the file names it.
    pub renderer: String,
    /// The device it ran on, as the file names it.
    pub device: Option<String>,
    /// What its times are (`wall` for Mitsuba's), as the file says.
    pub time: Option<String>,
    /// Its images' errors, by increasing samples per pixel.
    pub points: Vec<ExternalPoint>,
}

/// Reads `arg`'s series and loads its images: every image must be `size` and finite, every
/// time positive.
pub fn read(arg: &ExternalArg, size: (u32, u32)) -> anyhow::Result<ExternalSeries> {
    let text = std::fs::read_to_string(&arg.file)
        .with_context(|| format!("reading --external {}", arg.file.display()))?;
    let mut file: SeriesFile = serde_json::from_str(&text)
        .with_context(|| format!("--external {}: not a series file", arg.file.display()))?;
    ensure!(
        !file.points.is_empty(),
        "--external {}: no points",
        arg.file.display()
    );
    file.points.sort_by_key(|p| p.spp);
    let folder = arg.file.parent().unwrap_or(Path::new("."));
    let mut images = Vec::with_capacity(file.points.len());
    for point in &file.points {
        ensure!(
            point.ms.is_finite() && point.ms > 0.0,
            "--external {}: the time of {} spp is {} ms, not a positive number",
            arg.file.display(),
            point.spp,
            point.ms
        );
        let path = folder.join(&point.image);
        let image = capture::load(&path)
            .with_context(|| format!("--external {}: loading its image", arg.file.display()))?;
        if (image.width, image.height) != size {
            bail!(
                "--external {}: {} is {}x{}, --size {}x{}",
                arg.file.display(),
                path.display(),
                image.width,
                image.height,
                size.0,
                size.1
            );
        }
        ensure!(
            !image.has_non_finite(),
            "--external {}: {} has NaN or infinite pixels",
            arg.file.display(),
            path.display()
        );
        images.push(image);
    }
    Ok(ExternalSeries {
        arg: arg.clone(),
        file,
        images,
    })
}

impl ExternalSeries {
    /// Each image's errors against `reference`, as `lucid converge` measures its own.
    pub fn measure(&self, reference: &PreparedReference) -> anyhow::Result<ExternalResult> {
        let points = self
            .file
            .points
            .iter()
            .zip(&self.images)
            .map(|(point, image)| {
                let m = reference
                    .evaluate(image)
                    .with_context(|| format!("measuring {}", point.image.display()))?;
                Ok(ExternalPoint {
                    spp: point.spp,
                    measurement: Measurement {
                        frame: 1,
                        target_ms: None,
                        gpu_ms: point.ms,
                        frame_ms: point.ms,
                        dssim: m.dssim,
                        flip: m.flip,
                        rel_mse: m.rel_mse,
                    },
                })
            })
            .collect::<anyhow::Result<Vec<_>>>()?;
        Ok(ExternalResult {
            name: self.arg.name.clone(),
            file: self.arg.file.clone(),
            renderer: self.file.renderer.clone(),
            device: self.file.device.clone(),
            time: self.file.time.clone(),
            points,
        })
    }
}

impl ExternalResult {
    /// The measurements, by increasing samples per pixel.
    pub fn rows(&self) -> Vec<Measurement> {
        self.points.iter().map(|p| p.measurement).collect()
    }

    /// The legend's name: the given name and the kind of time when the file says it.
    pub fn label(&self) -> String {
        match &self.time {
            Some(time) => format!("{} ({time} time)", self.name),
            None => self.name.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn external_arguments_are_a_name_and_a_file() {
        let arg: ExternalArg = "Mitsuba 3=/tmp/mi/series.json".parse().unwrap();
        assert_eq!(arg.name, "Mitsuba 3");
        assert_eq!(arg.file, PathBuf::from("/tmp/mi/series.json"));
        for bad in ["series.json", "=series.json", "Mitsuba=", " =x"] {
            assert!(bad.parse::<ExternalArg>().is_err(), "{bad:?} accepted");
        }
    }
}
