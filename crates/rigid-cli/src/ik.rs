//! `rigid ik MODEL --frame F --target x,y,z[,rx,ry,rz]`: inverse kinematics
//! ([`rigid::kinematics::inverse`]). This file parses the flags and prints; the solver is the
//! library's.

use crate::load::{load_model, LoadArgs};
use crate::simulate::{parse_list, Numbers};
use clap::Args;
use rigid::kinematics::{inverse, ErrorTwist, IkError, Options, Site, Solution, Target};
use rigid::multibody::{forward_kinematics_q, neutral, Data, Model};
use rigid::spatial::{so3, Transform, Vec3};
use std::process::ExitCode;

/// Options of `rigid ik`.
#[derive(Args, Debug)]
pub struct IkArgs {
    /// A URDF file, a robot of example-robot-data by name, or a built-in model.
    pub model: String,
    #[command(flatten)]
    pub load: LoadArgs,
    /// The joint or frame to place (a joint name is looked up first, then the frames).
    #[arg(long)]
    pub frame: String,
    /// Where: `x,y,z` (m; the frame's origin, orientation free) or `x,y,z,rx,ry,rz`, the full
    /// pose with the orientation as a rotation vector (axis times angle, rad; exponential
    /// coordinates), or roll-pitch-yaw with `--rpy`.
    #[arg(long, value_parser = parse_list, allow_hyphen_values = true)]
    pub target: Numbers,
    /// Read `rx,ry,rz` of `--target` as fixed-axis roll, pitch, yaw (URDF's `rpy`).
    #[arg(long)]
    pub rpy: bool,
    /// The starting configuration, `nq` comma-separated numbers (default: the neutral one).
    #[arg(long, value_parser = parse_list, allow_hyphen_values = true)]
    pub q0: Option<Numbers>,
    /// Drive the space twist `V_s` to zero (`IKinSpace`) instead of the body twist `V_b`.
    #[arg(long)]
    pub space: bool,
    /// Angular and linear tolerances (rad and m).
    #[arg(long, default_value_t = 1e-9, allow_hyphen_values = true)]
    pub tolerance: f64,
    /// Steps per attempt.
    #[arg(long, default_value_t = 100)]
    pub max_iterations: usize,
    /// λ₀ of the damped least-squares step; 0 is the textbook's Newton step.
    #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true)]
    pub damping: f64,
    /// Attempts from random configurations after the first fails.
    #[arg(long, default_value_t = 20)]
    pub restarts: usize,
    /// Seed of the restarts.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Ignore the joints' position limits.
    #[arg(long)]
    pub no_limits: bool,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

fn target(args: &IkArgs) -> Result<Target, String> {
    let t = &args.target.0;
    match t.len() {
        3 if !args.rpy => Ok(Target::Position(Vec3::new(t[0], t[1], t[2]))),
        6 => {
            let r = if args.rpy {
                so3::from_rpy(t[3], t[4], t[5])
            } else {
                so3::exp(&Vec3::new(t[3], t[4], t[5]))
            };
            Ok(Target::Pose(Transform::new(r, Vec3::new(t[0], t[1], t[2]))))
        }
        3 => Err("--rpy needs a full pose: --target x,y,z,roll,pitch,yaw".into()),
        n => Err(format!(
            "--target has {n} numbers: give x,y,z or x,y,z,rx,ry,rz"
        )),
    }
}

fn json(model: &Model, pose: &Transform, s: &Solution) -> serde_json::Value {
    let names: Vec<&str> = model.joints().iter().map(|j| j.name.as_str()).collect();
    let r = &pose.rotation;
    serde_json::json!({
        "converged": s.converged,
        "q": s.q,
        "joints": names,
        "angular_error": s.angular_error,
        "linear_error": s.linear_error,
        "position_error": s.position_error,
        "iterations": s.iterations,
        "total_iterations": s.total_iterations,
        "attempts": s.attempts,
        "pose": {
            "rotation": (0..3).map(|i| (0..3).map(|j| r[(i, j)]).collect::<Vec<_>>()).collect::<Vec<_>>(),
            "translation": [pose.translation.x, pose.translation.y, pose.translation.z],
        },
    })
}

fn text(model: &Model, frame: &str, pose: &Transform, s: &Solution) {
    let verdict = if s.converged {
        "converged"
    } else {
        "NOT converged (best attempt)"
    };
    println!(
        "{frame}: {verdict} after {} steps ({} attempts, {} steps in all)",
        s.iterations, s.attempts, s.total_iterations
    );
    println!(
        "  error: angular {:.3e} rad, linear {:.3e} m, position {:.3e} m",
        s.angular_error, s.linear_error, s.position_error
    );
    let p = pose.translation;
    let w = so3::log(&pose.rotation);
    println!(
        "  pose reached: x,y,z = {:.9}, {:.9}, {:.9} m; rotation vector {:.9}, {:.9}, {:.9}",
        p.x, p.y, p.z, w.x, w.y, w.z
    );
    for j in model.joints() {
        let q = &s.q[j.coordinates()];
        let q: Vec<String> = q.iter().map(|x| format!("{x:.12}")).collect();
        println!("  {:<24} {}", j.name, q.join(" "));
    }
    println!(
        "  q = {}",
        s.q.iter()
            .map(|x| format!("{x}"))
            .collect::<Vec<_>>()
            .join(",")
    );
}

/// Runs `rigid ik`: exit 0 with a solution, 1 when no attempt converged (the best is printed),
/// 2 for an error.
pub fn run(args: &IkArgs) -> ExitCode {
    match solve(args) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}

fn solve(args: &IkArgs) -> Result<bool, String> {
    let model = load_model(&args.model, &args.load)?;
    let target = target(args)?;
    let site = Site::by_name(&model, &args.frame).map_err(|e| format!("--frame: {e}"))?;
    let q0 = args.q0.clone().map_or_else(|| neutral(&model), |n| n.0);
    if q0.len() != model.nq() {
        return Err(format!(
            "--q0 has {} numbers; nq = {}",
            q0.len(),
            model.nq()
        ));
    }
    let options = Options {
        twist: if args.space {
            ErrorTwist::Space
        } else {
            ErrorTwist::Body
        },
        angular_tolerance: args.tolerance,
        linear_tolerance: args.tolerance,
        max_iterations: args.max_iterations,
        damping: args.damping,
        restarts: args.restarts,
        seed: args.seed,
        respect_limits: !args.no_limits,
    };
    let mut data = Data::new(&model);
    let solution = match inverse(&model, &mut data, site, &target, &q0, &options) {
        Ok(s) => s,
        Err(IkError::NotConverged { best }) => *best,
        Err(IkError::Input(e)) => return Err(format!("--q0: {e}")),
        Err(IkError::BadOption {
            name,
            value,
            reason,
        }) => {
            let flag = match name {
                "angular_tolerance" | "linear_tolerance" => "--tolerance",
                "max_iterations" => "--max-iterations",
                _ => "--damping",
            };
            return Err(format!("{flag} {value}: {reason}"));
        }
        Err(e) => return Err(format!("--target: {e}")),
    };
    forward_kinematics_q(&model, &mut data, &solution.q).map_err(|e| e.to_string())?;
    let pose = site.pose(&model, &data);
    if args.json {
        println!("{}", json(&model, &pose, &solution));
    } else {
        text(&model, &args.frame, &pose, &solution);
    }
    Ok(solution.converged)
}
