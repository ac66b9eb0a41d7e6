//! `rigid mobile h|odometry|capstone`: wheeled mobile robots ([`rigid::mobile`]). This file parses
//! the flags and prints; the kinematics, odometry and the capstone are the library's.

use crate::util::write_atomic;
use clap::{Args, Subcommand};
use rigid::mobile::{Base, Kind};
use std::fmt::Write as _;
use std::path::PathBuf;

/// Options of `rigid mobile`.
#[derive(Args, Debug)]
pub struct MobileArgs {
    #[command(subcommand)]
    pub command: MobileCommand,
}

/// The verbs of `rigid mobile`.
#[derive(Subcommand, Debug)]
pub enum MobileCommand {
    /// A base's H(φ) (wheel speeds u = H(φ) q̇ for q = (φ, x, y)), F = H(0)† and its
    /// nonholonomic constraint.
    H(HArgs),
    /// Odometry: the chassis configuration (φ, x, y) along a CSV of wheel angles.
    Odometry(OdometryArgs),
    /// A robot (URDF) on the ground with its wheels under velocity control: how it moves, beside
    /// its kinematic model; CSV and a replay.
    Drive(Box<DriveArgs>),
    /// The Modern Robotics capstone: the youBot picks a cube and places it, its end effector
    /// driven along the reference by feedforward plus PI; the course's scene CSV, X_err, a plot
    /// and a replay.
    Capstone(CapstoneArgs),
}

/// The base: its kind and geometry.
#[derive(Args, Debug)]
pub struct BaseArgs {
    /// `mecanum` (--radius, --half-length l, --half-width w), `omni3` (--radius, --distance d),
    /// `diff-drive` (--radius, --track), `car` (--radius, --track, --wheelbase), or `youbot`
    /// (the capstone's mecanum base: r = 0.0475, l = 0.235, w = 0.15).
    #[arg(long)]
    pub base: Option<String>,
    /// Wheel radius r (m).
    #[arg(long, allow_hyphen_values = true)]
    pub radius: Option<f64>,
    /// Mecanum: half the distance between the front and rear axles, l (m).
    #[arg(long, allow_hyphen_values = true)]
    pub half_length: Option<f64>,
    /// Mecanum: half the distance between the left and right wheels, w (m).
    #[arg(long, allow_hyphen_values = true)]
    pub half_width: Option<f64>,
    /// Omni3: the wheels' distance from the centre, d (m).
    #[arg(long, allow_hyphen_values = true)]
    pub distance: Option<f64>,
    /// Differential drive, car: distance between the driven wheels (m).
    #[arg(long, allow_hyphen_values = true)]
    pub track: Option<f64>,
    /// Car: rear axle to front axle (m).
    #[arg(long, allow_hyphen_values = true)]
    pub wheelbase: Option<f64>,
}

impl BaseArgs {
    /// The base `--base` names.
    fn base(&self) -> Result<Base, String> {
        self.optional()?.ok_or_else(|| {
            "--base is required: mecanum, omni3, diff-drive, car or youbot".to_string()
        })
    }

    /// The base `--base` names, if it is given.
    pub fn optional(&self) -> Result<Option<Base>, String> {
        let Some(kind) = &self.base else {
            return Ok(None);
        };
        let need =
            |x: Option<f64>, flag: &str| x.ok_or_else(|| format!("--base {kind} needs --{flag}"));
        let r = || need(self.radius, "radius");
        match kind.as_str() {
            "youbot" => Ok(Base::youbot()),
            "mecanum" => Base::mecanum(
                r()?,
                need(self.half_length, "half-length")?,
                need(self.half_width, "half-width")?,
            ),
            "omni3" => Base::omni3(r()?, need(self.distance, "distance")?),
            "diff-drive" => Base::diff_drive(r()?, need(self.track, "track")?),
            "car" => Base::car(
                r()?,
                need(self.track, "track")?,
                need(self.wheelbase, "wheelbase")?,
            ),
            other => {
                return Err(format!(
                    "unknown base {other:?}: expected mecanum, omni3, diff-drive, car or youbot"
                ))
            }
        }
        .map(Some)
        .map_err(|e| e.to_string())
    }
}

