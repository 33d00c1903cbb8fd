//! `lucid dataset`: renders the learned denoiser's training data: camera-path sequences whose
//! frames hold the denoiser's 1-sample inputs (the record of `lucid_passes::denoise::neural`: demodulated
//! radiance, albedo, emission, normal, roughness, depth, motion), each pixel's object id (which the
//! denoiser's averages of albedo and emission over time test) and a many-sample reference, one
//! safetensors file per sequence plus `index.json` (read by `training/data.py`). Records and
//! references are half precision, saturated at ±65504; a NaN is an error naming scene and frame.
//!
//! Scenes: procedural rooms (`random-room-<seed>`) and the built-in scenes, except `classroom` and
//! `caustics`, which stay held out for evaluation; or, with `--scenes`, only the scenes named, in
//! the split `study` that training never reads (to study the model on held-out frames, e.g.
//! `training/surface_study.py`). Each sequence follows the scene's camera path
//! from a random start at a random speed, with a random extra turn (slow pans to fast turns); with
//! `--stops`, some sequences slow down until the camera comes to rest and stays there; a new
//! sequence is a camera cut.

use super::output_path;
use super::progress::Progress;
use super::render_options::samples_per_pixel;
use super::size::Size;
use anyhow::{bail, Context as _};
use clap::Args;
use glam::Quat;
use half::f16;
use lucid_engine::atomic_write::write_atomic;
use lucid_engine::scene::{builtin, Camera, Scene};
use lucid_engine::{Context, ContextDesc};
use lucid_passes::denoise::neural::{RECORD_CHANNELS, RECORD_OBJECT};
use lucid_passes::renderer::{Denoiser, Renderer, SamplesPerPixel, Settings};
use lucid_passes::tradeoff::measure::REFERENCE_SPP_PER_FRAME;
use safetensors::tensor::{Dtype, TensorView};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Built-in scenes that never enter training data (the denoiser is evaluated on them).
pub const HELD_OUT: [&str; 2] = ["classroom", "caustics"];

/// Built-in scenes that teach nothing a denoiser needs (`furnace`: one sphere in a uniform sky).
const SKIPPED: [&str; 1] = ["furnace"];

/// Options of `lucid dataset`.
#[derive(Debug, Args)]
pub struct DatasetArgs {
    /// Output folder (created): `index.json` and `NNNN.safetensors` per sequence.
    #[arg(long)]
    out: PathBuf,
    /// Frame size `WxH`, each a multiple of 4 (the network's two poolings).
    #[arg(long, default_value = "256x256")]
    size: Size,
    /// Frames per sequence.
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u32).range(2..=1024))]
    frames: u32,
    /// Procedural rooms in the training split.
    #[arg(long, default_value_t = 24)]
    rooms: u32,
    /// Procedural rooms in the validation split (seeds after the training rooms').
    #[arg(long, default_value_t = 4)]
    validation_rooms: u32,
    /// Sequences per scene.
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=64))]
    sequences: u32,
    /// Samples per pixel of each reference frame.
    #[arg(long, default_value = "256", value_parser = samples_per_pixel(65536))]
    reference_spp: SamplesPerPixel,
    /// Leave out the built-in scenes (procedural rooms only).
    #[arg(long)]
    no_builtin: bool,
    /// Seed of the camera choices and of the room seeds.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Only these scenes (comma-separated built-in names or `random-room-<seed>`, held-out ones
    /// included), `--sequences` each, in the split `study`, which training never reads.
    #[arg(long, value_delimiter = ',', conflicts_with_all = ["rooms", "validation_rooms", "no_builtin"])]
    scenes: Vec<String>,
    /// The share of sequences whose camera slows down evenly until it comes to rest, after 0.1 to
    /// 0.8 s, and stays there (the denoiser's long histories; drawn apart from the other camera
    /// choices, which stay the same).
    #[arg(long, default_value_t = 0.0, value_parser = share)]
    stops: f32,
}

/// Parses a share from 0 to 1.
fn share(text: &str) -> Result<f32, String> {
    text.parse::<f32>()
        .ok()
        .filter(|v| (0.0..=1.0).contains(v))
        .ok_or_else(|| format!("{text:?} is not a number from 0 to 1"))
}

/// Seeds the stream of `--stops`' draws apart from the other camera choices'.
const STOPS_STREAM: u64 = 0x5707_5707_5707_5707;
/// The shortest and longest time a stopping sequence's camera takes to come to rest, in seconds.
const STOP_SECONDS: (f32, f32) = (0.1, 0.8);

