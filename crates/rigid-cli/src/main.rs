//! The `rigid` command-line tool. Each subcommand lives in its own module; this file only
//! parses the command line and dispatches.

use clap::{Parser, Subcommand};
use std::process::ExitCode;

mod mass;

/// Rigid-body dynamics from the command line.
#[derive(Parser)]
#[command(name = "rigid", version)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Mass properties of a body made of parts (a TOML spec): mass, CoM, inertia, G.
    Mass(mass::MassArgs),
}

fn main() -> ExitCode {
    match Cli::parse().command {
        Command::Mass(args) => mass::run(&args),
    }
}
