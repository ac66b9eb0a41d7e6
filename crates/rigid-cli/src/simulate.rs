//! `rigid simulate SPEC.toml`: one rigid body, free or on a pivot, integrated on SE(3).

mod plot;

use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rigid::body::{BodyError, Integrator, RigidBody, Simulator, State};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::spatial::{so3, Transform, Twist, Vec3};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The CSV header: pose in the world of the frame at the CoM with the axes of the spec frame
/// (position, quaternion x-y-z-w), and that frame's body twist, angular first.
pub const CSV_HEADER: &str = "t,px,py,pz,qx,qy,qz,qw,wx,wy,wz,vx,vy,vz";

/// Most points drawn per curve in the plot.
const PLOT_POINTS: usize = 2000;

/// Most steps a run may take.
const MAX_STEPS: f64 = 1e9;

/// Options of `rigid simulate`.
#[derive(Args, Debug)]
pub struct SimulateArgs {
    /// The body: a `rigid mass` spec (TOML with `[[part]]` tables).
    pub spec: PathBuf,
    /// Initial body angular velocity `wx,wy,wz` (rad/s, axes of the spec frame).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true, default_value = "0,0,0")]
    pub omega: Vec3,
    /// Initial linear velocity of the CoM `vx,vy,vz` (m/s, axes of the spec frame); a free body
    /// only.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true, default_value = "0,0,0")]
    pub velocity: Vec3,
    /// Gravity `gx,gy,gz` in the world (m/s²); none by default. The world axes start aligned
    /// with the spec frame.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub gravity: Option<Vec3>,
    /// A point `x,y,z` of the spec frame fixed in the world (a spherical pivot), placed at the
    /// world origin.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    pub pivot: Option<Vec3>,
    /// Simulated time (s).
    #[arg(long, default_value_t = 10.0, allow_hyphen_values = true)]
    pub duration: f64,
    /// Time step (s).
    #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true)]
    pub dt: f64,
    /// `rk4` (explicit Lie-group Runge-Kutta-Munthe-Kaas, 4th order) or `variational` (Lie-group
    /// variational integrator: symplectic, momentum to round-off, bounded energy error).
    #[arg(long, default_value = "variational")]
    pub integrator: Integrator,
    /// Write one row per step to this CSV file (header `t,px,py,pz,qx,qy,qz,qw,wx,wy,wz,vx,vy,vz`).
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Draw body angular velocity, energy error and momentum error against time to this SVG file.
    #[arg(long)]
    pub plot: Option<PathBuf>,
}

/// Parses `x,y,z` into three finite numbers.
fn parse_vec3(s: &str) -> Result<Vec3, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!("expected three numbers x,y,z, got {s:?}"));
    }
    let mut v = Vec3::zeros();
    for (i, p) in parts.iter().enumerate() {
        let x: f64 = p.parse().map_err(|_| format!("{p:?} is not a number"))?;
        if !x.is_finite() {
            return Err(format!("{p:?} is not a finite number"));
        }
        v[i] = x;
    }
    Ok(v)
}

/// Mass, CoM (spec frame) and inertia about the CoM (spec-frame axes) of the body in `path`.
fn load_body(path: &Path) -> Result<(f64, Vec3, RotationalInertia), String> {
    let p = crate::mass::load_mass_properties(path)?;
    Ok((p.mass, p.com, p.inertia_com))
}

/// The body and its initial state, in the frame {b} the simulator integrates: at the CoM (free)
/// or at the pivot, with the axes of the spec frame. Also returns `r`: the CoM in {b}.
fn setup(args: &SimulateArgs) -> Result<(RigidBody, State, Vec3), String> {
    let (mass, com, inertia_com) = load_body(&args.spec)?;
    let err = |e: BodyError| e.to_string();
    let (body, r, v_b) = match args.pivot {
        None => {
            let g = SpatialInertia::from_com(mass, Vec3::zeros(), inertia_com);
            (
                RigidBody::free(g).map_err(err)?,
                Vec3::zeros(),
                args.velocity,
            )
        }
        Some(p) => {
            if args.velocity != Vec3::zeros() {
                return Err(
                    "--velocity cannot be used with --pivot: the pivot point is fixed".into(),
                );
            }
            let r = com - p;
            let g = SpatialInertia::from_com(mass, r, inertia_com);
            (RigidBody::pivot(g).map_err(err)?, r, Vec3::zeros())
        }
    };
    let body = body
        .with_gravity(args.gravity.unwrap_or_default())
        .map_err(err)?;
    let x0 = State::new(Transform::identity(), Twist::new(args.omega, v_b));
    Ok((body, x0, r))
}

