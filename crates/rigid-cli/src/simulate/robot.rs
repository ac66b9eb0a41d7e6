//! `rigid simulate MODEL` for a robot: a URDF file, a robot of example-robot-data by name, or a
//! built-in model, simulated by `rigid::simulation`.

use super::world;
use super::{robot_plot::Samples, SimulateArgs, PLOT_POINTS};
use crate::load::urdf_path;
use rigid::multibody::{center_of_mass, column_names, Data, Model};
use rigid::simulation::contact::{ContactResiduals, ContactStats};
use rigid::simulation::{JointLimits, Simulator};
use rigid::spatial::Vec3;
use rigid_replay::{collision_nodes, robot_nodes, Recording};
use std::io::Write;

/// The CSV header (docs/cli.md): `t`, then `q_<joint>`, `v_<joint>`, `tau_<joint>`
/// (`_<coordinate>` for multi-dof joints) and `energy`; a body spec's `t,px,py,pz,qx,qy,qz,qw,
/// wx,wy,wz,vx,vy,vz` (the CoM frame's pose and body twist) and `energy`; then `contacts` and
/// `normal_force` when anything can touch (and with `--residuals` the solve's `iterations`,
/// `converged`, `signorini`, `coulomb`, `dissipation`, `velocity_error`), `violation_position` and
/// `violation_velocity` with bilateral constraints.
fn csv_header(model: &Model, spec: bool, contacts: Columns, loops: bool) -> String {
    let mut cols: Vec<String> = if spec {
        super::body::CSV_HEADER
            .split(',')
            .map(String::from)
            .collect()
    } else {
        let mut c = vec!["t".to_string()];
        c.extend(column_names(model, &["q", "v", "tau"]));
        c
    };
    cols.push("energy".into());
    if contacts != Columns::None {
        cols.extend(["contacts".to_string(), "normal_force".to_string()]);
    }
    if contacts == Columns::Residuals {
        cols.extend(ContactStats::SOLVE_COLUMNS.map(String::from));
    }
    if loops {
        cols.extend(["violation_position", "violation_velocity"].map(String::from));
    }
    cols.join(",")
}

/// The CSV's contact columns.
#[derive(Clone, Copy, PartialEq)]
enum Columns {
    None,
    Contacts,
    /// The contacts and their solve.
    Residuals,
}

/// One CSV row of `sim` (a body spec: no torques).
fn write_row(
    out: &mut impl Write,
    sim: &mut Simulator,
    spec: bool,
    contacts: Columns,
    loops: bool,
    dt: f64,
) -> Result<(), String> {
    let (t, q, v) = (sim.time(), sim.q().to_vec(), sim.v().to_vec());
    let tau = if spec {
        Vec::new()
    } else {
        sim.torques().map_err(|e| e.to_string())?.0.to_vec()
    };
    let e = sim.energy().map_err(|e| e.to_string())?;
    let mut row = format!("{t}");
    for x in q.iter().chain(&v).chain(&tau) {
        row += &format!(",{x}");
    }
    row += &format!(",{e}");
    let s = sim.contact_stats();
    if contacts != Columns::None {
        row += &format!(",{},{}", s.active, s.normal_impulse / dt);
    }
    if contacts == Columns::Residuals {
        for x in s.solve_row() {
            row += &format!(",{x}");
        }
    }
    if loops {
        let w = sim.violation().map_err(|e| e.to_string())?;
        row += &format!(",{},{}", w.position, w.velocity);
    }
    writeln!(out, "{row}").map_err(|e| e.to_string())
}

