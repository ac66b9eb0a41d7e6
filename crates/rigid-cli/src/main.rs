//! The `rigid` command-line tool. Each subcommand lives in its own module.

mod simulate;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// Rigid-body dynamics from the command line.
#[derive(Parser)]
#[command(name = "rigid", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Simulate one rigid body (free, or on a pivot) and report energy and momentum errors.
    Simulate(simulate::SimulateArgs),
}

fn main() -> ExitCode {
    let result = match Cli::parse().command {
        Command::Simulate(args) => simulate::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
