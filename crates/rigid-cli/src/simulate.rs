//! `rigid simulate MODEL`: a robot (a URDF file or a built-in model, [`robot`]) or one rigid body
//! (a `rigid mass` TOML spec, [`body`]), chosen by the input.

mod body;
mod plot;
mod robot;
mod robot_plot;
mod world;

use crate::load::LoadArgs;
use clap::Args;
use rigid::simulation::{ControlKind, Integrator, JointLimits, SimulationError, TimeScaling};
use rigid::spatial::Vec3;
use std::path::PathBuf;

/// Most points drawn per curve in a plot.
pub const PLOT_POINTS: usize = 2000;

/// Options of `rigid simulate`.
#[derive(Args, Debug)]
pub struct SimulateArgs {
    /// What to simulate: a URDF file or a built-in model (`ur5`, `panda`, `talos` and the other
    /// robots of example-robot-data when it is installed; `puma560`, `double_pendulum`, …), or
    /// one rigid body as a `rigid mass` spec (`.toml`).
    pub model: String,
    #[command(flatten)]
    pub load: LoadArgs,
    /// Robot: initial configuration, `nq` comma-separated numbers (default: the neutral one);
    /// a body on the ground (`--ground`): its CoM pose `x,y,z,qx,qy,qz,qw`.
    #[arg(long, value_parser = parse_list, allow_hyphen_values = true)]
    pub q0: Option<Numbers>,
    /// Robot: initial velocity, `nv` comma-separated numbers (default: zero).
    #[arg(long, value_parser = parse_list, allow_hyphen_values = true)]
    pub v0: Option<Numbers>,
    /// Robot: `none`, `gravity` (compensation), `pd` (to --target, with gravity compensation) or
    /// `track` (computed torque along a quintic from q0 to --target in --move-time).
    #[arg(long, default_value = "none", value_name = "none|gravity|pd|track")]
    pub controller: ControlKind,
    /// Robot: the target configuration of `pd` and `track` (`nq` numbers).
    #[arg(long, value_parser = parse_list, allow_hyphen_values = true)]
    pub target: Option<Numbers>,
    /// Robot: duration of the `track` motion (s; default half of --duration).
    #[arg(long)]
    pub move_time: Option<f64>,
    /// Robot: time scaling of the `track` motion: `quintic` or `trapezoidal`.
    #[arg(long, default_value = "quintic", value_name = "quintic|trapezoidal")]
    pub profile: TimeScaling,
    /// Robot: joint position limits: `spring` (a stiff spring-damper past a limit) or `ignored`.
    #[arg(long, default_value = "spring", value_name = "spring|ignored")]
    pub limits: JointLimits,
    /// Robot: leave out the URDF's joint damping and friction (`<dynamics>`).
    #[arg(long)]
    pub no_joint_dynamics: bool,
    /// Body: initial body angular velocity `wx,wy,wz` (rad/s, axes of the spec frame).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true, default_value = "0,0,0")]
    pub omega: Vec3,
    /// Body: initial linear velocity of the CoM `vx,vy,vz` (m/s, spec axes); a free body only.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true, default_value = "0,0,0")]
    pub velocity: Vec3,
    /// Gravity `gx,gy,gz` in the world (m/s²). Body: none by default; robot: the model's.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub gravity: Option<Vec3>,
    /// Body: a point `x,y,z` of the spec frame fixed in the world (a spherical pivot).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub pivot: Option<Vec3>,
    /// Robot or body: a ground plane `z = HEIGHT` (0 when no number is given), which the robot's
    /// collision geometry (URDF `<collision>`, MJCF geoms; meshes as convex hulls) touches with
    /// Coulomb friction. An MJCF file's own `plane` is its ground without this flag (which then
    /// refuses to add a second), and its geoms collide with each other as MuJoCo collides them
    /// (`contype`/`conaffinity`, not parent and child, `<contact><exclude>` and `<pair>`); a
    /// URDF's bodies touch each other only with --self-collision. Anything that can touch is
    /// stepped by the `semi-implicit` time-stepping scheme (rk4 is replaced, variational
    /// refused). A floating robot starts set down on the ground (its lowest geometry touching),
    /// at --target when given and no --q0; `--controller pd` then holds the stance with the
    /// torques that carry its weight on the feet. A body spec (`.toml`) collides through its
    /// parts' shapes; its pose is then --q0 (`x,y,z,qx,qy,qz,qw` of its CoM with the spec axes;
    /// default: set down), its twist --omega and --velocity. A negative height is written
    /// `--ground=-0.5`.
    #[arg(
        long,
        num_args = 0..=1,
        default_missing_value = "0",
        value_name = "HEIGHT"
    )]
    pub ground: Option<f64>,
    /// Coulomb friction coefficient of every contact (default: an MJCF file's geoms', else 0.8).
    #[arg(long, allow_hyphen_values = true, value_name = "MU")]
    pub friction: Option<f64>,
    /// Robot (URDF): its bodies collide with each other (not parent with child); an MJCF file's
    /// always do, as its masks say.
    #[arg(long)]
    pub self_collision: bool,
    /// Robot (URDF): an SRDF file whose `<disable_collisions link1 link2>` pairs never collide
    /// (with --self-collision).
    #[arg(long, value_name = "FILE")]
    pub srdf: Option<PathBuf>,
    /// Newton restitution of the contacts, in [0, 1] (with --ground; default 0: no bounce).
    #[arg(long, allow_hyphen_values = true, value_name = "E")]
    pub restitution: Option<f64>,
    /// The contact solver: `pgs` (projected Gauss–Seidel, contact by contact) or `admm` (the
    /// alternating direction method of multipliers, island by island: converges where the
    /// sweep stalls, on stacks and redundant contacts, and spreads a load over a flat face).
    /// Both solve the same problem (hard contacts, the exact Coulomb cone) to the same tolerance;
    /// the summary prints their ContactBench residuals.
    #[arg(long, default_value = "pgs", value_name = "pgs|admm")]
    pub contact_solver: rigid::simulation::contact::Solver,
    /// With `pgs`: do not polish the sweep by its active set (by default Newton's method on the
    /// modes the impulses show ends the solve after sweeps 4, 8, 16, ... when they stand;
    /// docs/contact.md): the walker and the ant then take 33-56 sweeps a step instead of 4-5.
    #[arg(long)]
    pub no_polish: bool,
    /// With --csv, when anything can touch: the contact solve of each step as well, columns
    /// `iterations`, `converged` (1 or 0) and the ContactBench residuals `signorini` (J),
    /// `coulomb` (N·s), `dissipation` (J) and `velocity_error` (m/s).
    #[arg(long)]
    pub residuals: bool,
    /// Simulated time (s).
    #[arg(long, default_value_t = 10.0, allow_hyphen_values = true)]
    pub duration: f64,
    /// Time step (s; default: an MJCF file's `<option timestep>`, else 0.001).
    #[arg(long, allow_hyphen_values = true)]
    pub dt: Option<f64>,
    /// `rk4` (the default for bodies and robots: explicit, 4th order, any force), `variational`
    /// (4th order, symplectic: no energy or momentum drift, 10-40 times the cost), `semi-implicit`
    /// (symplectic Euler, 1st order) or, for a body only, `lgvi` (the 2nd-order Lie-group
    /// variational integrator, which `variational` named for a body before: momentum and energy
    /// of a torque-free body to round-off).
    #[arg(
        long,
        default_value = "rk4",
        value_name = "rk4|variational|semi-implicit|lgvi"
    )]
    pub integrator: Integrator,
    /// Robot: closed loops and welds (`{"constraints": [...]}` as `rigid eval --constraints`),
    /// held exactly by the same step as everything else (contacts, limits, control): the
    /// constrained dynamics under rk4, bilateral rows of the contact problem under the
    /// time-stepping scheme, then a projection back onto the constraints each step. An MJCF
    /// file's own `<equality>` elements are held without this flag. Prints the largest
    /// violation; the CSV gains `violation_position` and `violation_velocity`.
    #[arg(long)]
    pub constraints: Option<PathBuf>,
    /// Robot (URDF): mimic joints follow their sources (`<mimic>`), held as joint constraints
    /// of the full model, whose constrained dynamics are the reduced model's (docs/mimic.md);
    /// the CSV keeps every joint's column. `--q0`, `--v0` and `--target` may be given in the
    /// reduced coordinates.
    #[arg(long)]
    pub mimic: bool,
    /// Write one row per step to this CSV file. Robot: `t`, then q, v and τ with joint-named
    /// columns, then `energy` (K + U, J); body: `t,px,py,pz,qx,qy,qz,qw,wx,wy,wz,vx,vy,vz` (the
    /// CoM frame's pose and body twist), with --ground then `energy`. When anything can touch,
    /// then `contacts` (active contacts) and `normal_force` (the sum of their normal forces,
    /// N); with constraints, then `violation_position` and `violation_velocity` (the largest
    /// constraint error, m or rad, and its rate).
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Draw a figure to this SVG or PNG file (robot: joint angles, velocities, torques and total
    /// energy; body: angular velocity, energy and momentum errors).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Write a 3D replay to this self-contained HTML file (opens offline in a browser).
    #[arg(long)]
    pub html: Option<PathBuf>,
}

