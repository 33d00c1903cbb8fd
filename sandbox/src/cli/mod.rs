//! The `lucid` subcommands.

mod bench;
mod dataset;
mod evaluate;
mod info;
mod pipeline_stats;
mod progress;
mod render;
mod render_options;
mod scene_source;
mod scenes;
mod sequence;
mod size;
mod split;
mod view;

use clap::{Parser, Subcommand};

/// Lucid: real-time physically based light transport with a temporal denoiser.
///
/// Without a subcommand it opens the sandbox window on the default scene.
#[derive(Debug, Parser)]
#[command(name = "lucid", version, about)]
pub struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Open the interactive sandbox on a scene (the default without a subcommand).
    View(view::ViewArgs),
    /// Show the Vulkan device Lucid would use, its limits and the validation level.
    Info(info::InfoArgs),
    /// List the built-in scenes with their triangle counts and features.
    Scenes(scenes::ScenesArgs),
    /// Render frames headless and write the result as EXR (HDR) or PNG (tone-mapped).
    Render(render::RenderArgs),
    /// Measure GPU frame time, per-pass times, paths/s and rays/s.
    Bench(bench::BenchArgs),
    /// Render a scene's camera path as a reference and through each denoiser, then evaluate them.
    Sequence(sequence::SequenceArgs),
    /// Metrics of rendered sequences against their reference, as CSV and an SVG plot.
    Evaluate(evaluate::EvaluateArgs),
    /// Render the learned denoiser's training data (inputs and references along camera paths).
    Dataset(dataset::DatasetArgs),
}

/// Runs the parsed command.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    let command = match cli.command {
        Some(command) => command,
        None => Cli::parse_from(["lucid", "view"])
            .command
            .expect("`lucid view` parses to a command"),
    };
    match command {
        Command::View(args) => view::run(&args),
        Command::Info(args) => info::run(&args),
        Command::Scenes(args) => scenes::run(&args),
        Command::Render(args) => render::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Sequence(args) => sequence::run(&args),
        Command::Evaluate(args) => evaluate::run(&args),
        Command::Dataset(args) => dataset::run(&args),
    }
}
