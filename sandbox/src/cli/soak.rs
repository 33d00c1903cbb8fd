//! `lucid soak`: many frames with everything changing — the camera along the scene's path, an
//! object moving, the algorithm and the denoiser switching through every combination, every other
//! one with the emission supersampled at emitters' edges and the learned denoiser's gated filter
//! off — sampling host memory (resident set) and GPU memory (the memory tracker) every few frames.
//! Fails when either grows after the first full cycle of configurations, or when the validation
//! layer says anything.

use super::progress::Progress;
use super::scene_source;
use super::size::Size;
use anyhow::{bail, Context as _};
use clap::Args;
use glam::{Affine3A, Vec3};
use lucid_engine::{Context, ContextDesc, Validation};
use lucid_passes::denoise::neural::NeuralParams;
use lucid_passes::renderer::{Algorithm, Denoiser, EdgeEmission, Renderer, Settings};
use std::path::PathBuf;

/// Options of `lucid soak`.
#[derive(Debug, Args)]
pub struct SoakArgs {
    /// Built-in scene name or glTF file.
    #[arg(long, default_value = "cornell-box")]
    scene: String,
    /// Frame size `WxH`.
    #[arg(long, default_value = "640x360")]
    size: Size,
    /// Frames to render.
    #[arg(long, default_value_t = 10_000, value_parser = clap::value_parser!(u32).range(1..))]
    frames: u32,
    /// Frames between configuration switches (algorithm x denoiser, in turn; every other one with
    /// the edge pass).
    #[arg(long, default_value_t = 100, value_parser = clap::value_parser!(u32).range(1..))]
    switch_every: u32,
    /// Frames between memory samples.
    #[arg(long, default_value_t = 100, value_parser = clap::value_parser!(u32).range(1..))]
    sample_every: u32,
    /// Growth of the host's resident memory allowed after the first cycle, in MiB.
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u64).range(0..=65536))]
    host_tolerance_mib: u64,
    /// Growth of GPU memory allowed after the first cycle, in KiB.
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u64).range(0..=1048576))]
    gpu_tolerance_kib: u64,
    /// Also write the samples as JSON to this file.
    #[arg(long)]
    json: Option<PathBuf>,
}

/// Memory at one frame.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Sample {
    /// Frames rendered so far.
    pub frame: u32,
    /// The process's resident set, bytes (0 where the system does not say).
    pub host_bytes: u64,
    /// GPU memory allocated by the engine, bytes.
    pub gpu_bytes: u64,
}

/// How much memory may grow before the soak fails.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tolerance {
    /// Host resident-set bytes.
    pub host: u64,
    /// GPU bytes (scene buffers rebuilt for a moving object vary by a few hundred bytes).
    pub gpu: u64,
}

/// The first growth beyond `tolerance` among `samples`: each sample after the first full cycle of
/// configurations from frame `settled` on (`cycle` frames) is compared with the sample at the same
/// point of that first cycle, so that every comparison is between the same configuration. `None`
/// when memory stayed flat; an error when no two samples could be compared.
pub fn growth(
    samples: &[Sample],
    settled: u32,
    cycle: u32,
    tolerance: Tolerance,
) -> Result<Option<String>, String> {
    let first_cycle = |s: &Sample| (settled..settled + cycle).contains(&s.frame);
    let mut compared = 0;
    for s in samples.iter().filter(|s| s.frame >= settled + cycle) {
        let Some(base) = samples
            .iter()
            .find(|b| first_cycle(b) && (s.frame - b.frame) % cycle == 0)
        else {
            continue;
        };
        compared += 1;
        if s.gpu_bytes > base.gpu_bytes + tolerance.gpu {
            return Ok(Some(format!(
                "GPU memory grew from {} to {} bytes between frames {} and {}",
                base.gpu_bytes, s.gpu_bytes, base.frame, s.frame
            )));
        }
        if s.host_bytes > base.host_bytes + tolerance.host {
            return Ok(Some(format!(
                "host memory grew from {} to {} bytes between frames {} and {}",
                base.host_bytes, s.host_bytes, base.frame, s.frame
            )));
        }
    }
    if compared == 0 {
        return Err(format!(
            "no two memory samples to compare: render at least two cycles of {cycle} frames after \
             frame {settled}, sampling every n frames with n dividing {cycle}"
        ));
    }
    Ok(None)
}

