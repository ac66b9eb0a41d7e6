//! `rigid simulate MODEL` for a robot: a URDF file, a robot of example-robot-data by name, or a
//! built-in model, simulated by `rigid::multibody::simulation`.

use super::ground;
use super::{robot_plot::Samples, Numbers, SimulateArgs, PLOT_POINTS};
use crate::load::{load_printing_warnings, urdf_path};
use rigid::collision::CollisionModel;
use rigid::multibody::simulation::{
    ControlKind, ControlLaw, Controller, Integrator, JointLimits, SimulationError,
    SimulationOptions, Simulator,
};
use rigid::multibody::{center_of_mass, column_names, neutral, Data, Model};
use rigid::spatial::Vec3;
use rigid_replay::{collision_nodes, robot_nodes, Recording};
use std::io::Write;

/// `t`, then `q_<joint>`, `v_<joint>`, `tau_<joint>` (`_<coordinate>` for multi-dof joints).
fn csv_header(model: &Model, contacts: bool) -> String {
    let mut cols = vec!["t".to_string()];
    cols.extend(column_names(model, &["q", "v", "tau"]));
    if contacts {
        cols.extend(["contacts".to_string(), "normal_force".to_string()]);
    }
    cols.join(",")
}

fn write_row(
    out: &mut impl Write,
    t: f64,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    contacts: Option<(usize, f64)>,
) -> std::io::Result<()> {
    write!(out, "{t}")?;
    for x in q.iter().chain(v).chain(tau) {
        write!(out, ",{x}")?;
    }
    if let Some((n, f)) = contacts {
        write!(out, ",{n},{f}")?;
    }
    writeln!(out)
}

/// A configuration from the command line: `nq` numbers, quaternions of unit norm.
pub(super) fn configuration(
    model: &Model,
    what: &str,
    x: &Option<Numbers>,
) -> Result<Vec<f64>, String> {
    let q = x.clone().map_or_else(|| neutral(model), |n| n.0);
    if q.len() != model.nq() {
        return Err(format!(
            "--{what} has {} numbers; {} has nq = {} ({})",
            q.len(),
            model.name(),
            model.nq(),
            joint_list(model)
        ));
    }
    Ok(q)
}

/// The initial velocity from the command line: `nv` numbers, zero by default.
pub(super) fn velocity(model: &Model, x: &Option<Numbers>) -> Result<Vec<f64>, String> {
    let v0 = x.clone().map_or_else(|| vec![0.0; model.nv()], |n| n.0);
    if v0.len() != model.nv() {
        return Err(format!(
            "--v0 has {} numbers; nv = {}",
            v0.len(),
            model.nv()
        ));
    }
    Ok(v0)
}

/// `name (nq)` for every joint.
fn joint_list(model: &Model) -> String {
    model
        .joints()
        .iter()
        .map(|j| format!("{} ({})", j.name, j.nq))
        .collect::<Vec<_>>()
        .join(", ")
}

fn options(args: &SimulateArgs) -> Result<SimulationOptions, String> {
    // contacts step with the time-stepping scheme; rk4, the default, gives way to it
    let integrator = match (args.ground, args.integrator) {
        (Some(_), Integrator::Rk4) => Integrator::SemiImplicitEuler,
        (_, i) => i,
    };
    Ok(SimulationOptions {
        dt: args.dt,
        integrator,
        limits: args.limits,
        joint_dynamics: !args.no_joint_dynamics,
        ..SimulationOptions::default()
    })
}

fn controller(
    args: &SimulateArgs,
    model: &Model,
    q0: &[f64],
    target: Option<Vec<f64>>,
    collision: Option<&CollisionModel>,
) -> Result<Controller, String> {
    if let (Some(cm), ControlKind::Pd, Some(target)) = (collision, args.controller, &target) {
        // standing: PD to the stance with the torques that hold it on its contacts
        let law = ControlLaw::standing(model, target, cm).map_err(|e| format!("--target: {e}"))?;
        return Controller::new(model, law).map_err(|e| e.to_string());
    }
    let time = args.move_time.unwrap_or(0.5 * args.duration);
    let law = ControlLaw::builtin(
        model,
        args.controller,
        q0,
        target.as_deref(),
        time,
        args.profile,
    )
    .map_err(|e| match e {
        SimulationError::MissingTarget { controller, nq } => {
            format!("--controller {controller} needs --target (nq = {nq} numbers)")
        }
        e => format!("--target: {e}"),
    })?;
    Controller::new(model, law).map_err(|e| e.to_string())
}

