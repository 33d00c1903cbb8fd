//! Times the metrics `lucid evaluate` computes per frame (relative MSE, SSIM, FLIP, as
//! `metrics::evaluate_frame`, and temporal instability over a frame pair) on synthetic HDR frames:
//!
//! ```sh
//! cargo run --release -p lucid-engine --example metrics_timing -- 1920x1080 10
//! ```
//!
//! prints the mean wall-clock and CPU (all threads) milliseconds per frame of each metric and of the whole evaluation, and the
//! milliseconds per frame of evaluating 4 methods' sequences of 6 frames against one reference
//! sequence as `lucid evaluate` does.

use lucid_engine::capture::{ImageData, PngEncoding};
use lucid_engine::metrics::{
    evaluate_frame, evaluate_sequence, evaluate_sequences, flip, rel_mse, ssim,
    temporal_instability, SsimMode, DEFAULT_PIXELS_PER_DEGREE, DEFAULT_REL_MSE_EPSILON,
};
use std::time::Instant;

/// A deterministic HDR frame: smooth structure, edges and noise of amplitude `noise`.
fn frame(width: u32, height: u32, noise: f32, seed: u64) -> ImageData {
    let mut state = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
    let mut random = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let pixels = (0..height)
        .flat_map(|y| (0..width).map(move |x| (x, y)))
        .map(|(x, y)| {
            let (fx, fy) = (x as f32 / width as f32, y as f32 / height as f32);
            let edge = if (x / 64 + y / 64) % 2 == 0 { 1.5 } else { 0.3 };
            let base = [
                fx * edge,
                (fx * 7.0 + fy * 3.0).sin().abs() * edge,
                fy * 2.0,
            ];
            let n = 1.0 + noise * (random() - 0.5) * 2.0;
            [base[0] * n, base[1] * n, base[2] * n, 1.0]
        })
        .collect();
    ImageData::from_pixels(width, height, pixels).expect("sized")
}

/// CPU milliseconds this process has used, all threads (Linux: `/proc/self/stat`; 0 elsewhere).
fn cpu_ms() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat
        .rsplit_once(')')
        .map_or(vec![], |(_, rest)| rest.split_whitespace().collect());
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|f| f.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    // utime and stime (fields 14 and 15 of the line, 12 and 13 after the command name), in
    // clock ticks of 10 ms.
    (ticks(11) + ticks(12)) * 10.0
}

/// Wall and CPU milliseconds per run of `f`.
fn time_ms(runs: u32, mut f: impl FnMut()) -> (f64, f64) {
    let (started, cpu) = (Instant::now(), cpu_ms());
    for _ in 0..runs {
        f();
    }
    let n = f64::from(runs);
    (
        started.elapsed().as_secs_f64() * 1e3 / n,
        (cpu_ms() - cpu) / n,
    )
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let size = args.get(1).map_or("1920x1080", String::as_str);
    let (w, h) = size
        .split_once('x')
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .expect("size as WxH");
    let runs: u32 = args.get(2).map_or(5, |n| n.parse().expect("a run count"));
    let display = PngEncoding::default();
    let reference = frame(w, h, 0.0, 1);
    let test = frame(w, h, 0.6, 2);
    let next = frame(w, h, 0.6, 3);
    println!(
        "{w}x{h}, {runs} runs, {} threads",
        rayon::current_num_threads()
    );
    println!("{:<24} {:>9} {:>9}", "", "wall ms", "CPU ms");
    let report = |name: &str, (wall, cpu): (f64, f64)| println!("{name:<24} {wall:9.1} {cpu:9.1}");
    report(
        "display encoding",
        time_ms(runs, || {
            display.to_display(&test);
        }),
    );
    report(
        "tone mapping",
        time_ms(runs, || {
            display.tone_map(&test);
        }),
    );
    report(
        "relMSE",
        time_ms(runs, || {
            rel_mse(&test, &reference, DEFAULT_REL_MSE_EPSILON).unwrap();
        }),
    );
    report(
        "SSIM (with display)",
        time_ms(runs, || {
            ssim(
                &display.to_display(&test),
                &display.to_display(&reference),
                SsimMode::Luminance,
            )
            .unwrap();
        }),
    );
    report(
        "FLIP (with tone map)",
        time_ms(runs, || {
            flip(
                &display.tone_map(&test),
                &display.tone_map(&reference),
                DEFAULT_PIXELS_PER_DEGREE,
            )
            .unwrap();
        }),
    );
    let pair = [test.clone(), next.clone()];
    let references = [reference.clone(), reference.clone()];
    report(
        "temporal (per pair)",
        time_ms(runs, || {
            temporal_instability(&pair, &references).unwrap();
        }),
    );
    report(
        "evaluate_frame",
        time_ms(runs, || {
            evaluate_frame(&test, &reference, &display).unwrap();
        }),
    );
    const METHODS: u64 = 4;
    const FRAMES: u64 = 6;
    let references: Vec<ImageData> = (0..FRAMES).map(|i| frame(w, h, 0.05, 10 + i)).collect();
    let methods: Vec<Vec<ImageData>> = (0..METHODS)
        .map(|m| (0..FRAMES).map(|i| frame(w, h, 0.6, 100 * m + i)).collect())
        .collect();
    let per_frame = (METHODS * FRAMES) as f64;
    let per_frame_of = |(wall, cpu): (f64, f64)| (wall / per_frame, cpu / per_frame);
    report(
        "4 sequences, one by one",
        per_frame_of(time_ms(1, || {
            for frames in &methods {
                evaluate_sequence(frames, &references, &display).unwrap();
            }
        })),
    );
    report(
        "4 sequences together",
        per_frame_of(time_ms(1, || {
            let tests: Vec<&[ImageData]> = methods.iter().map(Vec::as_slice).collect();
            evaluate_sequences(&tests, &references, &display).unwrap();
        })),
    );
}
