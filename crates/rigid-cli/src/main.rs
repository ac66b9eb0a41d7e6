//! The `rigid` command-line tool. Each subcommand lives in its own module; this file only
//! parses the command line and dispatches. The contract of `mass` and `eval` output is in
//! `CONVENTIONS.md` ("The command-line contract").

use clap::{Parser, Subcommand};
use std::process::ExitCode;

mod bench;
mod bench_batch;
mod eval;
mod explicit;
mod load;
mod mass;
mod model;
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
    /// Evaluate a robot model's dynamics (RNEA, CRBA, ABA, energies, CoM, placements) on cases.
    Eval(eval::EvalArgs),
    /// The explicit dynamic model: M(q), Coriolis, centrifugal and gravity terms as abbreviated tables or code.
    Explicit(explicit::ExplicitArgs),
    /// Summarise a robot model: bodies, joints, sizes, mass and the validity of every inertia.
    Model(model::ModelArgs),
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
        Command::Eval(args) => report(eval::run(&args)),
        Command::Model(args) => report(model::run(&args)),
        Command::Explicit(args) => report(explicit::run(&args)),
    }
}