/// One sequence to render.
struct Job {
    scene: String,
    split: &'static str,
    start: f32,
    speed: f32,
    turn: f32,
    /// Seconds until the camera comes to rest (`--stops`), if it does.
    stop: Option<f32>,
}

/// Renders every sequence and writes the index.
pub fn run(args: &DatasetArgs) -> anyhow::Result<()> {
    let (w, h) = (args.size.width, args.size.height);
    if w % 4 != 0 || h % 4 != 0 {
        bail!("--size {w}x{h}: width and height must be multiples of 4");
    }
    output_path::create_folder("--out", &args.out)?;
    let jobs = plan(args);
    let ctx = Context::new(&ContextDesc::from_env())?;
    let progress = Progress::new(jobs.len() as u64 * u64::from(args.frames), "frames");
    let mut index = Vec::new();
    let mut loaded: Option<(String, Scene)> = None;
    for (i, job) in jobs.iter().enumerate() {
        if loaded.as_ref().is_none_or(|(name, _)| name != &job.scene) {
            let scene =
                builtin::build(&job.scene).with_context(|| format!("scene {}", job.scene))?;
            loaded = Some((job.scene.clone(), scene));
        }
        let scene = &loaded.as_ref().expect("loaded above").1;
        let cameras = cameras(scene, job, args.frames)?;
        let file = format!("{i:04}.safetensors");
        render_sequence(
            &ctx,
            scene,
            &cameras,
            args,
            &args.out.join(&file),
            &progress,
        )?;
        index.push(serde_json::json!({
            "file": file,
            "scene": job.scene,
            "split": job.split,
            "frames": args.frames,
            "width": w,
            "height": h,
            "start": job.start,
            "speed": job.speed,
            "turn": job.turn,
            "stop": job.stop,
        }));
    }
    progress.finish();
    let index = serde_json::json!({
        "format": lucid_passes::denoise::neural::FORMAT,
        "record_channels": RECORD_CHANNELS,
        "reference_spp": args.reference_spp.get(),
        "held_out": HELD_OUT,
        "sequences": index,
    });
    let path = args.out.join("index.json");
    write_atomic(&path, serde_json::to_string_pretty(&index)?.as_bytes())
        .with_context(|| format!("writing {}", path.display()))?;
    eprintln!("{} sequences in {}", jobs.len(), args.out.display());
    Ok(())
}

/// A small deterministic generator for the camera choices (splitmix64).
struct Random(u64);