/// Runs `rigid simulate` on a robot.
pub fn run(args: &SimulateArgs) -> Result<(), String> {
    let steps = super::step_count(args)?;
    // a body spec on the ground is a one-body model: its pose is --q0 (the CoM and the spec
    // axes), its twist --omega and --velocity
    let spec = super::is_body_spec(&args.model);
    let (loaded, collision) = if spec {
        let (loaded, cm) = ground::body_on_ground(args)?;
        (loaded, Some(cm))
    } else {
        let loaded = load_printing_warnings(&args.model, &args.load)?;
        let cm = ground::collision_model(args, &loaded)?;
        (loaded, cm)
    };
    let home = loaded.home();
    let mut model = loaded.model;
    if let Some(g) = args.gravity {
        model = model.with_gravity(g);
    }
    // an MJCF model starts where the file puts it (MuJoCo's qpos0)
    let mut target = match &args.target {
        Some(_) => Some(configuration(&model, "target", &args.target)?),
        None => None,
    };
    let mut q0 = match (&args.q0, &target, &collision) {
        (None, Some(t), Some(_)) => t.clone(),
        (None, _, _) => home,
        (Some(_), _, _) => configuration(&model, "q0", &args.q0)?,
    };
    if let Some(cm) = &collision {
        // a floating robot starts on the ground, and its stance is on the ground
        if args.q0.is_none() {
            ground::set_down(&model, cm, &mut q0)?;
        }
        if let Some(t) = target.as_mut() {
            ground::set_down(&model, cm, t)?;
        }
    }
    let v0 = if spec {
        let (w, v) = (args.omega, args.velocity);
        vec![w.x, w.y, w.z, v.x, v.y, v.z]
    } else {
        velocity(&model, &args.v0)?
    };
    let opts = options(args)?;
    let ctrl = controller(args, &model, &q0, target, collision.as_ref())?;
    let mut sim = Simulator::new(&model, &q0, &v0, opts, ctrl).map_err(|e| e.to_string())?;
    let contacts = collision.is_some();
    // a body spec has no visual of its own: the page draws its parts' shapes
    let spec_nodes = collision
        .as_ref()
        .filter(|_| spec && args.html.is_some())
        .map(collision_nodes);
    if let Some(cm) = collision {
        sim = sim.with_collision(cm).map_err(|e| e.to_string())?;
    }
    let contact_row = |sim: &Simulator| {
        contacts.then(|| {
            let s = sim.contact_stats();
            (s.active, s.normal_impulse / args.dt)
        })
    };
    let (nq, nv) = (model.nq(), model.nv());

    let mut csv = match &args.csv {
        Some(path) => Some(crate::util::AtomicFile::create(path)?),
        None => None,
    };
    let tau_row = |sim: &mut Simulator| -> Result<Vec<f64>, String> {
        Ok(sim.torques().map_err(|e| e.to_string())?.0.to_vec())
    };
    if let Some(f) = csv.as_mut() {
        writeln!(f.writer(), "{}", csv_header(&model, contacts)).map_err(|e| e.to_string())?;
        let tau = tau_row(&mut sim)?;
        write_row(f.writer(), 0.0, &q0, &v0, &tau, contact_row(&sim)).map_err(|e| e.to_string())?;
    }
    let mut scene = match (spec_nodes, &args.html) {
        (Some((nodes, warnings)), _) => rigid_replay::Scene {
            nodes,
            warnings,
            extent: 0.5,
            ..Default::default()
        },
        (None, Some(_)) => robot_nodes(&model, urdf_path(&args.model).as_deref()),
        (None, None) => Default::default(),
    };
    let mut rec = Recording::default();
    let mut data = Data::new(&model);
    // with --ground the page draws the ground, marks the contacts that push and draws their
    // forces (the last step's impulse over dt), the weight's arrow half the robot's size
    let height = args.ground.unwrap_or_default();
    let markers = match (&args.html, contacts) {
        (Some(_), true) => {
            let c = center_of_mass(&model, &mut data, &q0).map_err(|e| e.to_string())?;
            let weight = model.total_mass() * model.gravity().norm();
            Some(scene.add_ground(height, c, weight))
        }
        _ => None,
    };
    let mark = |scene: &mut rigid_replay::Scene, sim: &Simulator| {
        if let Some(first) = markers {
            let pushing: Vec<(Vec3, Vec3)> = sim
                .contacts()
                .iter()
                .zip(sim.contact_impulses())
                .filter(|(_, p)| p.norm() > 0.0)
                .map(|(c, p)| (c.point, p / args.dt))
                .collect();
            scene.set_contacts(first, &pushing, height);
        }
    };
    if args.html.is_some() {
        mark(&mut scene, &sim);
        rec.record_model(&scene, &model, &mut data, 0.0, &q0, true)?;
    }
    let stride = (steps as usize).div_ceil(PLOT_POINTS).max(1) as u64;
    let mut samples = Samples::new(&model);
    let (e0, k0) = {
        let (k, u) = sim.energies().map_err(|e| e.to_string())?;
        (k + u, k)
    };
    if args.plot.is_some() {
        let tau = tau_row(&mut sim)?;
        let c = contacts.then_some((0.0, 0.0));
        samples.push(0.0, sim.q(), sim.v(), &tau, e0, c);
    }
    let mut max_speed = (0.0f64, 0usize);
    let mut max_penetration = 0.0f64;
    let mut progress = super::Progress::new(steps)?;
    let mut failure = None;
    for k in 1..=steps {
        if let Err(e) = sim.step() {
            failure = Some(format!("step {k} (t = {:.6} s): {e}", sim.time()));
            break;
        }
        let t = sim.time();
        max_penetration = max_penetration.max(sim.contact_stats().penetration);
        for (i, x) in sim.v().iter().enumerate() {
            if x.abs() > max_speed.0 {
                max_speed = (x.abs(), i);
            }
        }
        let plot_now = args.plot.is_some() && (k.is_multiple_of(stride) || k == steps);
        if csv.is_some() || plot_now {
            let tau = tau_row(&mut sim)?;
            if let Some(f) = csv.as_mut() {
                write_row(f.writer(), t, sim.q(), sim.v(), &tau, contact_row(&sim))
                    .map_err(|e| e.to_string())?;
            }
            if plot_now {
                let e = sim.energy().map_err(|e| e.to_string())?;
                let c = contact_row(&sim).map(|(_, n)| (n, sim.contact_dissipation()));
                samples.push(t, sim.q(), sim.v(), &tau, e, c);
            }
        }
        if args.html.is_some() && (rec.due(t) || k == steps) {
            mark(&mut scene, &sim);
            rec.record_model(&scene, &model, &mut data, t, sim.q(), k == steps)?;
        }
        progress.tick(k);
    }
    let wall = progress.finish();
    if let Some(f) = csv {
        f.commit()?;
    }
    if let Some(path) = &args.plot {
        samples.draw(path)?;
    }
    let limits = match opts.limits {
        JointLimits::Ignored => "ignored".to_string(),
        JointLimits::Unilateral => "unilateral (an impulse stops a joint at its limit)".to_string(),
        JointLimits::Spring {
            time_constant,
            damping_ratio,
        } => {
            format!("spring-damper past a limit (time constant {time_constant} s, damping ratio {damping_ratio})")
        }
    };
    if let Some(path) = &args.html {
        scene.title = format!("{} — {}", model.name(), args.controller);
        scene.info = format!(
            "{}, dt = {} s, {:.3} s simulated; limits {}",
            opts.integrator,
            args.dt,
            sim.time(),
            if opts.limits == JointLimits::Ignored {
                "ignored"
            } else {
                "spring"
            }
        );
        if let Some(e) = &failure {
            scene.warnings.push(format!("stopped: {e}"));
        }
        crate::util::write_atomic(path, scene.html(&rec).as_bytes())?;
        for w in &scene.warnings {
            eprintln!("warning: replay: {w}");
        }
    }
    if let Some(e) = failure {
        return Err(e);
    }
    let (k1, u1) = sim.energies().map_err(|e| e.to_string())?;
    let e1 = k1 + u1;
    let scale = e0.abs().max(k0.abs());
    let drift = if scale > 0.0 {
        (e1 - e0).abs() / scale
    } else {
        (e1 - e0).abs()
    };
    let dof = max_speed.1;
    let dof_name = &model.joints()[model.dof_joint(dof).0].name;
    let passive = model
        .damping()
        .iter()
        .chain(model.friction())
        .any(|x| *x > 0.0)
        && opts.joint_dynamics;
    println!("model: {} (nq = {nq}, nv = {nv})", model.name());
    println!(
        "integrator: {}, dt = {} s, controller: {}",
        opts.integrator, args.dt, args.controller
    );
    println!("joint limits: {limits}");
    println!(
        "joint damping and friction: {}",
        if passive {
            "on (URDF <dynamics>)"
        } else {
            "off"
        }
    );
    if let Some(h) = args.ground {
        let s = sim.contact_stats();
        println!(
            "ground: z = {h} m, friction {}, restitution {}",
            args.friction.unwrap_or(rigid::collision::DEFAULT_FRICTION),
            args.restitution.unwrap_or(0.0)
        );
        println!(
            "contacts at the end: {} active, normal force {:.6} N; deepest penetration {max_penetration:.3e} m",
            s.active,
            s.normal_impulse / args.dt
        );
    }
    println!("steps: {}", sim.steps());
    println!("simulated time: {} s", sim.time());
    println!(
        "wall time: {wall:.3} s ({:.0} steps/s)",
        sim.steps() as f64 / wall.max(1e-9)
    );
    println!("energy: {e0:.6} J -> {e1:.6} J, relative drift {drift:.3e} (exact only without control, damping, friction and limits)");
    println!(
        "max joint speed: {:.4} (dof {dof}, joint {dof_name})",
        max_speed.0
    );
    let names: Vec<String> = model
        .joints()
        .iter()
        .map(|j| {
            let r = j.idx_q..j.idx_q + j.nq;
            let x: Vec<String> = sim.q()[r].iter().map(|x| format!("{x:.6}")).collect();
            format!("{}={}", j.name, x.join(","))
        })
        .collect();
    println!("final q: {}", names.join(" "));
    Ok(())
}