/// Options of `rigid mobile h`.
#[derive(Args, Debug)]
pub struct HArgs {
    #[command(flatten)]
    pub base: BaseArgs,
    /// The chassis heading φ (rad).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub phi: f64,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Options of `rigid mobile odometry`.
#[derive(Args, Debug)]
pub struct OdometryArgs {
    #[command(flatten)]
    pub base: BaseArgs,
    /// A CSV of wheel angles (rad), one row per sample, one column per wheel (in the order of H's
    /// rows); an optional header line, whose first cell `t` marks a time column first.
    pub wheels: PathBuf,
    /// The chassis configuration at the first row, `φ,x,y`.
    #[arg(long, value_parser = crate::simulate::parse_list, allow_hyphen_values = true)]
    pub start: Option<crate::simulate::Numbers>,
    /// Write the CSV here instead of printing it.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Options of `rigid mobile drive`.
#[derive(Args, Debug)]
pub struct DriveArgs {
    /// A URDF file or a robot of example-robot-data by name (loaded with a free-flyer root and
    /// set down on the ground z = 0).
    pub model: String,
    /// The wheel joints, comma-separated (revolute or continuous).
    #[arg(long, value_delimiter = ',')]
    pub wheels: Vec<String>,
    /// Their commanded speeds (rad/s), comma-separated.
    #[arg(long, value_parser = crate::simulate::parse_list, allow_hyphen_values = true)]
    pub speeds: crate::simulate::Numbers,
    /// The kinematic model to compare with (its wheels in the order of --wheels): v and ω it
    /// predicts, `F u`, beside the simulated ones.
    #[command(flatten)]
    pub base: BaseArgs,
    /// Simulated time (s).
    #[arg(long, default_value_t = 3.0)]
    pub time: f64,
    /// Time step (s).
    #[arg(long, default_value_t = 1e-3)]
    pub dt: f64,
    /// Velocity gain K of `τ = K (u_d − u)` on each wheel (N·m·s/rad).
    #[arg(long, default_value_t = 20.0)]
    pub gain: f64,
    /// Coulomb friction of the ground.
    #[arg(long, default_value_t = 1.0)]
    pub friction: f64,
    /// Friction of the wheels' own collision shapes (a shape's friction with the ground is the
    /// larger of the two: `--friction 0 --wheel-friction 1` makes everything but the wheels
    /// slide freely, as swivel casters that a URDF fixes).
    #[arg(long)]
    pub wheel_friction: Option<f64>,
    /// Hold the other actuated joints at their start with the stance controller (an arm, a
    /// torso); without it they are passive (casters).
    #[arg(long)]
    pub hold: bool,
    /// CSV of `t,x,y,yaw,v,omega` and the wheel speeds, every step.
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// A 3D replay in the browser (self-contained HTML).
    #[arg(long)]
    pub html: Option<PathBuf>,
}

/// Options of `rigid mobile capstone`.
#[derive(Args, Debug)]
pub struct CapstoneArgs {
    /// The course's scene CSV (13 columns per row, no header: φ, x, y, 5 arm joints, 4 wheels,
    /// gripper), for CoppeliaSim's scene 6.
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// X_err at each step as CSV (`t,wx,wy,wz,vx,vy,vz`).
    #[arg(long)]
    pub errors: Option<PathBuf>,
    /// A plot of X_err against time (SVG or PNG).
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// A 3D replay in the browser (self-contained HTML): the youBot carrying the cube.
    #[arg(long)]
    pub html: Option<PathBuf>,
    /// K_p, the same on all six rows (1/s).
    #[arg(long, default_value_t = 1.5)]
    pub kp: f64,
    /// K_i (1/s²).
    #[arg(long, default_value_t = 0.0)]
    pub ki: f64,
    /// Keep arm joints 3 and 4 below -0.2 rad (away from the stretched-arm singularity), as the
    /// capstone suggests: a joint about to leave its range stops and the others take over; the
    /// arm then starts at (0, 0, -0.3, -1.6, 0), inside that range.
    #[arg(long)]
    pub limits: bool,
    /// Control period and reference step (s).
    #[arg(long, default_value_t = 0.01)]
    pub dt: f64,
    /// Speed limit of every wheel and joint (rad/s).
    #[arg(long, default_value_t = 15.0)]
    pub max_speed: f64,
    /// The chassis at the start, `φ,x,y` (default 0.5,-0.2,0.2: 0.42 m and 30° off the reference).
    #[arg(long, value_parser = crate::simulate::parse_list, allow_hyphen_values = true)]
    pub chassis: Option<crate::simulate::Numbers>,
}

/// Runs `rigid mobile`.
pub fn run(args: &MobileArgs) -> Result<(), String> {
    match &args.command {
        MobileCommand::H(a) => h(a),
        MobileCommand::Odometry(a) => odometry(a),
        MobileCommand::Drive(a) => crate::mobile_drive::run(a),
        MobileCommand::Capstone(a) => crate::mobile_capstone::run(a),
    }
}

fn rows_text(m: &nalgebra::DMatrix<f64>) -> String {
    let mut s = String::new();
    for r in 0..m.nrows() {
        let row: Vec<String> = (0..m.ncols())
            .map(|c| format!("{:>10.5}", m[(r, c)]))
            .collect();
        let _ = writeln!(s, "  {}", row.join(" "));
    }
    s
}

fn rows_json(m: &nalgebra::DMatrix<f64>) -> serde_json::Value {
    (0..m.nrows())
        .map(|r| (0..m.ncols()).map(|c| m[(r, c)]).collect::<Vec<_>>())
        .collect()
}

fn h(args: &HArgs) -> Result<(), String> {
    if !args.phi.is_finite() {
        return Err(format!("--phi must be finite, got {}", args.phi));
    }
    let base = args.base.base()?;
    let (hm, f) = (base.H(args.phi), base.F().clone());
    let a = base.constraint([args.phi, 0.0, 0.0]);
    if args.json {
        let v = serde_json::json!({
            "base": base.name(),
            "wheels": base.wheels().len(),
            "phi": args.phi,
            "H": rows_json(&hm),
            "F": rows_json(&f),
            "constraint": a,
        });
        println!("{v}");
        return Ok(());
    }
    println!(
        "{} base, {} wheels, φ = {} rad",
        base.name(),
        base.wheels().len(),
        args.phi
    );
    println!("H(φ): wheel speeds u = H(φ) q̇, q̇ = (φ̇, ẋ, ẏ) (rad/s per rad/s, m/s)");
    print!("{}", rows_text(&hm));
    println!("F = H(0)†: the body twist (ω_z, v_x, v_y) = F u");
    print!("{}", rows_text(&f));
    match (a, base.kind()) {
        (Some(a), Kind::Car { wheelbase, .. }) => println!(
            "nonholonomic: A(q) q̇ = 0 with A = [{:.5}, {:.5}, {:.5}]; steering ψ = atan({wheelbase} ω / v)",
            a[0], a[1], a[2]
        ),
        (Some(a), _) => println!(
            "nonholonomic: A(q) q̇ = 0 with A = [{:.5}, {:.5}, {:.5}]",
            a[0], a[1], a[2]
        ),
        (None, _) => println!("omnidirectional: any (ω_z, v_x, v_y)"),
    }
    Ok(())
}

fn odometry(args: &OdometryArgs) -> Result<(), String> {
    let base = args.base.base()?;
    let m = base.wheels().len();
    let text = std::fs::read_to_string(&args.wheels)
        .map_err(|e| format!("{}: {e}", args.wheels.display()))?;
    let mut q = match &args.start {
        Some(n) if n.0.len() == 3 => [n.0[0], n.0[1], n.0[2]],
        Some(n) => return Err(format!("--start has {} numbers; expected φ,x,y", n.0.len())),
        None => [0.0; 3],
    };
    let file = args.wheels.display();
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .peekable();
    // a header (a first line of names, no numbers) names a time column by a first cell `t`
    let mut timed = false;
    if let Some((_, first)) = lines.peek() {
        let cells: Vec<&str> = first.split(',').map(str::trim).collect();
        let words = cells.iter().filter(|c| c.parse::<f64>().is_err()).count();
        if words > 0 && words < cells.len() {
            return Err(format!("{file} line 1: not numbers, nor a header of names"));
        }
        if words > 0 {
            timed = cells[0].eq_ignore_ascii_case("t") || cells[0].eq_ignore_ascii_case("time");
            if cells.len() != m + usize::from(timed) {
                return Err(format!(
                    "{file} line 1: a header of {} columns; the {} base has {m} wheels (and an \
                     optional time column t first)",
                    cells.len(),
                    base.name()
                ));
            }
            lines.next();
        }
    }
    let mut out = String::from(if timed { "t,phi,x,y\n" } else { "phi,x,y\n" });
    let mut previous: Option<Vec<f64>> = None;
    for (i, line) in lines {
        let at = |what: String| format!("{file} line {}: {what}", i + 1);
        let cells: Vec<f64> = line
            .split(',')
            .map(|c| c.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| at(format!("not numbers: {}", line.trim())))?;
        if cells.len() != m + usize::from(timed) {
            return Err(at(format!(
                "{} numbers; expected {}{m} wheel angles",
                cells.len(),
                if timed { "a time and " } else { "" }
            )));
        }
        if cells.iter().any(|x| !x.is_finite()) {
            return Err(at("a number that is not finite".into()));
        }
        let angles = cells[usize::from(timed)..].to_vec();
        if let Some(p) = &previous {
            let d: Vec<f64> = angles.iter().zip(p).map(|(a, b)| a - b).collect();
            q = base.odometry(q, &d).map_err(|e| at(e.to_string()))?;
        }
        if timed {
            let _ = write!(out, "{},", cells[0]);
        }
        let _ = writeln!(out, "{},{},{}", q[0], q[1], q[2]);
        previous = Some(angles);
    }
    if previous.is_none() {
        return Err(format!(
            "{}: no rows of wheel angles",
            args.wheels.display()
        ));
    }
    match &args.out {
        Some(path) => {
            write_atomic(path, out.as_bytes())?;
            println!("wrote {}", path.display());
        }
        None => print!("{out}"),
    }
    Ok(())
}