impl Random {
    fn next(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// The scenes with their splits: only the `--scenes` (split `study`), or procedural rooms
/// (training, then validation seeds) and the built-in scenes that are neither held out nor
/// skipped.
fn scene_splits(args: &DatasetArgs) -> Vec<(String, &'static str)> {
    if !args.scenes.is_empty() {
        return args
            .scenes
            .iter()
            .map(|name| (name.clone(), "study"))
            .collect();
    }
    let room_seed = args.seed.wrapping_mul(1000);
    let room = |i: u32| format!("random-room-{}", room_seed + u64::from(i));
    let mut scenes: Vec<(String, &'static str)> = (0..args.rooms)
        .map(|i| (room(i), "train"))
        .chain((0..args.validation_rooms).map(|i| (room(args.rooms + i), "validation")))
        .collect();
    if !args.no_builtin {
        scenes.extend(
            builtin::names()
                .iter()
                .filter(|n| !HELD_OUT.contains(n) && !SKIPPED.contains(n))
                .map(|n| (n.to_string(), "train")),
        );
    }
    scenes
}

/// The sequences: one job per scene of [`scene_splits`] and sequence, with random camera choices.
fn plan(args: &DatasetArgs) -> Vec<Job> {
    let mut random = Random(args.seed);
    let mut stops = Random(args.seed ^ STOPS_STREAM);
    let mut jobs = Vec::new();
    for (scene, split) in scene_splits(args) {
        for _ in 0..args.sequences {
            let speed = [0.5, 1.0, 2.0, 4.0][(random.next() * 4.0) as usize % 4];
            // Most sequences add no turn; some a slow pan, some a fast turn (up to 3 rad/s).
            let turn = match (random.next() * 3.0) as u32 {
                0 => 0.0,
                1 => (random.next() - 0.5) * 0.8,
                _ => (random.next() - 0.5) * 6.0,
            };
            let stops_here = stops.next() < args.stops;
            let seconds = stops.next();
            let stop =
                stops_here.then_some(STOP_SECONDS.0 + (STOP_SECONDS.1 - STOP_SECONDS.0) * seconds);
            jobs.push(Job {
                scene: scene.clone(),
                split,
                start: random.next(),
                speed,
                turn,
                stop,
            });
        }
    }
    jobs
}

/// How far the camera of a sequence that comes to rest after `stop` seconds has moved at `seconds`,
/// in seconds of its motion at full speed: its speed falls evenly from full to zero.
fn slowed_clock(seconds: f32, stop: f32) -> f32 {
    let t = seconds.min(stop);
    t - t * t / (2.0 * stop)
}

/// The cameras of `job`'s frames at 30 frames per second.
fn cameras(scene: &Scene, job: &Job, frames: u32) -> anyhow::Result<Vec<Camera>> {
    let path = scene
        .camera_path
        .as_ref()
        .with_context(|| format!("scene {} has no camera path", scene.name))?;
    let duration = path.duration().max(1e-3);
    Ok((0..frames)
        .map(|i| {
            let real = i as f32 / 30.0;
            let seconds = job.stop.map_or(real, |stop| slowed_clock(real, stop));
            let t = (job.start * duration + seconds * job.speed) % duration;
            let mut camera = path.sample(t);
            camera.orientation = Quat::from_rotation_y(job.turn * seconds) * camera.orientation;
            camera
        })
        .collect())
}

/// Renders one sequence: the 1-sample records through the learned denoiser's path and the
/// references, written as float16 `record` [T, channels, H, W] and `reference` [T, 3, H, W], and
/// int32 `objects` [T, H, W] (the records' object ids).
fn render_sequence(
    ctx: &Context,
    scene: &Scene,
    cameras: &[Camera],
    args: &DatasetArgs,
    path: &Path,
    progress: &Progress,
) -> anyhow::Result<()> {
    let (w, h) = (args.size.width, args.size.height);
    let noisy_settings = Settings {
        denoiser: Denoiser::Neural,
        accumulate: false,
        seed: (args.seed as u32) ^ 0x5eed,
        ..Settings::default()
    };
    let reference_settings = Settings {
        samples_per_pixel: args.reference_spp.min(REFERENCE_SPP_PER_FRAME),
        accumulate: true,
        ..Settings::default()
    };
    let mut noisy = Renderer::new(ctx, scene.clone(), w, h, noisy_settings)?;
    let mut reference = Renderer::new(ctx, scene.clone(), w, h, reference_settings)?;
    let reference_frames = args
        .reference_spp
        .get()
        .div_ceil(REFERENCE_SPP_PER_FRAME.get());
    let pixels = (w * h) as usize;
    let mut records: Vec<u16> =
        Vec::with_capacity(cameras.len() * pixels * RECORD_CHANNELS as usize);
    let mut references: Vec<u16> = Vec::with_capacity(cameras.len() * pixels * 3);
    let mut objects: Vec<i32> = Vec::with_capacity(cameras.len() * pixels);
    for (frame, &camera) in cameras.iter().enumerate() {
        noisy.set_camera(camera);
        let (_, record) = noisy.render_and_read_record()?;
        let floats: Vec<f32> = bytemuck::pod_collect_to_vec(&record);
        let (channels, ids) = floats.split_at(RECORD_OBJECT as usize * pixels);
        records.extend(
            half_saturated(channels.iter().copied()).with_context(|| {
                format!("scene {}, frame {frame}: the noisy record", scene.name)
            })?,
        );
        // The ids are the low 24 bits, exact in the float.
        objects.extend(ids.iter().map(|&id| id as i32));

        reference.set_camera(camera);
        for _ in 1..reference_frames {
            reference.render()?;
        }
        let image = reference.render_and_read()?;
        for c in 0..3 {
            references.extend(
                half_saturated(image.pixels.iter().map(|p| p[c])).with_context(|| {
                    format!("scene {}, frame {frame}: the reference", scene.name)
                })?,
            );
        }
        progress.inc();
    }
    noisy.finish()?;
    reference.finish()?;
    let t = cameras.len();
    let record_bytes: &[u8] = bytemuck::cast_slice(&records);
    let reference_bytes: &[u8] = bytemuck::cast_slice(&references);
    let object_bytes: &[u8] = bytemuck::cast_slice(&objects);
    let tensors = HashMap::from([
        (
            "record".to_string(),
            TensorView::new(
                Dtype::F16,
                vec![t, RECORD_CHANNELS as usize, h as usize, w as usize],
                record_bytes,
            )?,
        ),
        (
            "reference".to_string(),
            TensorView::new(
                Dtype::F16,
                vec![t, 3, h as usize, w as usize],
                reference_bytes,
            )?,
        ),
        (
            "objects".to_string(),
            TensorView::new(Dtype::I32, vec![t, h as usize, w as usize], object_bytes)?,
        ),
    ]);
    let metadata = HashMap::from([("scene".to_string(), scene.name.clone())]);
    let bytes = safetensors::serialize(&tensors, &Some(metadata))?;
    write_atomic(path, &bytes).with_context(|| format!("writing {}", path.display()))
}

/// `values` as half-precision bits, saturated to the largest finite half (65504) so that a bright
/// sample is stored as bright rather than infinite (infinities turn a training step's arithmetic
/// into NaN); a NaN is an error naming its index.
fn half_saturated(values: impl IntoIterator<Item = f32>) -> anyhow::Result<Vec<u16>> {
    let max = f32::from(f16::MAX);
    values
        .into_iter()
        .enumerate()
        .map(|(i, v)| {
            if v.is_nan() {
                bail!("value {i} is NaN");
            }
            Ok(f16::from_f32(v.clamp(-max, max)).to_bits())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_values_saturate_and_nan_is_an_error() {
        let bits = half_saturated([1.5, 1e6, f32::NEG_INFINITY, 65504.0]).unwrap();
        let back: Vec<f32> = bits.iter().map(|&b| f16::from_bits(b).to_f32()).collect();
        assert_eq!(back, [1.5, 65504.0, -65504.0, 65504.0]);
        let err = half_saturated([0.0, f32::NAN]).unwrap_err().to_string();
        assert!(err.contains("value 1 is NaN"), "{err}");
    }

    fn args(stops: f32) -> DatasetArgs {
        DatasetArgs {
            out: PathBuf::from("unused"),
            size: "64x64".parse().expect("size"),
            frames: 32,
            rooms: 40,
            validation_rooms: 4,
            sequences: 2,
            reference_spp: SamplesPerPixel::new(4).expect("spp"),
            no_builtin: true,
            seed: 7,
            scenes: Vec::new(),
            stops,
        }
    }

    #[test]
    fn stops_leave_the_other_camera_choices_as_they_were() {
        let plain = plan(&args(0.0));
        assert!(plain.iter().all(|job| job.stop.is_none()));
        let stopping = plan(&args(0.5));
        assert_eq!(plain.len(), stopping.len());
        for (a, b) in plain.iter().zip(&stopping) {
            assert_eq!(
                (&a.scene, a.start, a.speed, a.turn),
                (&b.scene, b.start, b.speed, b.turn)
            );
        }
        let stopped: Vec<f32> = stopping.iter().filter_map(|job| job.stop).collect();
        // 88 sequences, half of them expected to stop: far from none and from all.
        assert!((24..=64).contains(&stopped.len()), "{}", stopped.len());
        assert!(stopped
            .iter()
            .all(|s| (STOP_SECONDS.0..=STOP_SECONDS.1).contains(s)));
        assert!(plan(&args(1.0)).iter().all(|job| job.stop.is_some()));
    }

    #[test]
    fn a_stopping_camera_slows_evenly_and_rests() {
        let stop = 0.5;
        assert_eq!(slowed_clock(0.0, stop), 0.0);
        assert_eq!(slowed_clock(stop, stop), stop / 2.0);
        assert_eq!(slowed_clock(0.9, stop), stop / 2.0);
        // Full speed at the start, none at the stop: the steps between frames shrink evenly.
        let step = |s: f32| slowed_clock(s + 0.01, stop) - slowed_clock(s, stop);
        assert!((step(0.0) - 0.01).abs() < 1e-3);
        assert!(step(0.2) < step(0.1) && step(0.4) < step(0.2));
        assert!(step(stop - 0.01) < 1e-3 && step(stop) == 0.0);

        let scene = builtin::build("random-room-7").expect("room");
        let job = Job {
            scene: scene.name.clone(),
            split: "train",
            start: 0.3,
            speed: 2.0,
            turn: 0.5,
            stop: Some(0.4),
        };
        let frames = cameras(&scene, &job, 32).expect("cameras");
        // At rest from frame 12 (0.4 s) on; moving before.
        assert!(frames[12..].iter().all(|c| c == &frames[12]));
        assert!(frames[10] != frames[11]);
        let moving = Job { stop: None, ..job };
        let free = cameras(&scene, &moving, 32).expect("cameras");
        assert_eq!(frames[0], free[0]);
        assert!(free[20] != free[12]);
    }
}
