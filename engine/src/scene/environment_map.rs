//! Equirectangular environment maps (`lucid render --env FILE.hdr|.exr`): loading, the mapping
//! between directions and image coordinates, and the distribution next-event estimation samples
//! directions from (mirrored in `shaders/common/environment.glsl`).
//!
//! Mapping (y up): `u = 0.5 + atan2(x, -z) / 2π`, `v = acos(y) / π`. The image's top row looks
//! straight up, its bottom row straight down and its centre column along −z (where the default
//! camera looks); u grows towards +x.

use std::f32::consts::PI;
use std::path::Path;

use glam::{Vec2, Vec3};

use super::{luminance, AliasTable, SceneError, TexelData, Texture};

/// The unit direction's image coordinates in `[0, 1]²`.
pub fn direction_to_uv(d: Vec3) -> Vec2 {
    let u = 0.5 + d.x.atan2(-d.z) / (2.0 * PI);
    let v = d.y.clamp(-1.0, 1.0).acos() / PI;
    Vec2::new(u.rem_euclid(1.0), v)
}

/// The unit direction at image coordinates `uv`.
pub fn uv_to_direction(uv: Vec2) -> Vec3 {
    let phi = (uv.x - 0.5) * 2.0 * PI;
    let theta = uv.y * PI;
    let (sin_t, cos_t) = theta.sin_cos();
    Vec3::new(sin_t * phi.sin(), cos_t, -sin_t * phi.cos())
}

fn map_error(path: &Path, message: impl Into<String>) -> SceneError {
    SceneError::EnvironmentMap {
        path: path.to_path_buf(),
        message: message.into(),
    }
}

/// Reads an equirectangular map, Radiance `.hdr` or OpenEXR `.exr` (its RGB, linear), as a float
/// texture; other extensions, unreadable files, a width other than twice the height and
/// non-finite or negative texels are errors naming the file.
pub fn load(path: &Path) -> Result<Texture, SceneError> {
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let (width, height, texels) = match extension.as_deref() {
        Some("hdr") => {
            let bytes = std::fs::read(path).map_err(|source| SceneError::Io {
                path: path.to_path_buf(),
                source,
            })?;
            let image = image::load_from_memory_with_format(&bytes, image::ImageFormat::Hdr)
                .map_err(|e| map_error(path, e.to_string()))?
                .to_rgba32f();
            let (w, h) = image.dimensions();
            let texels = image.pixels().map(|p| [p[0], p[1], p[2], 1.0]).collect();
            (w, h, texels)
        }
        Some("exr") => {
            if !path.exists() {
                return Err(SceneError::Io {
                    path: path.to_path_buf(),
                    source: std::io::Error::from(std::io::ErrorKind::NotFound),
                });
            }
            let image =
                crate::capture::load_exr(path).map_err(|e| map_error(path, e.to_string()))?;
            let texels = image
                .pixels
                .iter()
                .map(|p| [p[0], p[1], p[2], 1.0])
                .collect();
            (image.width, image.height, texels)
        }
        _ => {
            return Err(map_error(
                path,
                "not an environment map: expected a .hdr or .exr file",
            ))
        }
    };
    let texels: Vec<[f32; 4]> = texels;
    if width != 2 * height {
        return Err(map_error(
            path,
            format!(
                "an equirectangular map is twice as wide as high, this one is {width}x{height}"
            ),
        ));
    }
    if let Some(bad) = texels
        .iter()
        .position(|t| t.iter().any(|c| !c.is_finite() || *c < 0.0))
    {
        return Err(map_error(
            path,
            format!(
                "texel ({}, {}) is {:?}: radiance must be finite and not negative",
                bad as u32 % width,
                bad as u32 / width,
                &texels[bad][..3]
            ),
        ));
    }
    let name = path.file_name().map_or_else(
        || "environment".to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    Ok(Texture {
        name,
        width,
        height,
        srgb: false,
        texels: TexelData::RgbaF32(texels),
    })
}

/// The distribution next-event estimation draws environment directions from: the map's cells
/// (texels, or square blocks of them for maps wider than [`Self::MAX_WIDTH`]) in proportion to
/// the mean luminance of the bilinearly filtered map over them times the sine of their centre's
/// polar angle, plus a floor of
/// [`Self::FLOOR`] of the mean weight so every direction (also where bilinear filtering spreads a
/// bright texel) can be drawn; a uniform point within the chosen cell in image coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct EnvironmentDistribution {
    /// Cells across.
    pub width: u32,
    /// Cells down.
    pub height: u32,
    /// One entry per cell, row by row from the top.
    pub table: AliasTable,
}