/// Runs `rigid simulate` on a robot (or a body spec on the ground).
pub fn run(args: &SimulateArgs) -> Result<(), String> {
    super::step_count(args)?; // the flags' own errors first
    let world = world::world(args)?;
    let (scenario, spec, dt) = (&world.scenario, world.spec, world.dt);
    let steps = super::step_count_dt(args.duration, dt)?;
    let model = &scenario.model;
    let contacts = scenario.touches();
    let loops = !scenario.constraints.is_empty();
    let mut sim = scenario.build().map_err(world::simulation_error)?;
    let opts = *sim.options();
    let q0 = sim.q().to_vec();
    // a body spec has no visual of its own: the page draws its parts' shapes
    let spec_nodes = scenario
        .collision
        .as_ref()
        .filter(|_| spec && args.html.is_some())
        .map(collision_nodes);
    let (nq, nv) = (model.nq(), model.nv());

    let mut csv = match &args.csv {
        Some(path) => Some(crate::util::AtomicFile::create(path)?),
        None => None,
    };
    let columns = match (contacts, args.residuals) {
        (false, _) => Columns::None,
        (true, false) => Columns::Contacts,
        (true, true) => Columns::Residuals,
    };
    if let Some(f) = csv.as_mut() {
        writeln!(f.writer(), "{}", csv_header(model, spec, columns, loops))
            .map_err(|e| e.to_string())?;
        write_row(f.writer(), &mut sim, spec, columns, loops, dt)?;
    }
    let mut scene = match (spec_nodes, &args.html) {
        (Some((nodes, warnings)), _) => rigid_replay::Scene {
            nodes,
            warnings,
            extent: 0.5,
            ..Default::default()
        },
        (None, Some(_)) => robot_nodes(model, urdf_path(&args.model).as_deref()),
        (None, None) => Default::default(),
    };
    let mut rec = Recording::default();
    let mut data = Data::new(model);
    // with --ground the page draws the ground, marks the contacts that push and draws their
    // forces (the last step's impulse over dt), the weight's arrow half the robot's size
    let ground = scenario.collision.as_ref().and_then(|c| c.ground);
    let height = ground.map_or(0.0, |g| g.height);
    let markers = match (&args.html, ground) {
        (Some(_), Some(_)) => {
            let c = center_of_mass(model, &mut data, &q0).map_err(|e| e.to_string())?;
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
                .map(|(c, p)| (c.point, p / dt))
                .collect();
            scene.set_contacts(first, &pushing, height);
        }
    };
    if args.html.is_some() {
        mark(&mut scene, &sim);
        rec.record_model(&scene, model, &mut data, 0.0, &q0, true)?;
    }
    let stride = (steps as usize).div_ceil(PLOT_POINTS).max(1) as u64;
    let mut samples = Samples::new(model);
    let (e0, k0) = {
        let (k, u) = sim.energies().map_err(|e| e.to_string())?;
        (k + u, k)
    };
    let tau_row = |sim: &mut Simulator| -> Result<Vec<f64>, String> {
        Ok(sim.torques().map_err(|e| e.to_string())?.0.to_vec())
    };
    let mut worst = rigid::simulation::Violation::default();
    if args.plot.is_some() {
        let tau = tau_row(&mut sim)?;
        let c = contacts.then_some((0.0, 0.0));
        samples.push(0.0, sim.q(), sim.v(), &tau, e0, c);
    }
    let mut max_speed = (0.0f64, 0usize);
    let mut max_penetration = 0.0f64;
    // the contact solves: (steps with one, their sweeps, those that met the tolerance), and
    // the largest residuals
    let mut solves = (0usize, 0usize, 0usize);
    let mut residuals = ContactResiduals::default();
    let mut progress = super::Progress::new(steps)?;
    let mut failure = None;
    for k in 1..=steps {
        if let Err(e) = sim.step() {
            failure = Some(format!("step {k} (t = {:.6} s): {e}", sim.time()));
            break;
        }
        let t = sim.time();
        let stats = sim.contact_stats();
        max_penetration = max_penetration.max(stats.penetration);
        if stats.iterations > 0 {
            solves.0 += 1;
            solves.1 += stats.iterations;
            solves.2 += usize::from(stats.converged);
            residuals = residuals.max(stats.residuals);
        }
        for (i, x) in sim.v().iter().enumerate() {
            if x.abs() > max_speed.0 {
                max_speed = (x.abs(), i);
            }
        }
        if loops {
            let w = sim.violation().map_err(|e| e.to_string())?;
            worst.position = worst.position.max(w.position);
            worst.velocity = worst.velocity.max(w.velocity);
        }
        if let Some(f) = csv.as_mut() {
            write_row(f.writer(), &mut sim, spec, columns, loops, dt)?;
        }
        if args.plot.is_some() && (k.is_multiple_of(stride) || k == steps) {
            let tau = tau_row(&mut sim)?;
            let e = sim.energy().map_err(|e| e.to_string())?;
            let normal = sim.contact_stats().normal_impulse / dt;
            let c = contacts.then(|| (normal, sim.contact_dissipation()));
            samples.push(t, sim.q(), sim.v(), &tau, e, c);
        }
        if args.html.is_some() && (rec.due(t) || k == steps) {
            mark(&mut scene, &sim);
            rec.record_model(&scene, model, &mut data, t, sim.q(), k == steps)?;
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
            dt,
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
        "integrator: {}, dt = {dt} s, controller: {}",
        opts.integrator, args.controller
    );
    println!("joint limits: {limits}");
    println!(
        "joint damping and friction: {}",
        if passive {
            "on (the file's joint damping and friction)"
        } else {
            "off"
        }
    );
    if let Some(g) = ground {
        let n = g.normal;
        let plane = if n == Vec3::z() {
            format!("z = {} m", g.height)
        } else {
            format!("n·x = {} m, n = ({}, {}, {})", g.height, n.x, n.y, n.z)
        };
        println!(
            "ground: {plane}, friction {}, restitution {}",
            g.friction, g.restitution
        );
    }
    if let Some(cm) = &scenario.collision {
        let pairs = if cm.self_collision { "on" } else { "off" };
        let excluded = if cm.excluded.is_empty() {
            String::new()
        } else {
            format!(" ({} pairs excluded)", cm.excluded.len())
        };
        println!(
            "collision: {} geometries, between bodies {pairs}{excluded}",
            cm.geometries.len()
        );
    }
    if contacts {
        let s = sim.contact_stats();
        println!(
            "contacts at the end: {} active, normal force {:.6} N; deepest penetration {max_penetration:.3e} m",
            s.active,
            s.normal_impulse / dt
        );
        if solves.0 > 0 {
            let (name, unit) = (
                args.contact_solver.name(),
                args.contact_solver.iterations_name(),
            );
            println!(
                "contact solves ({name}): {} steps, {:.1} {unit} on average, {:.1} % converged",
                solves.0,
                solves.1 as f64 / solves.0 as f64,
                100.0 * solves.2 as f64 / solves.0 as f64
            );
            let r = residuals;
            println!(
                "contact residuals, largest of a step: Signorini {:.1e} J, Coulomb {:.1e} N·s, \
                 dissipation {:.1e} J, velocity error {:.1e} m/s",
                r.signorini, r.coulomb, r.dissipation, r.velocity_error
            );
        }
    }
    if loops {
        println!(
            "constraints: {} (closed loops, welds), largest violation {:.2e} (position), {:.2e} (velocity)",
            scenario.constraints.len(),
            worst.position,
            worst.velocity
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
