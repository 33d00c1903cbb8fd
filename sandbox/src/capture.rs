//! Writing captures: F12 saves the HDR output as EXR and, through the current display transform,
//! as PNG; `--screenshot-after` saves the final window image (UI included) as PNG.

use super::settings::DisplaySettings;
use anyhow::Context as _;
use lucid_engine::capture::{self, ExrPrecision, ImageData};
use std::path::{Path, PathBuf};

/// The base name of a capture: `lucid-<seconds since the epoch>-f<frame>`.
pub fn capture_stem(unix_seconds: u64, frame: u64) -> String {
    format!("lucid-{unix_seconds}-f{frame}")
}

/// Saves an F12 capture as `<dir>/<stem>.exr` and `<dir>/<stem>.png` (creating `dir`); returns
/// both paths.
pub fn save_capture(
    dir: &Path,
    stem: &str,
    hdr: &ImageData,
    display: &DisplaySettings,
) -> anyhow::Result<[PathBuf; 2]> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let exr = dir.join(format!("{stem}.exr"));
    let png = dir.join(format!("{stem}.png"));
    capture::save_exr(&exr, hdr, ExrPrecision::F32)
        .with_context(|| format!("writing {}", exr.display()))?;
    capture::save_png(&png, hdr, &display.png_encoding())
        .with_context(|| format!("writing {}", png.display()))?;
    Ok([exr, png])
}

/// Saves an image that is already display-encoded (a read-back window image) as an 8-bit PNG.
pub fn save_display_png(path: &Path, image: &ImageData) -> anyhow::Result<()> {
    let bytes: Vec<u8> = image
        .pixels
        .iter()
        .flat_map(|p| p.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8))
        .collect();
    image::save_buffer(
        path,
        &bytes,
        image.width,
        image.height,
        image::ExtendedColorType::Rgba8,
    )
    .with_context(|| format!("writing {}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_writes_captures() {
        assert_eq!(capture_stem(1700000000, 42), "lucid-1700000000-f42");
        let dir = std::env::temp_dir().join(format!("lucid-capture-test-{}", std::process::id()));
        let image = ImageData {
            width: 2,
            height: 1,
            pixels: vec![[0.5, 2.0, 0.0, 1.0], [0.0, 0.25, 1.0, 1.0]],
        };
        let [exr, png] = save_capture(&dir, "x", &image, &DisplaySettings::default()).unwrap();
        assert!(exr.exists() && png.exists());
        let shot = dir.join("shot.png");
        save_display_png(&shot, &image).unwrap();
        let back = capture::load_png(&shot).unwrap();
        assert_eq!((back.width, back.height), (2, 1));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
