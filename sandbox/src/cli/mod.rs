//! The `lucid` subcommands.

mod info;
mod render;
mod size;

use clap::{Parser, Subcommand};

/// Lucid: real-time physically based light transport with a temporal denoiser.
#[derive(Debug, Parser)]
#[command(name = "lucid", version, about, arg_required_else_help = true)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Show the Vulkan device Lucid would use, its limits and the validation level.
    Info(info::InfoArgs),
    /// Render frames headless and write the result as EXR (HDR) or PNG (tone-mapped).
    Render(render::RenderArgs),
}

/// Runs the parsed command.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Info(args) => info::run(&args),
        Command::Render(args) => render::run(&args),
    }
}
