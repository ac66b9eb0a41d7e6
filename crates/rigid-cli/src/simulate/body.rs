//! `rigid simulate SPEC.toml`: one rigid body, free or on a pivot, integrated on SE(3).

use super::{plot, SimulateArgs};
use rigid::body::{BodyError, Setup, Simulator, State};
use rigid::spatial::{so3, Transform};
use rigid_replay::{body_box, Recording};
use std::io::Write;
use std::path::Path;

/// The CSV header: pose in the world of the frame at the CoM with the axes of the spec frame
/// (position, quaternion x-y-z-w), and that frame's body twist, angular first.
pub const CSV_HEADER: &str = "t,px,py,pz,qx,qy,qz,qw,wx,wy,wz,vx,vy,vz";

use super::PLOT_POINTS;

/// The body of the spec and its initial state ([`Setup`]): in a frame {b} at the CoM (free) or
/// at the pivot, with the axes of the spec frame.
fn setup(args: &SimulateArgs) -> Result<Setup, String> {
    let props = crate::mass::load_mass_properties(Path::new(&args.model))?;
    let gravity = args.gravity.unwrap_or_default();
    Setup::new(&props, args.pivot, args.omega, args.velocity, gravity).map_err(|e| match e {
        BodyError::PivotMoves { .. } => {
            "--velocity cannot be used with --pivot: the pivot point is fixed".into()
        }
        e => e.to_string(),
    })
}

/// One CSV row: the CoM frame's pose and body twist ([`Setup::com_frame`]).
fn write_row(out: &mut impl Write, t: f64, x: &State, s: &Setup) -> std::io::Result<()> {
    let (pose, v) = s.com_frame(x);
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
    let steps = super::step_count(args)?;
    let integrator = args.integrator;
    let setup = setup(args)?;
    let (x0, body) = (setup.x0, &setup.body);
    let (mass, inertia) = (body.inertia().mass(), body.inertia().inertia_com());
    let mut sim = Simulator::new(body.clone(), x0, integrator, args.dt.unwrap_or(1e-3))
        .map_err(|e| e.to_string())?;

    let mut csv = match &args.csv {
        Some(path) => {
            let mut f = crate::util::AtomicFile::create(path)?;
            let w = f.writer();
            writeln!(w, "{CSV_HEADER}").map_err(|e| e.to_string())?;
            write_row(w, 0.0, &x0, &setup).map_err(|e| e.to_string())?;
            Some(f)
        }
        None => None,
    };
    // the replay: the inertia-equivalent box at the CoM
    let mut scene = body_box(mass, &inertia);
    let mut rec = Recording::default();
    let com_pose = |x: &State| -> Transform { setup.com_frame(x).0 };
    if args.html.is_some() {
        let p = com_pose(&x0);
        rec.push(0.0, [p], p.translation);
    }
    let stride = (steps as usize).div_ceil(PLOT_POINTS).max(1) as u64;
    let mut samples = plot::Samples::default();
    if args.plot.is_some() {
        samples.push(0.0, sim.state(), &sim.summary());
    }

    let mut progress = super::Progress::new(steps)?;
    let mut failure = None;
    for k in 1..=steps {
        if let Err(e) = sim.step() {
            failure = Some(format!("step {k} (t = {:.6} s): {e}", sim.time()));
            break;
        }
        if let Some(f) = csv.as_mut() {
            write_row(f.writer(), sim.time(), sim.state(), &setup).map_err(|e| e.to_string())?;
        }
        if args.html.is_some() && (rec.due(sim.time()) || k == steps) {
            let p = com_pose(sim.state());
            rec.push(sim.time(), [p], p.translation);
        }
        if args.plot.is_some() && (k.is_multiple_of(stride) || k == steps) {
            samples.push(sim.time(), sim.state(), &sim.summary());
        }
        progress.tick(k);
    }
    let wall = progress.finish();
    if let Some(f) = csv {
        f.commit()?;
    }
    if let Some(path) = &args.plot {
        plot::draw(path, &samples)?;
    }
    if let Some(path) = &args.html {
        let name = Path::new(&args.model)
            .file_name()
            .map_or(args.model.clone(), |n| n.to_string_lossy().into_owned());
        scene.title = format!(
            "{name} ({} body)",
            if args.pivot.is_some() {
                "pivoted"
            } else {
                "free"
            }
        );
        scene.info = format!(
            "{integrator}, dt = {} s, {} s",
            args.dt.unwrap_or(1e-3),
            args.duration
        );
        crate::util::write_atomic(path, scene.html(&rec).as_bytes())?;
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
    println!("integrator: {integrator}");
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