/// One CSV row: the CoM frame `T_sc = T_sb (I, r)` and its body twist `V_c = [Ad_{T_cb}] V_b`.
fn write_row(out: &mut impl Write, t: f64, x: &State, r: &Vec3) -> std::io::Result<()> {
    let t_bc = Transform::from_translation(*r);
    let pose = x.pose * t_bc;
    let v = t_bc.inv_act_twist(&x.twist);
    let p = pose.translation;
    let [qx, qy, qz, qw] = so3::to_quaternion(&pose.rotation);
    writeln!(
        out,
        "{t},{},{},{},{qx},{qy},{qz},{qw},{},{},{},{},{},{}",
        p.x, p.y, p.z, v.w.x, v.w.y, v.w.z, v.v.x, v.v.y, v.v.z
    )
}

/// Runs `rigid simulate`.
pub fn run(args: &SimulateArgs) -> Result<(), String> {
    if !(args.dt.is_finite() && args.dt > 0.0) {
        return Err(format!("--dt must be positive and finite, got {}", args.dt));
    }
    if !(args.duration.is_finite() && args.duration > 0.0) {
        return Err(format!(
            "--duration must be positive and finite, got {}",
            args.duration
        ));
    }
    let steps = (args.duration / args.dt).round().max(1.0);
    if steps > MAX_STEPS {
        return Err(format!(
            "{steps:.0} steps is too many (at most {MAX_STEPS:.0}): raise --dt"
        ));
    }
    let steps = steps as u64;
    let (body, x0, r) = setup(args)?;
    let mut sim = Simulator::new(body, x0, args.integrator, args.dt).map_err(|e| e.to_string())?;

    let mut csv = match &args.csv {
        Some(path) => {
            let f =
                File::create(path).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            let mut w = BufWriter::new(f);
            writeln!(w, "{CSV_HEADER}").map_err(|e| e.to_string())?;
            write_row(&mut w, 0.0, &x0, &r).map_err(|e| e.to_string())?;
            Some(w)
        }
        None => None,
    };
    let stride = (steps as usize).div_ceil(PLOT_POINTS).max(1) as u64;
    let mut samples = plot::Samples::default();
    if args.plot.is_some() {
        samples.push(0.0, sim.state(), &sim.summary());
    }

    let bar = ProgressBar::with_draw_target(Some(steps), ProgressDrawTarget::hidden());
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} steps, {eta} left")
            .map_err(|e| e.to_string())?,
    );
    let start = Instant::now();
    let mut shown = false;
    let mut failure = None;
    for k in 1..=steps {
        if let Err(e) = sim.step() {
            failure = Some(format!("step {k} (t = {:.6} s): {e}", sim.time()));
            break;
        }
        if let Some(w) = csv.as_mut() {
            write_row(w, sim.time(), sim.state(), &r).map_err(|e| e.to_string())?;
        }
        if args.plot.is_some() && (k.is_multiple_of(stride) || k == steps) {
            samples.push(sim.time(), sim.state(), &sim.summary());
        }
        if k.is_multiple_of(1024) {
            if !shown && start.elapsed() > Duration::from_secs(1) {
                bar.set_draw_target(ProgressDrawTarget::stderr());
                shown = true;
            }
            bar.set_position(k);
        }
    }
    bar.finish_and_clear();
    let wall = start.elapsed().as_secs_f64();
    if let Some(mut w) = csv {
        w.flush().map_err(|e| e.to_string())?;
    }
    if let Some(path) = &args.plot {
        plot::draw(path, &samples).map_err(|e| format!("cannot draw {}: {e}", path.display()))?;
    }
    if let Some(e) = failure {
        return Err(e);
    }
    let s = sim.summary();
    let about = match (args.pivot, s.conserved_axis) {
        (None, _) => "about the CoM",
        (Some(_), None) => "about the pivot",
        (Some(_), Some(_)) => "about the pivot, along gravity",
    };
    println!("integrator: {}", args.integrator);
    println!("steps: {}", s.steps);
    println!("simulated time: {} s", s.time);
    println!(
        "wall time: {wall:.3} s ({:.0} steps/s)",
        s.steps as f64 / wall.max(1e-9)
    );
    println!("relative energy error: {:.3e}", s.relative_energy_error());
    println!(
        "relative angular momentum error ({about}): {:.3e}",
        s.relative_momentum_error()
    );
    Ok(())
}
