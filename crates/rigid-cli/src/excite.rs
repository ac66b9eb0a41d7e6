//! `rigid excite MODEL --duration 10 --out traj.csv`: an exciting trajectory for identification
//! (a Fourier series per joint within the limits, optimised for the condition number of the
//! base regressor; see `rigid::identification::excitation`).

use crate::load::{load_model, LoadArgs};
use clap::Args;
use rigid::identification::excitation::{optimize, ExcitationOptions};
use rigid::identification::JointTerms;
use std::path::PathBuf;

/// Arguments of `rigid excite`.
#[derive(Args)]
pub struct ExciteArgs {
    /// A URDF file, a robot of example-robot-data by name, or a built-in model (every joint of
    /// one degree of freedom).
    pub model: String,
    /// Duration (s): one period of the series; the motion starts and ends at rest.
    #[arg(long, default_value_t = 10.0)]
    pub duration: f64,
    /// The CSV to write: `t, q_…, v_…, a_…, tau_…` (tau: the torques the model predicts; run
    /// the motion on the robot and replace them with the measured ones).
    #[arg(long, value_name = "traj.csv")]
    pub out: PathBuf,
    /// Samples per second in the CSV.
    #[arg(long, default_value_t = 100.0)]
    pub rate: f64,
    /// Harmonics of the Fourier series per joint.
    #[arg(long, default_value_t = 5)]
    pub harmonics: usize,
    /// Evaluations of the condition number by the optimiser.
    #[arg(long, default_value_t = 300)]
    pub iterations: usize,
    /// Excite the friction parameters too.
    #[arg(long)]
    pub friction: bool,
    /// Seed of the optimiser's random start.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    #[command(flatten)]
    pub load: LoadArgs,
}

/// Runs `rigid excite`.
///
/// # Errors
/// A model that cannot be loaded or has multi-dof joints, options out of range, an output that
/// cannot be written.
pub fn run(args: &ExciteArgs) -> Result<(), String> {
    if !(args.rate.is_finite() && args.rate > 0.0) {
        return Err(format!("--rate must be positive, got {}", args.rate));
    }
    if !(args.duration.is_finite() && args.duration > 0.0) {
        return Err(format!(
            "--duration must be positive, got {}",
            args.duration
        ));
    }
    if args.harmonics == 0 || args.iterations == 0 {
        return Err("--harmonics and --iterations must be at least 1".into());
    }
    let model = load_model(&args.model, &args.load)?;
    let opts = ExcitationOptions {
        duration: args.duration,
        harmonics: args.harmonics,
        iterations: args.iterations,
        terms: JointTerms {
            friction: args.friction,
            rotor_inertia: false,
        },
        seed: args.seed,
        ..ExcitationOptions::default()
    };
    let (traj, cond) = optimize(&model, &opts).map_err(|e| format!("{}: {e}", args.model))?;
    let samples = traj
        .samples(&model, 1.0 / args.rate)
        .map_err(|e| e.to_string())?;
    crate::util::write_atomic(&args.out, samples.to_csv(&model).as_bytes())?;
    println!(
        "wrote {}: {} samples at {} Hz over {} s (t, q, v, a, tau; tau is what the model \
         predicts: replace it with the measured torques); condition number of the base \
         regressor {cond:.4e}",
        args.out.display(),
        samples.len(),
        args.rate,
        args.duration
    );
    Ok(())
}
