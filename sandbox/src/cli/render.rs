//! `lucid render`: a headless render written to an image.

use super::output_path;
use super::progress::Progress;
use super::render_options::RenderOptions;
use super::scene_source;
use clap::Args;
use lucid_engine::capture::{self, ExrPrecision};
use lucid_engine::{Context, ContextDesc};
use std::path::PathBuf;

/// Options of `lucid render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    #[command(flatten)]
    options: RenderOptions,
    /// Frames to accumulate (the image averages frames × spp samples per pixel).
    #[arg(long, default_value_t = 16, value_parser = clap::value_parser!(u32).range(1..))]
    frames: u32,
    /// Output file: `.exr` (linear HDR, 32-bit float) or `.png` (tone-mapped sRGB).
    #[arg(long, default_value = "lucid.png")]
    out: PathBuf,
    /// Print the compiled render graph of one frame.
    #[arg(long)]
    dump_graph: bool,
}

/// Renders and writes the image.
pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    let extension = output_path::check_file("--out", &args.out, &["png", "exr"])?;
    let scene = scene_source::load(&args.options.scene, args.options.env.as_deref())?;
    let ctx = Context::new(&ContextDesc::from_env())?;
    let (w, h) = (args.options.size.width, args.options.size.height);
    let mut renderer =
        args.options
            .calibrated_renderer(&ctx, scene, (w, h), args.options.settings(true))?;
    let settings = *renderer.settings();
    if args.dump_graph {
        print!("{}", renderer.frame_plan()?.dump());
    }
    eprintln!(
        "rendering {} ({} triangles) {w}x{h}, {} frames x {} spp, {}, denoiser {} on {}; \
         specialization: {}",
        renderer.scene().name,
        renderer.scene().triangle_count(),
        args.frames,
        settings.samples_per_pixel,
        settings.algorithm.label(),
        settings.denoiser.label(),
        ctx.info().name,
        renderer.scene().features()
    );
    let progress = Progress::new(args.frames as u64, "frames");
    let started = std::time::Instant::now();
    for _ in 1..args.frames {
        renderer.render()?;
        progress.inc();
    }
    let image = renderer.render_and_read()?;
    progress.finish();
    let seconds = started.elapsed().as_secs_f64();
    if extension == "exr" {
        capture::save_exr(&args.out, &image, ExrPrecision::F32)
    } else {
        capture::save_png(&args.out, &image, &args.options.display())
    }?;
    println!(
        "{}: {} frames x {} spp in {seconds:.2} s, {} non-finite samples dropped -> {}",
        renderer.scene().name,
        args.frames,
        settings.samples_per_pixel,
        renderer.stats().non_finite_samples,
        args.out.display()
    );
    Ok(())
}
