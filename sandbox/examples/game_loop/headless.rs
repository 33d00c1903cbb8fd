//! The game without a window: one frame per tick, every `--every`-th read back and written as a
//! PNG.

use crate::game::Game;
use crate::Options;
use anyhow::Context as _;
use lucid_engine::capture::{self, PngEncoding};
use lucid_engine::graph::RenderGraph;
use lucid_engine::scene::builtin;
use lucid_engine::{Context, ContextDesc};
use lucid_passes::renderer::Renderer;
use std::path::PathBuf;

/// Ticks rendered when `--frames` is not given.
const DEFAULT_FRAMES: u32 = 60;

/// Runs the game for `options.frames` ticks; returns the PNG files written.
pub fn run(options: &Options) -> anyhow::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(&options.out)
        .with_context(|| format!("creating {}", options.out.display()))?;
    let ctx = Context::new(&ContextDesc::from_env())?;
    let scene = builtin::build("cornell-box")?;
    let (width, height) = options.size;
    let mut renderer = Renderer::new(&ctx, scene, width, height, options.settings())?;
    let game = Game::new(&renderer, options.camera_moves);
    let frames = options.frames.unwrap_or(DEFAULT_FRAMES);
    let mut written = Vec::new();
    for tick in 0..u64::from(frames) {
        game.apply(&mut renderer, tick)?;
        let mut graph = RenderGraph::new();
        let (images, _) = renderer.add_frame(&mut graph);
        let capture = (tick % u64::from(options.every) == 0).then(|| graph.readback(images.hdr));
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
        "{frames} frames of {width}x{height} -> {}",
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
            headless: true,
            frames: Some(11),
            every: 10,
            size: (128, 128),
            spp: lucid_passes::renderer::SamplesPerPixel::new(8).unwrap(),
            svgf: false,
            camera_moves: false,
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
        let far = a
            .iter()
            .zip(&b)
            .enumerate()
            .filter(|(i, _)| i % width < width / 5 && i / width < width * 3 / 5);
        let mut largest = 0.0f32;
        for (i, (x, y)) in far {
            largest = largest.max((x - y).abs());
            assert!(
                (x - y).abs() < 0.05,
                "block {i} away from the box changed: {x} vs {y}"
            );
        }
        println!(
            "{changed} blocks changed by more than 0.1; largest change away from the box {largest:.4}"
        );
        std::fs::remove_dir_all(&out).unwrap();
    }
}