/// The process's resident set in bytes, from `/proc/self/statm` (0 elsewhere).
fn resident_bytes() -> u64 {
    std::fs::read_to_string("/proc/self/statm")
        .ok()
        .and_then(|s| s.split_whitespace().nth(1)?.parse::<u64>().ok())
        .map_or(0, |pages| pages * 4096)
}

/// Runs the soak.
pub fn run(args: &SoakArgs) -> anyhow::Result<()> {
    let scene = scene_source::load(&args.scene, None)?;
    if scene.instances.is_empty() {
        bail!("scene {} has no instance to move", scene.name);
    }
    let path = scene.camera_path.clone();
    // The last instance moves (in the built-in scenes, an object in view rather than the room).
    let moving = scene.instances.len() - 1;
    let home = scene.instances[moving].transform;
    let ctx = Context::new(&ContextDesc::from_env())?;
    let algorithms: Vec<Algorithm> = Algorithm::ALL
        .into_iter()
        .filter(|a| *a != Algorithm::Bidirectional || ctx.info().int64_atomics)
        .collect();
    // Every other configuration supersamples the emission at emitters' edges and turns the learned
    // denoiser's gated filter off, so that each denoiser runs with and without the edge pass and
    // the learned one with and without its filter's passes, all of them coming and going.
    let configurations: Vec<(Algorithm, Denoiser, EdgeEmission, NeuralParams)> = algorithms
        .iter()
        .flat_map(|&a| Denoiser::ALL.map(|d| (a, d)))
        .enumerate()
        .map(|(i, (a, d))| {
            let edges = [EdgeEmission::Off, EdgeEmission::On][i % 2];
            let neural = NeuralParams {
                gated_filter: i % 2 == 0,
            };
            (a, d, edges, neural)
        })
        .collect();
    // The first cycle of configurations creates pipelines and histories; memory is compared from
    // the second on.
    let cycle = configurations.len() as u32 * args.switch_every;
    let settled = cycle;
    eprintln!(
        "soak: {} frames of {}, {} configurations, memory compared from frame {settled}, \
         validation {:?}",
        args.frames,
        scene.name,
        configurations.len(),
        ctx.validation()
    );
    if ctx.validation() == Validation::Off {
        eprintln!(
            "note: validation is off, so validation messages are not checked: set LUCID_VALIDATION=1"
        );
    }
    let (w, h) = (args.size.width, args.size.height);
    let mut renderer = Renderer::new(&ctx, scene, w, h, Settings::default())?;
    let progress = Progress::new(u64::from(args.frames), "frames");
    let mut samples = Vec::new();
    // Speed is measured after the first cycle (which creates pipelines and histories).
    let timed_from = if args.frames > settled { settled } else { 0 };
    let mut started = std::time::Instant::now();
    let mut gpu_ms = 0.0;
    for frame in 0..args.frames {
        if frame == timed_from {
            started = std::time::Instant::now();
        }
        let (algorithm, denoiser, edge_emission, neural) =
            configurations[(frame / args.switch_every) as usize % configurations.len()];
        let settings = renderer.settings();
        let wanted = (algorithm, denoiser, edge_emission, neural);
        if (
            settings.algorithm,
            settings.denoiser,
            settings.edge_emission,
            settings.neural,
        ) != wanted
        {
            renderer.set_settings(Settings {
                algorithm,
                denoiser,
                edge_emission,
                neural,
                ..*settings
            })?;
        }
        let t = frame as f32 / 30.0;
        if let Some(path) = &path {
            renderer.set_camera(path.sample(t % path.duration().max(1e-3)));
        }
        let offset = Vec3::new(0.05 * (t * 2.0).sin(), 0.0, 0.0);
        renderer.set_instance_transform(moving, Affine3A::from_translation(offset) * home)?;
        renderer.render()?;
        // The passes of the frame completed last (each frame waits for the one before).
        if frame >= timed_from {
            gpu_ms += renderer
                .executor()
                .pass_timings()
                .iter()
                .map(|t| t.ms)
                .sum::<f64>();
        }
        if (frame + 1) % args.sample_every == 0 {
            renderer.finish()?;
            samples.push(Sample {
                frame: frame + 1,
                host_bytes: resident_bytes(),
                gpu_bytes: ctx.memory_report().allocated_bytes,
            });
            if let Some(report) = ctx.validation_log().take_report() {
                bail!("validation messages by frame {}:\n{report}", frame + 1);
            }
        }
        progress.inc();
    }
    renderer.finish()?;
    progress.finish();
    let timed_frames = f64::from(args.frames - timed_from);
    let wall_ms_per_frame = started.elapsed().as_secs_f64() * 1e3 / timed_frames;
    let gpu_ms_per_frame = gpu_ms / timed_frames;
    println!(
        "frames {timed_from} to {} at {w}x{h}: {wall_ms_per_frame:.2} ms per frame (wall), \
         {gpu_ms_per_frame:.2} ms of it in the passes on the GPU",
        args.frames
    );
    if let Some(path) = &args.json {
        let json = serde_json::json!({
            "scene": args.scene,
            "size": [w, h],
            "settled_from": settled,
            "wall_ms_per_frame": wall_ms_per_frame,
            "gpu_ms_per_frame": gpu_ms_per_frame,
            "samples": samples,
        });
        std::fs::write(path, serde_json::to_string_pretty(&json)?)
            .with_context(|| format!("writing {}", path.display()))?;
    }
    let tolerance = Tolerance {
        host: args.host_tolerance_mib << 20,
        gpu: args.gpu_tolerance_kib << 10,
    };
    match growth(&samples, settled, cycle, tolerance) {
        Ok(None) => {}
        Ok(Some(problem)) => bail!("memory is not flat: {problem}"),
        Err(problem) => bail!("{problem}"),
    }
    let last = samples.last().copied();
    match last {
        Some(s) => println!(
            "flat: host {:.1} MiB, GPU {:.1} MiB at frame {}",
            s.host_bytes as f64 / 1048576.0,
            s.gpu_bytes as f64 / 1048576.0,
            s.frame
        ),
        None => unreachable!("growth() found samples to compare"),
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(frame: u32, host_bytes: u64, gpu_bytes: u64) -> Sample {
        Sample {
            frame,
            host_bytes,
            gpu_bytes,
        }
    }

    const TOLERANCE: Tolerance = Tolerance { host: 16, gpu: 4 };

    #[test]
    fn flat_memory_passes_and_growth_is_named() {
        // Cycle of 20 frames from frame 20: frames 40 and 60 compare with 20, 50 with 30.
        let flat = [
            sample(10, 500, 10),
            sample(20, 1000, 70),
            sample(30, 1000, 40),
            sample(40, 1010, 72),
            sample(50, 1016, 40),
        ];
        assert_eq!(growth(&flat, 20, 20, TOLERANCE), Ok(None));
        let mut gpu = flat;
        gpu[3].gpu_bytes = 75;
        assert!(growth(&gpu, 20, 20, TOLERANCE)
            .unwrap()
            .unwrap()
            .contains("GPU memory grew"));
        let mut host = flat;
        host[4].host_bytes = 1017;
        assert!(growth(&host, 20, 20, TOLERANCE)
            .unwrap()
            .unwrap()
            .contains("host memory grew"));
    }

    #[test]
    fn too_few_samples_is_an_error() {
        let one_cycle = [sample(20, 1000, 70), sample(30, 1000, 40)];
        assert!(growth(&one_cycle, 20, 20, TOLERANCE).is_err());
    }
}