/// Comma-separated numbers from the command line.
#[derive(Clone, Debug, PartialEq)]
pub struct Numbers(pub Vec<f64>);

/// Parses `x,y,z` into three finite numbers.
fn parse_vec3(s: &str) -> Result<Vec3, String> {
    let v = parse_list(s)?.0;
    if v.len() != 3 {
        return Err(format!("expected three numbers x,y,z, got {s:?}"));
    }
    Ok(Vec3::new(v[0], v[1], v[2]))
}

/// Parses comma-separated finite numbers.
pub fn parse_list(s: &str) -> Result<Numbers, String> {
    s.split(',')
        .map(str::trim)
        .map(|p| match p.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            Ok(_) => Err(format!("{p:?} is not a finite number")),
            Err(_) => Err(format!("{p:?} is not a number")),
        })
        .collect::<Result<_, _>>()
        .map(Numbers)
}

/// The number of steps for `--duration` and `--dt` ([`rigid::simulation::step_count`]),
/// its errors naming the flags.
fn step_count(args: &SimulateArgs) -> Result<u64, String> {
    step_count_dt(args.duration, args.dt.unwrap_or(1e-3))
}

/// [`step_count`] with the step `dt` (a file's own).
fn step_count_dt(duration: f64, dt: f64) -> Result<u64, String> {
    use rigid::simulation::{step_count, MAX_STEPS};
    step_count(duration, dt).map_err(|e| match e {
        SimulationError::TimeStep { dt } => format!("--dt must be positive and finite, got {dt}"),
        SimulationError::Duration { duration } => {
            format!("--duration must be positive and finite, got {duration}")
        }
        SimulationError::TooManySteps { steps } => {
            format!("{steps:.0} steps is too many (at most {MAX_STEPS}): raise --dt")
        }
        e => e.to_string(),
    })
}