impl EnvironmentDistribution {
    /// Most cells across: wider maps are averaged in square blocks.
    pub const MAX_WIDTH: u32 = 1024;
    /// Every cell's weight is at least this share of the mean weight.
    pub const FLOOR: f32 = 1e-3;

    /// The distribution of `map` (an equirectangular texture).
    pub fn new(map: &Texture) -> Self {
        let (w, h) = (map.width as usize, map.height as usize);
        let lum: Vec<f32> = (0..w * h)
            .map(|i| luminance(Vec3::from_slice(&map.linear(i)[..3])).max(0.0))
            .collect();
        // The mean over each texel's square of the bilinearly reconstructed radiance the shaders
        // see (repeating around, clamped at the poles): a bright texel's light spreads half a
        // texel into its neighbours, which must be drawn as often as it arrives.
        const TAPS: [(isize, f32); 3] = [(-1, 0.125), (0, 0.75), (1, 0.125)];
        let mut filtered = vec![0.0f32; w * h];
        for y in 0..h {
            for x in 0..w {
                let mut sum = 0.0;
                for (dy, wy) in TAPS {
                    let yy = (y as isize + dy).clamp(0, h as isize - 1) as usize;
                    for (dx, wx) in TAPS {
                        let xx = (x as isize + dx).rem_euclid(w as isize) as usize;
                        sum += wx * wy * lum[yy * w + xx];
                    }
                }
                filtered[y * w + x] = sum;
            }
        }
        let block = map.width.div_ceil(Self::MAX_WIDTH).max(1) as usize;
        let (width, height) = (w.div_ceil(block), h.div_ceil(block));
        let mut weights = Vec::with_capacity(width * height);
        for cy in 0..height {
            let sin_theta = ((cy as f32 + 0.5) / height as f32 * PI).sin();
            for cx in 0..width {
                let (x0, y0) = (cx * block, cy * block);
                let (x1, y1) = ((x0 + block).min(w), (y0 + block).min(h));
                let sum: f32 = (y0..y1)
                    .flat_map(|y| (x0..x1).map(move |x| (x, y)))
                    .map(|(x, y)| filtered[y * w + x])
                    .sum();
                weights.push(sum / ((x1 - x0) * (y1 - y0)) as f32 * sin_theta);
            }
        }
        let mean = weights.iter().sum::<f32>() / weights.len().max(1) as f32;
        let floor = if mean > 0.0 { Self::FLOOR * mean } else { 1.0 };
        for weight in &mut weights {
            *weight += floor;
        }
        Self {
            width: width as u32,
            height: height as u32,
            table: AliasTable::new(&weights),
        }
    }

    /// The solid-angle density of drawing direction `d`.
    pub fn pdf(&self, d: Vec3) -> f32 {
        let uv = direction_to_uv(d);
        let sin_theta = (1.0 - d.y * d.y).max(0.0).sqrt();
        if sin_theta <= 0.0 {
            return 0.0;
        }
        let cx = ((uv.x * self.width as f32) as u32).min(self.width - 1);
        let cy = ((uv.y * self.height as f32) as u32).min(self.height - 1);
        let p = self.table.pdf[(cy * self.width + cx) as usize];
        p * (self.width * self.height) as f32 / (2.0 * PI * PI * sin_theta)
    }

