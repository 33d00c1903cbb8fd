//! A game loop with Lucid as a library: a fixed time step moves the tall box of the Cornell box
//! back and forth and sways the camera; every tick renders a frame through `Renderer`.
//!
//! ```sh
//! cargo run --release -p lucid-sandbox --example game_loop -- --frames 120 --out frames/
//! ```
//!
//! It renders headless and writes every `--every`-th frame as a PNG (tone-mapped on the GPU and
//! read back), printing the GPU time of each pass of the last frame.

use anyhow::{bail, Context as _};
use glam::{Affine3A, Vec3};
use lucid_engine::capture::{self, PngEncoding};
use lucid_engine::graph::RenderGraph;
use lucid_engine::scene::builtin;
use lucid_engine::{Context, ContextDesc};
use lucid_passes::renderer::{Renderer, Settings};
use std::path::PathBuf;

/// Simulation steps per second (fixed, independent of how fast frames render).
const TICKS_PER_SECOND: f32 = 60.0;

struct Options {
    frames: u32,
    every: u32,
    size: (u32, u32),
    spp: u32,
    sway: bool,
    out: PathBuf,
}

fn parse() -> anyhow::Result<Options> {
    let mut o = Options {
        frames: 60,
        every: 10,
        size: (256, 256),
        spp: 4,
        sway: true,
        out: PathBuf::from("game_loop_frames"),
    };
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = || args.next().with_context(|| format!("{arg} needs a value"));
        match arg.as_str() {
            "--frames" => o.frames = value()?.parse()?,
            "--every" => o.every = value()?.parse::<u32>()?.max(1),
            "--size" => {
                let v = value()?;
                let (w, h) = v.split_once('x').with_context(|| format!("{v} is not WxH"))?;
                o.size = (w.parse()?, h.parse()?);
            }
            "--out" => o.out = PathBuf::from(value()?),
            "--spp" => o.spp = value()?.parse::<u32>()?.max(1),
            "--no-sway" => o.sway = false,
            other => bail!(
                "unknown argument {other}; use --frames N --every K --size WxH --spp N --no-sway --out DIR"
            ),
        }
    }
    Ok(o)
}

fn main() -> anyhow::Result<()> {
    let written = run(&parse()?)?;
    println!("wrote {} frames", written.len());
    Ok(())
}

/// Runs the game for `options.frames` ticks; returns the PNG files written.
fn run(options: &Options) -> anyhow::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(&options.out)
        .with_context(|| format!("creating {}", options.out.display()))?;
    let ctx = Context::new(&ContextDesc::from_env())?;
    let scene = builtin::build("cornell-box")?;
    // The box the game moves: the scene's last instance (the tall box).
    let moving = scene.instances.len() - 1;
    let home = scene.instances[moving].transform;
    let mut renderer = Renderer::new(
        &ctx,
        scene,
        options.size.0,
        options.size.1,
        Settings {
            samples_per_pixel: options.spp,
            accumulate: false,
            ..Settings::default()
        },
    )?;
    let start_camera = renderer.camera();
    let dt = 1.0 / TICKS_PER_SECOND;
    let mut written = Vec::new();
    for tick in 0..options.frames {
        // Fixed-step simulation: the box slides, the camera sways.
        let t = tick as f32 * dt;
        let offset = Vec3::new(0.25 * (t * 3.0).sin(), 0.0, 0.0);
        renderer.set_instance_transform(moving, Affine3A::from_translation(offset) * home)?;
        let mut camera = start_camera;
        if options.sway {
            camera.position += Vec3::new(0.1 * (t * 0.7).sin(), 0.0, 0.0);
        }
        renderer.set_camera(camera);

        let mut graph = RenderGraph::new();
        let (images, _) = renderer.add_frame(&mut graph);
        let capture = (tick % options.every == 0).then(|| graph.readback(images.hdr));
        let frame = renderer.executor_mut().execute(graph.compile()?)?;
        if let Some(readback) = capture {
            let outputs = renderer.executor_mut().wait(frame)?;
            let image = outputs.image(readback)?;
            let path = options.out.join(format!("frame_{tick:04}.png"));
            capture::save_png(
                &path,
                &image,
                &PngEncoding {
                    exposure: 0.0,
                    tone: capture::ToneCurve::Aces,
                },
            )
            .with_context(|| format!("writing {}", path.display()))?;
            written.push(path);
        }
    }
    renderer.finish()?;
    for t in renderer.executor().pass_timings() {
        println!("{:<28} {:8.3} ms", t.name, t.ms);
    }
    println!(
        "{} frames of {}x{} -> {}",
        options.frames,
        options.size.0,
        options.size.1,
        options.out.display()
    );
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Mean luminance of each 4x4 block (averaging away most of the Monte Carlo noise).
    fn blocks(image: &lucid_engine::capture::ImageData) -> Vec<f32> {
        let (w, h) = (image.width / 4, image.height / 4);
        (0..h)
            .flat_map(|by| (0..w).map(move |bx| (bx, by)))
            .map(|(bx, by)| {
                let mut sum = 0.0;
                for y in 0..4 {
                    for x in 0..4 {
                        sum += image.luminance(bx * 4 + x, by * 4 + y).unwrap_or(0.0);
                    }
                }
                sum / 16.0
            })
            .collect()
    }

    #[test]
    fn frames_differ_where_the_box_moved_and_nowhere_else() {
        let out = std::env::temp_dir().join(format!("lucid-game-loop-{}", std::process::id()));
        let options = Options {
            frames: 11,
            every: 10,
            size: (128, 128),
            spp: 16,
            sway: false,
            out: out.clone(),
        };
        let written = run(&options).unwrap();
        assert_eq!(written.len(), 2, "frames 0 and 10 were captured");
        let first = capture::load(&written[0]).unwrap();
        let last = capture::load(&written[1]).unwrap();
        let (a, b) = (blocks(&first), blocks(&last));
        let changed = a
            .iter()
            .zip(&b)
            .filter(|(x, y)| (*x - *y).abs() > 0.1)
            .count();
        assert!(
            changed >= 5,
            "the moved box changes part of the image ({changed} blocks)"
        );
        // The upper left of the image is the red wall, far from the box and its shadow: only noise.
        let width = (first.width / 4) as usize;
        for (i, (x, y)) in a.iter().zip(&b).enumerate() {
            if i % width < width / 5 && i / width < width * 3 / 5 {
                assert!(
                    (x - y).abs() < 0.05,
                    "block {i} away from the box changed: {x} vs {y}"
                );
            }
        }
        std::fs::remove_dir_all(&out).unwrap();
    }
}