/// Runs `rigid simulate`: a `.toml` input is a body spec, anything else a robot.
pub fn run(args: &SimulateArgs) -> Result<(), String> {
    if let Some(plot) = &args.plot {
        crate::plotting::check_format(plot)?;
    }
    let body = is_body_spec(&args.model);
    // a flag of the other kind of simulation is a mistake, not something to ignore
    let zero = Vec3::zeros();
    let on_ground = body && args.ground.is_some();
    // a body takes none of a robot's flags, but on the ground its pose is --q0 (and its twist
    // --omega and --velocity, not --v0) and it has no pivot
    let robot_only = [
        ("--q0", args.q0.is_some() && !on_ground),
        ("--v0", args.v0.is_some()),
        ("--controller", args.controller != ControlKind::None),
        ("--target", args.target.is_some()),
        ("--move-time", args.move_time.is_some()),
        ("--profile", args.profile != TimeScaling::Quintic),
        ("--limits", args.limits != JointLimits::default()),
        ("--no-joint-dynamics", args.no_joint_dynamics),
        ("--floating", args.load.floating),
        ("--pivot", args.pivot.is_some() && on_ground),
    ];
    let body_only = [
        ("--omega", args.omega != zero),
        ("--velocity", args.velocity != zero),
        ("--pivot", args.pivot.is_some()),
    ];
    let misplaced: &[(&str, bool)] = if body { &robot_only } else { &body_only };
    if let Some((flag, _)) = misplaced.iter().find(|(_, given)| *given) {
        if on_ground {
            return Err(format!(
                "{flag} does not apply to a body on the ground ({}: its pose is --q0 \
                 x,y,z,qx,qy,qz,qw of its CoM, its twist --omega and --velocity)",
                args.model
            ));
        }
        let what = if body {
            "a robot (URDF or model name)"
        } else {
            "a body spec (.toml)"
        };
        return Err(format!("{flag} applies to {what}, not to {}", args.model));
    }
    if body && args.ground.is_none() {
        if let Some(flag) = [
            ("--friction", args.friction),
            ("--restitution", args.restitution),
        ]
        .iter()
        .find_map(|(f, x)| x.map(|_| f))
        {
            return Err(format!("{flag} applies with --ground"));
        }
    }
    if args.srdf.is_some() && !args.self_collision {
        return Err(
            "--srdf applies with --self-collision (its pairs are of the robot's own \
                    bodies)"
                .into(),
        );
    }
    if body && (args.constraints.is_some() || args.self_collision || args.mimic) {
        let flag = if args.self_collision {
            "--self-collision"
        } else if args.mimic {
            "--mimic"
        } else {
            "--constraints"
        };
        return Err(format!("{flag} applies to a robot, not to {}", args.model));
    }
    if body && args.ground.is_none() {
        body::run(args)
    } else {
        robot::run(args)
    }
}

/// True when `model` names a body spec (`.toml`, any case).
pub fn is_body_spec(model: &str) -> bool {
    model.to_ascii_lowercase().ends_with(".toml")
}

/// A progress bar on stderr that appears only once a run has taken more than a second.
pub struct Progress {
    bar: indicatif::ProgressBar,
    start: std::time::Instant,
    shown: bool,
}

impl Progress {
    /// A hidden bar for `steps` steps.
    pub fn new(steps: u64) -> Result<Self, String> {
        use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
        let bar = ProgressBar::with_draw_target(Some(steps), ProgressDrawTarget::hidden());
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} steps, {eta} left")
                .map_err(|e| e.to_string())?,
        );
        Ok(Self {
            bar,
            start: std::time::Instant::now(),
            shown: false,
        })
    }

    /// After step `k`.
    pub fn tick(&mut self, k: u64) {
        if k.is_multiple_of(1024) {
            if !self.shown && self.start.elapsed() > std::time::Duration::from_secs(1) {
                self.bar
                    .set_draw_target(indicatif::ProgressDrawTarget::stderr());
                self.shown = true;
            }
            self.bar.set_position(k);
        }
    }

    /// Clears the bar; returns the wall time (s).
    pub fn finish(self) -> f64 {
        self.bar.finish_and_clear();
        self.start.elapsed().as_secs_f64()
    }
}
