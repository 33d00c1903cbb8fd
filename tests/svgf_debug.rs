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
    for method in [Method::Svgf, Method::PerFrame] {
        let scene = build_with("classroom", &BuildOptions { detail: 0.05 }).unwrap();
        let mut r = renderer(&ctx, scene, method);
        let mut prev = frame(&mut r);
        let mut line = String::new();
        for _ in 0..12 {
            let f = frame(&mut r);
            line += &format!("{:.3} ", diff(&f, &prev));
            prev = f;
        }
        eprintln!("{method:?}: {line}");
    }
}
