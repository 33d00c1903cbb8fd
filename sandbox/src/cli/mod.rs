//! The `lucid` subcommands.

mod auto_options;
mod bench;
mod converge;
mod converge_chart;
mod dataset;
mod evaluate;
mod external_series;
mod float_range;
mod info;
mod lists;
mod maps;
mod output_path;
mod pipeline_stats;
mod progress;
mod render;
mod render_options;
mod scene_source;
mod scenes;
mod sequence;
mod size;
mod soak;
mod split;
mod stability;
mod view;

use clap::{Parser, Subcommand};

/// Lucid: real-time physically based light transport with a temporal denoiser.
///
/// Without a subcommand it opens the sandbox window, taking the options of `lucid view`.
#[derive(Debug, Parser)]
#[command(name = "lucid", version, about, args_conflicts_with_subcommands = true)]
pub struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// The sandbox's options when there is no subcommand.
    #[command(flatten)]
    view: view::ViewArgs,
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
    /// Error against GPU time as samples accumulate, per algorithm, denoiser and samples per
    /// pixel, against a many-sample reference: CSV, JSON and charts (Pareto front included).
    Converge(converge::ConvergeArgs),
    /// Render the learned denoiser's training data (inputs and references along camera paths).
    Dataset(dataset::DatasetArgs),
    /// Render many frames with everything changing and check that memory stays flat.
    Soak(soak::SoakArgs),
}

/// Runs the parsed command.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    let Some(command) = cli.command else {
        return view::run(&cli.view);
    };
    match command {
        Command::View(args) => view::run(&args),
        Command::Info(args) => info::run(&args),
        Command::Scenes(args) => scenes::run(&args),
        Command::Render(args) => render::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Sequence(args) => sequence::run(&args),
        Command::Evaluate(args) => evaluate::run(&args),
        Command::Converge(args) => converge::run(&args),
        Command::Dataset(args) => dataset::run(&args),
        Command::Soak(args) => soak::run(&args),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn the_command_line_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn without_a_subcommand_the_sandbox_takes_the_options_of_view() {
        let bare = Cli::try_parse_from(["lucid", "--screenshot-after", "20", "shot.png"]).unwrap();
        assert!(bare.command.is_none());
        let view =
            Cli::try_parse_from(["lucid", "view", "--screenshot-after", "20", "shot.png"]).unwrap();
        let Some(Command::View(view)) = view.command else {
            panic!("`lucid view` parses to the view command");
        };
        assert_eq!(format!("{:?}", bare.view), format!("{view:?}"));
    }

    #[test]
    fn a_first_word_that_names_no_subcommand_is_the_sandbox_scene() {
        let scene = Cli::try_parse_from(["lucid", "classroom", "--spp", "4"]).unwrap();
        assert!(scene.command.is_none());
        assert!(format!("{:?}", scene.view).contains("\"classroom\""));
        let render = Cli::try_parse_from(["lucid", "render", "--scene", "classroom"]).unwrap();
        assert!(matches!(render.command, Some(Command::Render(_))));
    }

    #[test]
    fn connection_roulette_takes_a_finite_share_of_at_least_zero() {
        for command in ["view", "render", "bench"] {
            let parse = |share: &str| {
                Cli::try_parse_from(["lucid", command, "--bdpt-connection-roulette", share])
            };
            assert!(parse("0").is_ok() && parse("0.5").is_ok(), "{command}");
            assert!(
                parse("-0.1").is_err() && parse("nan").is_err() && parse("inf").is_err(),
                "{command}"
            );
        }
        let render =
            Cli::try_parse_from(["lucid", "render", "--bdpt-connection-roulette", "0.5"]).unwrap();
        assert!(format!("{:?}", render.command).contains("bdpt_connection_roulette: 0.5"));
    }
}
