//! The `rigid` command-line tool. Each subcommand lives in its own module; the contract of their
//! output is in `CONVENTIONS.md` ("The command-line contract").

mod eval;
mod load;
mod model;

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
    /// Evaluate a robot model's dynamics (RNEA, CRBA, ABA, energies, CoM, placements) on cases.
    Eval(eval::EvalArgs),
    /// Summarise a robot model: bodies, joints, sizes, mass and the validity of every inertia.
    Model(model::ModelArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Eval(args) => eval::run(args),
        Command::Model(args) => model::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}
