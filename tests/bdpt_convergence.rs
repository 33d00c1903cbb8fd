//! BDPT and path tracing converge to the same image.

#[path = "bdpt_stats.rs"]
mod bdpt_stats;

use bdpt_stats::Comparison;
use lucid_engine::capture::ImageData;
use lucid_passes::renderer::{Algorithm, Settings};
use lucid_tests::render::{render_accumulated, scene};
use std::time::Instant;

fn variant(name: &str) -> lucid_engine::scene::Scene {
    use glam::{Affine3A, Quat, Vec3};
    use lucid_engine::scene::builtin::{cornell_box, teapot};
    use lucid_engine::scene::{Material, Scene};
    let Some(kind) = name.strip_prefix("pot-") else {
        return scene(name);
    };
    let mut s = Scene::new(name);
    cornell_box::room(&mut s);
    let m = match kind {
        "diffuse" => s.add_material(Material::diffuse("d", Vec3::new(0.8, 0.78, 0.7))),
        "glass" => s.add_material(Material::dielectric("g", 1.5, 0.0)),
        "roughglass" => s.add_material(Material::dielectric("g", 1.5, 0.3)),
        "copper" => s.add_material(Material::conductor(
            "c",
            Vec3::new(0.955, 0.638, 0.538),
            0.05,
        )),
        "mirror" => s.add_material(Material::conductor(
            "c",
            Vec3::new(0.955, 0.638, 0.538),
            0.0,
        )),
        "glassball" => {
            let g = s.add_material(Material::dielectric("g", 1.5, 0.0));
            s.add_sphere(Vec3::new(0.0, -0.6, 0.0), 0.4, g);
            s.validate().unwrap();
            return s;
        }
        _ => panic!("variant"),
    };
    let pot = s.add_mesh(teapot("teapot", m, 6));
    s.add_instance(
        pot,
        Affine3A::from_scale_rotation_translation(
            Vec3::splat(0.2),
            Quat::from_rotation_y(0.5),
            Vec3::new(0.0, -1.0, 0.0),
        ),
        None,
    );
    s.validate().unwrap();
    s
}

fn render(
    name: &str,
    size: u32,
    algorithm: Algorithm,
    spp: u32,
    frames: u32,
    seed: u32,
) -> ImageData {
    let start = Instant::now();
    let settings = Settings {
        algorithm,
        samples_per_pixel: spp,
        seed,
        max_depth: std::env::var("MAXD")
            .map(|s| s.parse().unwrap())
            .unwrap_or(8),
        ..Settings::default()
    };
    let image = render_accumulated(variant(name), (size, size), settings, frames);
    eprintln!(
        "{name} {} seed {seed}: {:.1} s",
        algorithm.short_name(),
        start.elapsed().as_secs_f64()
    );
    image
}

#[test]
fn explore() {
    let name = std::env::var("SCENE").unwrap_or("cornell-box".into());
    let size: u32 = std::env::var("SIZE")
        .map(|s| s.parse().unwrap())
        .unwrap_or(32);
    let spp: u32 = std::env::var("SPP")
        .map(|s| s.parse().unwrap())
        .unwrap_or(16);
    let frames: u32 = std::env::var("FRAMES")
        .map(|s| s.parse().unwrap())
        .unwrap_or(1);
    let a1 = render(&name, size, Algorithm::PathTracing, spp, frames, 1);
    let a2 = render(&name, size, Algorithm::PathTracing, spp, frames, 2);
    let b1 = render(&name, size, Algorithm::Bidirectional, spp, frames, 3);
    let b2 = render(&name, size, Algorithm::Bidirectional, spp, frames, 4);
    let c = Comparison::new([&a1, &a2], [&b1, &b2]);
    eprintln!(
        "{c:?} ratio {:.3} mean diff {:.4}",
        c.ratio(),
        c.mean_difference()
    );
    for (tag, img) in [("a1", &a1), ("a2", &a2), ("b1", &b1), ("b2", &b2)] {
        let bytes: Vec<u8> = img
            .pixels
            .iter()
            .flat_map(|p| p.iter().flat_map(|v| v.to_le_bytes()))
            .collect();
        std::fs::write(format!("/tmp/bdpt_{name}_{tag}.raw"), bytes).unwrap();
    }
}

#[test]
fn explore_ref() {
    let name = std::env::var("SCENE").unwrap_or("caustics".into());
    let f: u32 = std::env::var("FRAMES")
        .map(|s| s.parse().unwrap())
        .unwrap_or(256);
    let pt = render(&name, 32, Algorithm::PathTracing, 4, f * 4, 11);
    let bd = render(&name, 32, Algorithm::Bidirectional, 4, f, 12);
    eprintln!(
        "pt {:?} bd {:?}",
        bdpt_stats::mean(&pt),
        bdpt_stats::mean(&bd)
    );
    for (tag, img) in [("ref_pt", &pt), ("ref_bd", &bd)] {
        let bytes: Vec<u8> = img
            .pixels
            .iter()
            .flat_map(|p| p.iter().flat_map(|v| v.to_le_bytes()))
            .collect();
        std::fs::write(format!("/tmp/bdpt_{name}_{tag}.raw"), bytes).unwrap();
    }
}
