//! `lucid render`: a headless render written to an image.

use super::size::Size;
use anyhow::{bail, Context as _};
use clap::Args;
use lucid_engine::capture;
use lucid_engine::graph::{Executor, RenderGraph};
use lucid_engine::shader::ShaderLibrary;
use lucid_engine::{Context, ContextDesc};
use lucid_passes::test_pattern;
use std::path::PathBuf;

/// Options of `lucid render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// What to render: `test-pattern` (a three-pass graph self-test).
    #[arg(long, default_value = "test-pattern")]
    scene: String,
    /// Image size.
    #[arg(long, default_value = "256x256")]
    size: Size,
    /// Output file: `.exr` (linear HDR) or `.png` (tone-mapped sRGB).
    #[arg(long, default_value = "lucid.png")]
    out: PathBuf,
    /// Print the compiled render graph (passes, barriers, lifetimes, aliasing).
    #[arg(long)]
    dump_graph: bool,
}

/// Renders and writes the image.
pub fn run(args: &RenderArgs) -> anyhow::Result<()> {
    if args.scene != "test-pattern" {
        bail!("unknown scene {:?}; available: test-pattern", args.scene);
    }
    let ctx = Context::new(&ContextDesc::from_env())?;
    let library = ShaderLibrary::new(&ctx, None)?;
    let mut executor = Executor::new(&ctx, library)?;
    let (w, h) = (args.size.width, args.size.height);
    let mut graph = RenderGraph::new();
    let outputs = test_pattern::add(&mut graph, w, h, &test_pattern::Params::default());
    let readback = graph.readback(outputs.pattern);
    let compiled = graph.compile()?;
    if args.dump_graph {
        print!("{}", compiled.plan.dump());
    }
    let frame = executor.execute(compiled)?;
    let image = executor.wait(frame)?.image(readback)?;
    capture::save(&args.out, &image).with_context(|| format!("writing {}", args.out.display()))?;
    let total: f64 = executor.pass_timings().iter().map(|t| t.ms).sum();
    println!(
        "rendered {} {w}x{h} on {} in {total:.3} ms GPU time -> {}",
        args.scene,
        ctx.info().name,
        args.out.display()
    );
    Ok(())
}
