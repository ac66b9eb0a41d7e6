//! `rigid simulate SPEC.toml`: one rigid body, free or on a pivot, integrated on SE(3).

use super::{plot, SimulateArgs};
use rigid::body::{BodyError, Integrator, RigidBody, Simulator, State};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::spatial::{so3, Transform, Twist, Vec3};
use rigid_replay::{body_box, Recording};
use std::io::Write;
use std::path::Path;

/// The CSV header: pose in the world of the frame at the CoM with the axes of the spec frame
/// (position, quaternion x-y-z-w), and that frame's body twist, angular first.
pub const CSV_HEADER: &str = "t,px,py,pz,qx,qy,qz,qw,wx,wy,wz,vx,vy,vz";

use super::PLOT_POINTS;

/// Mass, CoM (spec frame) and inertia about the CoM (spec-frame axes) of the body in `path`.
fn load_body(path: &Path) -> Result<(f64, Vec3, RotationalInertia), String> {
    let p = crate::mass::load_mass_properties(path)?;
    Ok((p.mass, p.com, p.inertia_com))
}

/// The body and its initial state, in the frame {b} the simulator integrates: at the CoM (free)
/// or at the pivot, with the axes of the spec frame. Also returns `r`: the CoM in {b}.
fn setup(args: &SimulateArgs) -> Result<(RigidBody, State, Vec3), String> {
    let (mass, com, inertia_com) = load_body(Path::new(&args.model))?;
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
    let steps = super::step_count(args)?;
    let integrator: Integrator = args
        .integrator
        .as_deref()
        .unwrap_or("variational")
        .parse()?;
    let (body, x0, r) = setup(args)?;
    let (mass, inertia) = (body.inertia().mass(), body.inertia().inertia_com());
    let mut sim = Simulator::new(body, x0, integrator, args.dt).map_err(|e| e.to_string())?;

    let mut csv = match &args.csv {
        Some(path) => {
            let mut f = crate::util::AtomicFile::create(path)?;
            let w = f.writer();
            writeln!(w, "{CSV_HEADER}").map_err(|e| e.to_string())?;
            write_row(w, 0.0, &x0, &r).map_err(|e| e.to_string())?;
            Some(f)
        }
        None => None,
    };
    // the replay: the inertia-equivalent box at the CoM
    let mut scene = body_box(mass, &inertia);
    let mut rec = Recording::default();
    let com_pose = |x: &State| x.pose * Transform::from_translation(r);
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
            write_row(f.writer(), sim.time(), sim.state(), &r).map_err(|e| e.to_string())?;
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
        scene.info = format!("{integrator}, dt = {} s, {} s", args.dt, args.duration);
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
