//! `lucid bench`: GPU frame times (timestamps per pass), paths/s and rays/s for one scene and
//! algorithm, printed and written as JSON.

use super::output_path;
use super::pipeline_stats;
use super::progress::Progress;
use super::render_options::RenderOptions;
use super::scene_source;
use anyhow::Context as _;
use clap::Args;
use lucid_engine::atomic_write::write_atomic;
use lucid_engine::{Context, ContextDesc};
use std::collections::BTreeMap;
use std::path::PathBuf;

/// Options of `lucid bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    #[command(flatten)]
    options: RenderOptions,
    /// Frames measured (after the warm-up).
    #[arg(long, default_value_t = 100, value_parser = clap::value_parser!(u32).range(1..))]
    frames: u32,
    /// Frames rendered first and not measured (pipeline creation, caches, clocks).
    #[arg(long, default_value_t = 10)]
    warmup: u32,
    /// Also write the results as JSON to this file.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Time every frame as one after a scene change (an object or a light animating): SVGF's
    /// temporal gradients are then replayed every frame. The GPU work is that of a changed
    /// scene; the scene itself stays still, so the image stays comparable.
    #[arg(long)]
    dynamic: bool,
    /// Capture each compute pipeline's executable statistics (register count, ...) through
    /// VK_KHR_pipeline_executable_properties: printed to stderr and written as "pipelines" in the
    /// JSON (null when the device cannot capture them). `LUCID_PIPELINE_STATISTICS=1` does the same.
    #[arg(long)]
    pipeline_statistics: bool,
}

/// Whether a timed pass only serves the display (tone mapping, the host readback of the tone-mapped
/// image): `image_ms` leaves these out, timing the frame up to its HDR image on the GPU, which is
/// what an offline renderer's timing (Mitsuba's, say) covers. `image_ms` sums the passes' own
/// times; `image_span_ms` runs from the first pass's start to the end of the last of them, the
/// gaps between passes (their barriers) included.
fn serves_display_only(pass: &str) -> bool {
    pass.starts_with("tonemap") || pass.starts_with("readback")
}

/// Mean, standard deviation, median, minimum and maximum of a sample.
fn summary(values: &[f64]) -> serde_json::Value {
    let n = values.len().max(1) as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1.0).max(1.0);
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    serde_json::json!({
        "mean": mean,
        "std": var.sqrt(),
        "median": sorted.get(sorted.len() / 2).copied().unwrap_or(0.0),
        "min": sorted.first().copied().unwrap_or(0.0),
        "max": sorted.last().copied().unwrap_or(0.0),
    })
}

