#[allow(dead_code)]
#[path = "svgf_common.rs"]
mod common;
use common::*;
use lucid_engine::capture::{rec709_luminance, ImageData};
use lucid_engine::scene::builtin::{build_with, BuildOptions};
use lucid_tests::context;

fn diff(a: &ImageData, b: &ImageData) -> f64 {
    let m: f64 = b
        .pixels
        .iter()
        .map(|p| rec709_luminance(*p) as f64)
        .sum::<f64>()
        / b.pixels.len() as f64;
    a.pixels
        .iter()
        .zip(&b.pixels)
        .map(|(x, y)| (rec709_luminance(*x) - rec709_luminance(*y)).abs() as f64)
        .sum::<f64>()
        / a.pixels.len() as f64
        / m
}

#[test]
fn debug() {
    let ctx = context(false);
    let scene = build_with("classroom", &BuildOptions { detail: 0.05 }).unwrap();
    let c0 = scene.camera;
    let mut c1 = c0;
    c1.position += glam::Vec3::new(0.0005, 0.0, 0.0);
    for (spp, frames) in [(16, 8), (8, 16), (4, 32)] {
        let a = reference(&ctx, &scene, c0, spp, frames);
        let b = reference(&ctx, &scene, c0, spp, frames);
        let c = reference(&ctx, &scene, c1, spp, frames);
        eprintln!(
            "{spp}x{frames}: same {:.4} shifted {:.4} mean {:?}",
            diff(&a, &b),
            diff(&a, &c),
            a.mean_rgb()
        );
    }
}
