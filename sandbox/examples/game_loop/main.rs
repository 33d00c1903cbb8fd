//! A game loop with Lucid as a library: a fixed time step slides the tall box of the Cornell box
//! back and forth (`Renderer::set_instance_transform`) and moves the camera along a path; every
//! frame is rendered through `Renderer`.
//!
//! ```sh
//! cargo run --release -p lucid-sandbox --example game_loop               # in a window
//! cargo run --release -p lucid-sandbox --example game_loop -- --headless --frames 120 --out frames/
//! ```
//!
//! In a window (presented through `lucid_present::Presenter`), the simulation advances in fixed
//! 1/60 s steps however fast frames render, and the title shows the frame rate; `--frames N` exits
//! after N presented frames. `--headless` renders one frame per tick without a window and writes
//! every `--every`-th frame as a PNG, printing the GPU time of each pass of the last frame.

mod game;
mod headless;
mod windowed;
#[cfg(test)]
#[path = "../../tests/support/xvfb.rs"]
mod xvfb;

use anyhow::{bail, Context as _};
use lucid_passes::renderer::{Denoiser, SamplesPerPixel, Settings};
use std::path::PathBuf;

/// What the command line asks for.
struct Options {
    headless: bool,
    /// Frames to render (headless: ticks, default 60; windowed: presented frames, default until
    /// the window is closed).
    frames: Option<u32>,
    every: u32,
    size: (u32, u32),
    spp: SamplesPerPixel,
    svgf: bool,
    camera_moves: bool,
    out: PathBuf,
}

impl Options {
    /// The renderer settings: no accumulation, since the scene moves every tick.
    fn settings(&self) -> Settings {
        Settings {
            samples_per_pixel: self.spp,
            accumulate: false,
            denoiser: if self.svgf {
                Denoiser::Svgf
            } else {
                Denoiser::None
            },
            ..Settings::default()
        }
    }
}

const USAGE: &str =
    "use --headless --frames N --every K --size WxH --spp N --svgf --no-sway --out DIR";

fn parse() -> anyhow::Result<Options> {
    let mut o = Options {
        headless: false,
        frames: None,
        every: 10,
        size: (640, 360),
        spp: SamplesPerPixel::ONE,
        svgf: false,
        camera_moves: true,
        out: PathBuf::from("game_loop_frames"),
    };
    let mut args = std::env::args().skip(1);
    while let Some(arg) = args.next() {
        let mut value = || args.next().with_context(|| format!("{arg} needs a value"));
        match arg.as_str() {
            "--headless" => o.headless = true,
            "--frames" => o.frames = Some(value()?.parse().context("--frames")?),
            "--every" => o.every = value()?.parse::<u32>().context("--every")?.max(1),
            "--size" => {
                let v = value()?;
                let size = v
                    .split_once('x')
                    .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
                    .filter(|&(w, h): &(u32, u32)| w > 0 && h > 0);
                o.size = size.with_context(|| format!("--size {v} is not WxH"))?;
            }
            "--out" => o.out = PathBuf::from(value()?),
            "--spp" => {
                let count = value()?.parse::<u32>().context("--spp")?;
                o.spp = count.try_into().context("--spp")?;
            }
            "--svgf" => o.svgf = true,
            "--no-sway" => o.camera_moves = false,
            other => bail!("unknown argument {other}; {USAGE}"),
        }
    }
    Ok(o)
}

fn main() -> std::process::ExitCode {
    let result = parse().and_then(|options| {
        if options.headless {
            let written = headless::run(&options)?;
            println!("wrote {} frames", written.len());
            Ok(())
        } else {
            windowed::run(&options).map(|summary| println!("{summary}"))
        }
    });
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            std::process::ExitCode::FAILURE
        }
    }
}
