//! Lucid's FLIP and SSIM against the references people cite, on the committed image pairs of
//! `tests/metrics_reference/` (made by its `make_reference.py`, which says how each reference value
//! was computed): NVIDIA's `flip_evaluator` for LDR-FLIP and HDR-FLIP, scikit-image's
//! `structural_similarity` for SSIM. Every value agrees within 1e-3. No GPU and no Python needed.

use lucid_engine::capture::ImageData;
use lucid_engine::metrics::{flip, hdr_flip, ssim, HdrFlipParams, SsimMode};
use std::path::PathBuf;

const TOLERANCE: f64 = 1e-3;

fn folder() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("metrics_reference")
}

/// The reference and test images of pair `name`: raw little-endian RGB floats, `size` pixels.
fn pair(name: &str, (width, height): (u32, u32)) -> (ImageData, ImageData) {
    let load = |kind: &str| {
        let path = folder().join("pairs").join(format!("{name}_{kind}.f32"));
        let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let floats: Vec<f32> = bytes
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        assert_eq!(
            floats.len(),
            (width * height * 3) as usize,
            "{}",
            path.display()
        );
        let pixels = floats
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2], 1.0])
            .collect();
        ImageData::from_pixels(width, height, pixels).unwrap()
    };
    (load("reference"), load("test"))
}

/// The pairs' size and entries.
fn entries() -> ((u32, u32), Vec<serde_json::Value>) {
    let text = std::fs::read_to_string(folder().join("reference.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let side = |key: &str| json[key].as_u64().unwrap() as u32;
    (
        (side("width"), side("height")),
        json["pairs"].as_array().unwrap().clone(),
    )
}

fn check(name: &str, metric: &str, lucid: f64, reference: f64, failures: &mut Vec<String>) {
    let line = format!("{name} {metric}: Lucid {lucid:.6}, reference {reference:.6}");
    eprintln!("{line}");
    if (lucid - reference).abs() > TOLERANCE {
        failures.push(line);
    }
}

#[test]
fn flip_and_ssim_agree_with_the_reference_implementations() {
    let (size, entries) = entries();
    assert!(entries.len() >= 8, "the committed set");
    let mut failures = Vec::new();
    let (mut ldr, mut hdr) = (0, 0);
    for e in &entries {
        let name = e["name"].as_str().unwrap();
        let (reference, test) = pair(name, size);
        let ppd = e["ppd"].as_f64().unwrap();
        let expected_flip = e["flip"].as_f64().unwrap();
        match e["range"].as_str().unwrap() {
            "ldr" => {
                ldr += 1;
                let f = flip(&test, &reference, ppd).unwrap().mean;
                check(name, "LDR-FLIP", f, expected_flip, &mut failures);
                let s = ssim(&test, &reference, SsimMode::Luminance).unwrap();
                check(name, "SSIM", s, e["ssim"].as_f64().unwrap(), &mut failures);
            }
            "hdr" => {
                hdr += 1;
                let params = HdrFlipParams::for_reference(&reference, ppd);
                let start = e["start_exposure"].as_f64().unwrap();
                let stop = e["stop_exposure"].as_f64().unwrap();
                check(
                    name,
                    "start exposure",
                    params.start_exposure,
                    start,
                    &mut failures,
                );
                check(
                    name,
                    "stop exposure",
                    params.stop_exposure,
                    stop,
                    &mut failures,
                );
                assert_eq!(
                    params.exposures,
                    e["exposures"].as_u64().unwrap() as u32,
                    "{name}"
                );
                let f = hdr_flip(&test, &reference, &params).unwrap().mean;
                check(name, "HDR-FLIP", f, expected_flip, &mut failures);
            }
            other => panic!("{name}: unknown range {other}"),
        }
    }
    assert!(ldr >= 5 && hdr >= 3, "{ldr} LDR and {hdr} HDR pairs");
    assert!(
        failures.is_empty(),
        "disagreements:\n{}",
        failures.join("\n")
    );
}