/// Runs the benchmark.
pub fn run(args: &BenchArgs) -> anyhow::Result<()> {
    if let Some(path) = &args.json {
        output_path::check_file("--json", path, &["json"])?;
    }
    let scene = scene_source::load(&args.options.scene, args.options.env.as_deref())?;
    let mut desc = ContextDesc::from_env();
    desc.pipeline_statistics |= args.pipeline_statistics;
    let capture_statistics = desc.pipeline_statistics;
    let ctx = Context::new(&desc)?;
    if !ctx.info().timestamps {
        anyhow::bail!(
            "{} has no timestamp queries on its compute queue: cannot time passes",
            ctx.info().name
        );
    }
    let (w, h) = (args.options.size.width, args.options.size.height);
    let mut settings = args.options.settings(false);
    settings.svgf.gradients_every_frame = args.dynamic;
    let mut renderer = args
        .options
        .calibrated_renderer(&ctx, scene, (w, h), settings)?;
    let settings = *renderer.settings();
    for _ in 0..args.warmup {
        renderer.render()?;
    }
    renderer.finish()?;
    let progress = Progress::new(args.frames as u64, "frames");
    let mut frame_ms = Vec::new();
    let mut image_ms = Vec::new();
    let mut image_span_ms = Vec::new();
    let mut rays = Vec::new();
    let mut passes: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    let wall = std::time::Instant::now();
    for _ in 0..args.frames {
        let mut g = lucid_engine::graph::RenderGraph::new();
        let (images, stats) = renderer.add_frame(&mut g);
        // The displayed image leaves the graph, as in the sandbox: without a consumer, the
        // passes that only feed it (the last a-trous iterations, tone mapping) would be culled.
        g.readback(images.ldr);
        let frame = renderer.executor_mut().execute(g.compile()?)?;
        let outputs = renderer.executor_mut().wait(frame)?;
        renderer.collect_stats(&outputs, stats)?;
        frame_ms.push(outputs.timings.iter().map(|t| t.ms).sum());
        let image_passes = || {
            outputs
                .timings
                .iter()
                .filter(|t| !serves_display_only(&t.name))
        };
        image_ms.push(image_passes().map(|t| t.ms).sum());
        image_span_ms.push(
            image_passes()
                .map(|t| t.start_ms + t.ms)
                .fold(0.0, f64::max),
        );
        // Passes that share a name (SVGF's a-trous iterations) count as one: their sum.
        let mut frame_passes: BTreeMap<&str, f64> = BTreeMap::new();
        for t in &outputs.timings {
            *frame_passes.entry(&t.name).or_default() += t.ms;
        }
        for (name, ms) in frame_passes {
            passes.entry(name.to_owned()).or_default().push(ms);
        }
        rays.push(renderer.stats().rays as f64);
        progress.inc();
    }
    progress.finish();
    let wall_s = wall.elapsed().as_secs_f64();
    let mean_ms = frame_ms.iter().sum::<f64>() / frame_ms.len() as f64;
    let image_mean_ms = image_ms.iter().sum::<f64>() / image_ms.len() as f64;
    let paths = w as f64 * h as f64 * f64::from(settings.samples_per_pixel.get());
    let mean_rays = rays.iter().sum::<f64>() / rays.len() as f64;
    let pipelines = renderer.executor().library().pipeline_statistics();
    if capture_statistics {
        pipeline_stats::print_table(pipelines.as_deref(), &ctx.info().name);
    }
    let mut report = serde_json::json!({
        "command": std::env::args().collect::<Vec<_>>().join(" "),
        "device": ctx.info().name,
        "scene": renderer.scene().name,
        "triangles": renderer.scene().triangle_count(),
        "algorithm": settings.algorithm.short_name(),
        "denoiser": settings.denoiser.short_name(),
        "edge_emission": settings.supersamples_edges(),
        "svgf_firefly_clamp": settings.svgf.firefly_clamp,
        "svgf_firefly_headroom": settings.svgf.firefly_headroom,
        "neural_gated_filter": settings.neural.gated_filter,
        "neural_path": renderer.neural_path().short_name(),
        "neural_decoder": renderer.neural_decoder().name(),
        "bvh": renderer.bvh_layout().name(),
        "gpu_scene_bytes": renderer.gpu_scene().total_bytes(),
        "gpu_bytes_per_triangle": renderer.gpu_scene().bytes_per_triangle(),
        "size": [w, h],
        "spp": settings.samples_per_pixel.get(),
        "max_depth": args.options.max_depth,
        "bdpt_connections": settings.bdpt_connections.get(),
        "bdpt_mis": settings.bdpt_mis.short_name(),
        "bdpt_connection_roulette": settings.bdpt_connection_roulette,
        "frames": args.frames,
        "dynamic": args.dynamic,
        "frame_ms": summary(&frame_ms),
        "passes_ms": passes.iter().map(|(k, v)| (k.clone(), summary(v))).collect::<BTreeMap<_, _>>(),
        "paths_per_second": paths / (mean_ms / 1e3),
        "image_ms": summary(&image_ms),
        "image_ms_per_frame": image_ms,
        "image_span_ms": summary(&image_span_ms),
        "image_paths_per_second": paths / (image_mean_ms / 1e3),
        "rays_per_frame": mean_rays,
        "rays_per_second": mean_rays / (mean_ms / 1e3),
        "wall_fps": args.frames as f64 / wall_s,
        "non_finite_samples_last_frame": renderer.stats().non_finite_samples,
    });
    if capture_statistics {
        report["pipelines"] = pipeline_stats::to_json(pipelines.as_deref());
    }
    println!("{}", serde_json::to_string_pretty(&report)?);
    if let Some(path) = &args.json {
        write_atomic(path, serde_json::to_string_pretty(&report)?.as_bytes())
            .with_context(|| format!("writing {}", path.display()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::serves_display_only;

    #[test]
    fn only_tone_mapping_and_the_readback_serve_the_display_alone() {
        assert!(serves_display_only("tonemap"));
        assert!(serves_display_only("readback tonemap.ldr"));
        for pass in [
            "path_trace",
            "accumulate.radiance",
            "svgf.atrous",
            "bdpt.camera",
        ] {
            assert!(!serves_display_only(pass), "{pass}");
        }
    }
}
