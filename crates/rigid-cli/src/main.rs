//! The `rigid` command-line tool. Each subcommand lives in its own module; this file only
//! parses the command line and dispatches.

use clap::{Parser, Subcommand};
use std::process::ExitCode;

mod bench;
mod bench_batch;
mod mass;
mod simulate;

/// Rigid-body dynamics from the command line.
#[derive(Parser)]
#[command(name = "rigid", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Time the multibody algorithms on a model (median ns per call over random states).
    Bench(bench::BenchArgs),
    /// Mass properties of a body made of parts (a TOML spec): mass, CoM, inertia, G.
    Mass(mass::MassArgs),
    /// Simulate one rigid body (free, or on a pivot) and report energy and momentum errors.
    Simulate(simulate::SimulateArgs),
}

/// Exit code 2 and the message on stderr for an error.
fn report(result: Result<(), String>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

fn main() -> ExitCode {
    match Cli::parse().command {
        Command::Bench(args) => report(bench::run(&args)),
        Command::Mass(args) => mass::run(&args),
        Command::Simulate(args) => report(simulate::run(&args)),
    }
}