    /// The direction `u` (three uniform numbers) draws, with its solid-angle density (as the
    /// shaders draw it: u.x picks the column and, by its remainder, the alias); `None` for an
    /// empty distribution.
    pub fn sample(&self, u: Vec3) -> Option<(Vec3, f32)> {
        let keep = (u.x * self.table.len() as f32).fract();
        let cell = self.table.sample(u.x, keep)? as u32;
        let uv = Vec2::new(
            ((cell % self.width) as f32 + u.y) / self.width as f32,
            ((cell / self.width) as f32 + u.z) / self.height as f32,
        );
        let d = uv_to_direction(uv);
        Some((d, self.pdf(d)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(width: u32, texel: impl Fn(u32, u32) -> f32) -> Texture {
        let height = width / 2;
        let texels = (0..height)
            .flat_map(|y| (0..width).map(move |x| (x, y)))
            .map(|(x, y)| {
                let v = texel(x, y);
                [v, v, v, 1.0]
            })
            .collect();
        Texture {
            name: "test".into(),
            width,
            height,
            srgb: false,
            texels: TexelData::RgbaF32(texels),
        }
    }

    #[test]
    fn directions_and_image_coordinates_round_trip() {
        assert!((uv_to_direction(Vec2::new(0.5, 0.5)) - Vec3::NEG_Z).length() < 1e-6);
        assert!((uv_to_direction(Vec2::new(0.75, 0.5)) - Vec3::X).length() < 1e-6);
        assert!((uv_to_direction(Vec2::new(0.3, 0.0)) - Vec3::Y).length() < 1e-6);
        for (u, v) in [(0.1, 0.2), (0.6, 0.5), (0.95, 0.9), (0.5, 0.01)] {
            let uv = Vec2::new(u, v);
            let back = direction_to_uv(uv_to_direction(uv));
            assert!((back - uv).length() < 1e-5, "{uv} -> {back}");
        }
    }

    #[test]
    fn the_pdf_integrates_to_one_and_follows_the_light() {
        // Dark everywhere but a bright patch: the patch and the texels its filtered light spills
        // into get nearly all samples, the rest the floor, and the density integrates to 1 over
        // the sphere.
        let texture = map(64, |x, y| {
            if (40..44).contains(&x) && (8..11).contains(&y) {
                100.0
            } else {
                0.0
            }
        });
        let dist = EnvironmentDistribution::new(&texture);
        assert_eq!((dist.width, dist.height), (64, 32));
        let n = 512;
        let mut integral = 0.0f64;
        for j in 0..n {
            for i in 0..2 * n {
                let uv = Vec2::new(
                    (i as f32 + 0.5) / (2 * n) as f32,
                    (j as f32 + 0.5) / n as f32,
                );
                let d = uv_to_direction(uv);
                let d_omega = (2.0 * PI / (2 * n) as f32) * (PI / n as f32) * (uv.y * PI).sin();
                integral += f64::from(dist.pdf(d) * d_omega);
            }
        }
        assert!((integral - 1.0).abs() < 2e-3, "{integral}");
        let mut in_patch = 0;
        for k in 0..1000u32 {
            let u = Vec3::new(
                (k as f32 + 0.5) / 1000.0,
                ((k * 7919) % 1000) as f32 / 1000.0,
                ((k * 104_729) % 1000) as f32 / 1000.0,
            );
            let (d, pdf) = dist.sample(u).expect("a distribution");
            assert!(pdf > 0.0 && (pdf - dist.pdf(d)).abs() <= 1e-4 * pdf);
            let uv = direction_to_uv(d) * Vec2::new(64.0, 32.0);
            in_patch += u32::from((39.0..45.0).contains(&uv.x) && (7.0..12.0).contains(&uv.y));
        }
        assert!(in_patch > 990, "{in_patch} of 1000 samples at the patch");
    }

    #[test]
    fn large_maps_are_averaged_in_blocks() {
        let texture = map(2048 + 64, |_, _| 1.0);
        let dist = EnvironmentDistribution::new(&texture);
        assert_eq!((dist.width, dist.height), (704, 352));
    }

    #[test]
    fn bad_files_are_errors_naming_them() {
        let dir = std::env::temp_dir().join(format!("lucid-env-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let missing = load(&dir.join("missing.hdr")).unwrap_err().to_string();
        assert!(missing.contains("missing.hdr"), "{missing}");
        let png = dir.join("sky.png");
        std::fs::write(&png, b"not an image").unwrap();
        let wrong = load(&png).unwrap_err().to_string();
        assert!(
            wrong.contains("sky.png") && wrong.contains(".hdr or .exr"),
            "{wrong}"
        );
        let garbage = dir.join("sky.hdr");
        std::fs::write(&garbage, b"#?RADIANCE\ngarbage").unwrap();
        let corrupt = load(&garbage).unwrap_err().to_string();
        assert!(corrupt.contains("sky.hdr"), "{corrupt}");
    }
}
