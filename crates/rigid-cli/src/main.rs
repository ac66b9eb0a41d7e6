//! The `rigid` command-line tool. Each subcommand lives in its own module; this file only
//! parses the command line and dispatches. The contract of `mass` and `eval` output is in
//! `docs/conventions.md` ("The command-line contract").

use clap::{Parser, Subcommand};
use std::process::ExitCode;

mod bench;
mod convert;
mod doctor;
mod eval;
mod eval_constraints;
mod excite;
mod explicit;
mod identify;
mod ik;
mod load;
mod mass;
mod mobile;
mod mobile_capstone;
mod mobile_drive;
mod model;
mod plotting;
mod simulate;
mod step;
mod util;
mod view;

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
    /// Write a robot (URDF, MJCF or built-in) as MJCF (`.xml`) or URDF (`.urdf`).
    Convert(convert::ConvertArgs),
    /// Check a URDF's inertial data: what is wrong, the likely cause, the nearest valid value.
    Doctor(doctor::DoctorArgs),
    /// Mass properties of a body made of parts (a TOML spec): mass, CoM, inertia, G.
    Mass(mass::MassArgs),
    /// Simulate a robot (URDF or built-in model) or one rigid body (a TOML spec): CSV, plots, a
    /// 3D replay in the browser, and a summary.
    Simulate(Box<simulate::SimulateArgs>),
    /// Identify a robot's inertial parameters from measured motion (a CSV of samples).
    Identify(Box<identify::IdentifyArgs>),
    /// Write an exciting trajectory for identification (CSV).
    Excite(excite::ExciteArgs),
    /// Inverse kinematics: joint positions that put a frame at a target position or pose.
    Ik(ik::IkArgs),
    /// Evaluate a robot model's dynamics (RNEA, CRBA, ABA, energies, CoM, placements) on cases.
    Eval(eval::EvalArgs),
    /// One simulation step with contacts from each case's (q, v, tau), and its derivatives.
    Step(Box<step::StepArgs>),
    /// The explicit dynamic model: M(q), Coriolis, centrifugal and gravity terms as abbreviated tables or code.
    Explicit(explicit::ExplicitArgs),
    /// Summarise a robot model: bodies, joints, sizes, mass and the validity of every inertia.
    Model(model::ModelArgs),
    /// Draw a robot in one pose, as a self-contained HTML page (WebGL).
    View(view::ViewArgs),
    /// Wheeled mobile robots: a base's H(φ) and F, odometry on wheel angles, the Modern Robotics
    /// capstone (a youBot picking and placing a cube).
    Mobile(mobile::MobileArgs),
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

/// A command-line error of clap on one line: its message without the `error:` prefix, the usage
/// and the tips, the remaining lines joined by `; `.
fn one_line(text: &str) -> String {
    text.lines()
        .map(str::trim)
        .take_while(|l| !l.starts_with("Usage:"))
        .filter(|l| !l.is_empty() && !l.starts_with("tip:") && !l.starts_with("For more"))
        .map(|l| l.trim_start_matches("error:").trim())
        .collect::<Vec<_>>()
        .join("; ")
}

fn main() -> ExitCode {
    // Rust ignores SIGPIPE, so a closed stdout (`rigid doctor x.urdf | head`) would make every
    // `println!` panic; restore the default: the process ends quietly, as other tools do.
    #[cfg(unix)]
    // SAFETY: setting a signal's disposition to its default before any thread is started.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // --help and --version print as clap does
        Err(e) if !e.use_stderr() => e.exit(),
        Err(e) => {
            eprintln!("error: {}", one_line(&e.to_string()));
            return ExitCode::from(2);
        }
    };
    match cli.command {
        Command::Bench(args) => report(bench::run(&args)),
        Command::Convert(args) => report(convert::run(&args)),
        Command::Doctor(args) => report(doctor::run(&args)),
        Command::Mass(args) => mass::run(&args),
        Command::Simulate(args) => report(simulate::run(&args)),
        Command::Eval(args) => report(eval::run(&args)),
        Command::Step(args) => report(step::run(&args)),
        Command::Ik(args) => ik::run(&args),
        Command::Identify(args) => report(identify::run(&args)),
        Command::Excite(args) => report(excite::run(&args)),
        Command::Model(args) => report(model::run(&args)),
        Command::Explicit(args) => report(explicit::run(&args)),
        Command::View(args) => report(view::run(&args)),
        Command::Mobile(args) => report(mobile::run(&args)),
    }
}
