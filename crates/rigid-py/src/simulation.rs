//! Robot simulation from Python: `simulate` (rigid's `simulation`, the same options
//! and built-in controllers as `rigid simulate`, or a Python control law `u(t, q, v)`) and
//! `replay_html` (the 3D replay page of `rigid simulate --html`).

use crate::convert::{io_error, matrix, rows_array, value_error, vector};
use crate::model::{Model, ModelCore};
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rigid::io::collision::{exclude_srdf_pairs, file_world, ground_model, FileWorld, WorldOptions};
use rigid::multibody::constraints::ProximalSettings;
use rigid::multibody::{Data, Model as RigidModel, MultibodyError};
use rigid::simulation::contact::ContactStats;
use rigid::simulation::{
    step_count, ConstraintOptions, Control, Integrator, JointLimits, Scenario, SimulationError,
    SimulationOptions, Simulator,
};
use std::path::PathBuf;

/// A configuration argument (model layout) in rigid's layout.
fn q_arg(core: &ModelCore, func: &str, name: &str, x: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    let v = vector(x, func, name, "nq", core.nq())?;
    let mut out = Vec::new();
    core.q_into(&v, &mut out, func, name)?;
    Ok(out)
}

/// A velocity-space argument (model layout) in rigid's layout.
fn v_arg(core: &ModelCore, func: &str, name: &str, x: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    let v = vector(x, func, name, "nv", core.nv())?;
    let mut out = Vec::new();
    core.v_into(&v, &mut out, func, name)?;
    Ok(out)
}

/// The control law `τ = u(t, q, v)` of a Python callable, in the model's layout. A Python
/// exception stops the simulation and is raised by `simulate`.
struct PyControl<'py> {
    f: Bound<'py, PyAny>,
    core: &'py ModelCore,
    error: Option<PyErr>,
}

impl Control for PyControl<'_> {
    fn torque(
        &mut self,
        _model: &RigidModel,
        t: f64,
        q: &[f64],
        v: &[f64],
        tau: &mut [f64],
    ) -> Result<(), MultibodyError> {
        let py = self.f.py();
        let stop = MultibodyError::NonFinite {
            what: "tau",
            index: 0,
        };
        let result = self
            .f
            .call1((t, self.core.q_out(py, q), self.core.v_out(py, v)))
            .and_then(|r| {
                let x = vector(&r, "simulate", "control(t, q, v)", "nv", self.core.nv())?;
                let mut out = Vec::new();
                self.core
                    .v_into(&x, &mut out, "simulate", "control(t, q, v)")?;
                Ok(out)
            });
        match result {
            Ok(out) => {
                tau.copy_from_slice(&out);
                Ok(())
            }
            Err(e) => {
                self.error.get_or_insert(e);
                Err(stop)
            }
        }
    }
}

/// The recorded run: times and, per row, `q`, `v`, `τ` (the control's), the energy, the
/// contacts and the constraint violation.
#[derive(Default)]
pub(crate) struct Record {
    pub t: Vec<f64>,
    pub q: Vec<f64>,
    pub v: Vec<f64>,
    pub tau: Vec<f64>,
    pub energy: Vec<f64>,
    pub contacts: Vec<f64>,
    pub normal_force: Vec<f64>,
    pub violation_position: Vec<f64>,
    pub violation_velocity: Vec<f64>,
    /// Per row, the contact solve's iterations, whether it converged (1 or 0) and its
    /// residuals (Signorini, Coulomb, dissipation, velocity error).
    pub solves: Vec<[f64; 6]>,
}

pub(crate) fn run<C: Control>(
    sim: &mut Simulator<C>,
    steps: u64,
    every: u64,
    rec: &mut Record,
) -> Result<(), SimulationError> {
    let push = |sim: &mut Simulator<C>, rec: &mut Record| -> Result<(), SimulationError> {
        rec.t.push(sim.time());
        rec.q.extend_from_slice(sim.q());
        rec.v.extend_from_slice(sim.v());
        let tau = sim.torques()?.0.to_vec();
        rec.tau.extend_from_slice(&tau);
        rec.energy.push(sim.energy()?);
        let stats = sim.contact_stats();
        rec.contacts.push(stats.active as f64);
        rec.normal_force
            .push(stats.normal_impulse / sim.options().dt);
        rec.solves.push(stats.solve_row());
        let w = sim.violation()?;
        rec.violation_position.push(w.position);
        rec.violation_velocity.push(w.velocity);
        Ok(())
    };
    push(sim, rec)?;
    for k in 1..=steps {
        sim.step()?;
        if k % every == 0 || k == steps {
            push(sim, rec)?;
        }
    }
    Ok(())
}

/// The world of `core`'s model: its file's ([`file_world`]), or without a file the ground of
/// `options` alone; its warnings issued, its materials checked.
pub(crate) fn world(
    py: Python<'_>,
    func: &str,
    core: &ModelCore,
    options: &WorldOptions,
) -> PyResult<FileWorld> {
    let world = match &core.source {
        Some(path) => file_world(path, &core.model, options),
        None => FileWorld::without_file(options, Vec::new()),
    }
    .map_err(|e| value_error(func, e))?;
    warn_all(py, func, &world.warnings)?;
    world
        .check_materials(options)
        .map_err(|e| value_error(func, e))?;
    Ok(world)
}

/// Warns in Python with each of `warnings`, prefixed by `func`.
pub(crate) fn warn_all(py: Python<'_>, func: &str, warnings: &[String]) -> PyResult<()> {
    let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
    for w in warnings {
        let text =
            std::ffi::CString::new(format!("{func}: {w}").replace('\0', " ")).unwrap_or_default();
        PyErr::warn(py, category.as_any(), &text, 2)?;
    }
    Ok(())
}

/// Simulates `model` from `(q0, v0)` for `duration` seconds with a fixed step `dt` (the options,
/// the world and the built-in controllers of `rigid simulate`, the library's `Scenario`;
/// `control`, a Python function `u(t, q, v) -> τ`, replaces `controller`). Returns a dict of
/// numpy arrays, one row every `every` steps and the last, in the model's layout: `t` (N),
/// `q` (N × nq), `v` (N × nv), `tau` (N × nv, the control law's torques), `energy` (N, kinetic
/// + potential, J); when anything can touch, `contacts` (N, active contacts) and
/// `normal_force` (N, their normal force sum, N) and the contact solve of the step (`contact_solver`
/// `"pgs"`, by default with its active-set `polish`, or `"admm"`): `iterations`, `converged` (1 or 0) and its ContactBench residuals
/// `signorini` (J), `coulomb` (N·s), `dissipation` (J), `velocity_error` (m/s); with
/// constraints, `violation_position` and
/// `violation_velocity` (N, the largest constraint error and its rate). The world: an MJCF
/// file's own floor, geom pairs and `<equality>` elements; `ground` (a height, m) adds the
/// plane `z = ground` under a robot without one (its URDF `<collision>` or MJCF geoms, Coulomb
/// `friction`, default the file's or 0.8, and `restitution`, default 0); `self_collision`
/// makes a URDF's bodies collide with each other (`srdf`, a path: less the pairs of links its
/// `<disable_collisions>` name); `constraints` (a list of
/// `rigid.ConstraintModel`) replaces the file's. Anything that can touch is stepped by the
/// time-stepping `semi-implicit` scheme (`rk4` replaced), a floating robot without `q0`
/// starts set down on the ground at `target` (or its home), and `controller="pd"` holds the
/// stance on its feet.
#[pyfunction]
#[pyo3(signature = (
    model, q0 = None, v0 = None, duration = 1.0, dt = None, integrator = "rk4",
    controller = "none", target = None, move_time = None, profile = "quintic",
    limits = "spring", joint_dynamics = true, control = None, every = 1, ground = None,
    friction = None, restitution = None, self_collision = false, constraints = None,
    srdf = None, contact_solver = "pgs", polish = true
))]
#[allow(clippy::too_many_arguments)]
pub fn simulate<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    q0: Option<&Bound<'py, PyAny>>,
    v0: Option<&Bound<'py, PyAny>>,
    duration: f64,
    dt: Option<f64>,
    integrator: &str,
    controller: &str,
    target: Option<&Bound<'py, PyAny>>,
    move_time: Option<f64>,
    profile: &str,
    limits: &str,
    joint_dynamics: bool,
    control: Option<&Bound<'py, PyAny>>,
    every: u64,
    ground: Option<f64>,
    friction: Option<f64>,
    restitution: Option<f64>,
    self_collision: bool,
    constraints: Option<Vec<PyRef<'py, crate::constraints::ConstraintModel>>>,
    srdf: Option<PathBuf>,
    contact_solver: &str,
    polish: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let func = "simulate";
    let core: &ModelCore = &model.inner;
    let m = &core.model;
    let err = |e: SimulationError| value_error(func, e);
    if every == 0 {
        return Err(PyValueError::new_err("simulate: every must be at least 1"));
    }
    let options = WorldOptions {
        ground,
        friction,
        restitution,
        self_collision,
    };
    let mut world = world(py, func, core, &options)?;
    if let Some(path) = &srdf {
        let Some(cm) = world.collision.as_mut().filter(|_| self_collision) else {
            return Err(value_error(func, "srdf applies with self_collision=True"));
        };
        exclude_srdf_pairs(cm, path).map_err(|e| value_error(func, e))?;
    }
    let dt = world.time_step(dt);
    let steps = step_count(duration, dt).map_err(err)?;
    let mut s = Scenario::new(m.clone());
    s.home = world.home.clone();
    s.q0 = q0.map(|x| q_arg(core, func, "q0", x)).transpose()?;
    s.v0 = v0.map(|x| v_arg(core, func, "v0", x)).transpose()?;
    s.target = target.map(|x| q_arg(core, func, "target", x)).transpose()?;
    s.controller = controller.parse().map_err(err)?;
    s.profile = profile.parse().map_err(err)?;
    s.move_time = move_time.unwrap_or(0.5 * duration);
    s.options = SimulationOptions {
        dt,
        integrator: integrator.parse::<Integrator>().map_err(err)?,
        limits: limits.parse::<JointLimits>().map_err(err)?,
        joint_dynamics,
        ..SimulationOptions::default()
    };
    s.collision = world.collision;
    s.contact.solver = contact_solver.parse().map_err(|e| value_error(func, e))?;
    s.contact.polish = polish;
    s.constraint_options = ConstraintOptions {
        settings: world.constraint_settings,
        ..ConstraintOptions::default()
    };
    s.constraints = match &constraints {
        Some(list) => {
            s.constraint_options.settings = ProximalSettings::redundant();
            crate::constraints::rigid_constraints(func, core, list)?
        }
        None => world.constraints,
    };
    let mut rec = Record::default();
    match control {
        Some(f) => {
            if !f.is_callable() {
                return Err(PyValueError::new_err(
                    "simulate: control must be a function u(t, q, v) -> tau",
                ));
            }
            let law = PyControl {
                f: f.clone(),
                core,
                error: None,
            };
            let mut sim = s.build_with(law).map_err(err)?;
            let result = run(&mut sim, steps, every, &mut rec);
            if let Some(e) = sim.control_mut().error.take() {
                return Err(e);
            }
            result.map_err(err)?;
        }
        None => {
            let mut sim = s.build().map_err(err)?;
            py.detach(|| run(&mut sim, steps, every, &mut rec))
                .map_err(err)?;
        }
    }
    trajectory(py, core, rec, s.touches(), !s.constraints.is_empty())
}

/// The dict of a recorded run (see [`simulate`]).
fn trajectory<'py>(
    py: Python<'py>,
    core: &ModelCore,
    rec: Record,
    contacts: bool,
    loops: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let n = rec.t.len();
    let (nq, nv) = (core.model.nq(), core.model.nv());
    let q_rows: Vec<f64> = rec
        .q
        .chunks_exact(nq.max(1))
        .take(n)
        .flat_map(|q| core.q_to_layout(q))
        .collect();
    let v_rows = |x: &[f64]| -> Vec<f64> {
        x.chunks_exact(nv.max(1))
            .take(n)
            .flat_map(|v| core.v_to_layout(v))
            .collect()
    };
    let out = PyDict::new(py);
    out.set_item("t", PyArray1::from_vec(py, rec.t))?;
    out.set_item("q", rows_array(py, q_rows, n, core.nq())?)?;
    out.set_item("v", rows_array(py, v_rows(&rec.v), n, nv)?)?;
    out.set_item("tau", rows_array(py, v_rows(&rec.tau), n, nv)?)?;
    out.set_item("energy", PyArray1::from_vec(py, rec.energy))?;
    if contacts {
        out.set_item("contacts", PyArray1::from_vec(py, rec.contacts))?;
        out.set_item("normal_force", PyArray1::from_vec(py, rec.normal_force))?;
        for (i, name) in ContactStats::SOLVE_COLUMNS.iter().enumerate() {
            let x: Vec<f64> = rec.solves.iter().map(|s| s[i]).collect();
            out.set_item(*name, PyArray1::from_vec(py, x))?;
        }
    }
    if loops {
        let (p, v) = (rec.violation_position, rec.violation_velocity);
        out.set_item("violation_position", PyArray1::from_vec(py, p))?;
        out.set_item("violation_velocity", PyArray1::from_vec(py, v))?;
    }
    Ok(out)
}

/// Writes the 3D replay of a trajectory of `model` to `path`: one self-contained HTML file
/// (WebGL; the URDF's visual geometry, a stick figure without it) that opens offline. `traj` is
/// a dict (the result of `simulate`) or an object with `t` (N) and `q` (N × nq, the model's
/// layout). Frames are taken at 60 per second of `t`, and the last.
#[pyfunction]
#[pyo3(signature = (model, traj, path, title = None))]
pub fn replay_html(
    model: PyRef<'_, Model>,
    traj: &Bound<'_, PyAny>,
    path: PathBuf,
    title: Option<&str>,
) -> PyResult<()> {
    let func = "replay_html";
    let core: &ModelCore = &model.inner;
    let get = |key: &str| {
        traj.get_item(key)
            .or_else(|_| traj.getattr(key))
            .map_err(|_| PyValueError::new_err(format!("replay_html: traj has no \"{key}\"")))
    };
    let times = get("t")?;
    let n = times.len()?;
    let t = vector(&times, func, "traj[\"t\"]", "N", n)?
        .as_slice()
        .to_vec();
    let qs = matrix(&get("q")?, func, "traj[\"q\"]", "nq", core.nq())?;
    if qs.rows != t.len() {
        return Err(value_error(
            func,
            format!("traj has {} times but {} rows of q", t.len(), qs.rows),
        ));
    }
    let m = &core.model;
    let mut scene = rigid_replay::robot_nodes(m, core.source.as_deref());
    scene.title = title.map_or_else(|| m.name().to_string(), str::to_string);
    let mut data = Data::new(m);
    let mut rec = rigid_replay::Recording::default();
    let mut q = Vec::new();
    for (k, (tk, row)) in t
        .iter()
        .zip(qs.as_slice().chunks_exact(core.nq().max(1)))
        .enumerate()
    {
        let x = crate::convert::Vector::Owned(row.to_vec());
        core.q_into(&x, &mut q, func, &format!("traj[\"q\"][{k}]"))?;
        rec.record_model(&scene, m, &mut data, *tk, &q, k + 1 == t.len())
            .map_err(|e| value_error(func, format!("row {k}: {e}")))?;
    }
    let html = scene.html(&rec);
    let tmp = path.with_extension(format!("tmp{}", std::process::id()));
    std::fs::write(&tmp, html)
        .and_then(|()| std::fs::rename(&tmp, &path))
        .map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            io_error(
                &e,
                format!("replay_html: cannot write {}: {e}", path.display()),
            )
        })
}

/// `simulate_body(spec, ground=...)`: the body of the spec file at `path` as one free body at
/// its CoM ([`rigid::io::collision::spec_body`]) colliding through its parts' shapes with the
/// ground `z = height` ([`rigid::io::collision::ground_model`]), stepped by the time-stepping
/// integrator with no control, as `rigid simulate SPEC.toml --ground`. `q0` is the pose
/// `(x, y, z, qx, qy, qz, qw)` of the CoM frame (`None`: set down on the ground, spec axes
/// upright), `twist` its body twist `(ω, v)`, `gravity` replaces the default `-9.81 ẑ` m/s².
/// Returns the rows of `simulate_body` plus `contacts` and `normal_force`.
pub(crate) struct BodyOnGround<'a> {
    pub path: &'a std::path::Path,
    pub height: f64,
    pub friction: Option<f64>,
    pub restitution: Option<f64>,
    pub q0: Option<Vec<f64>>,
    pub twist: [f64; 6],
    pub gravity: Option<rigid::spatial::Vec3>,
    pub duration: f64,
    pub dt: f64,
    pub every: u64,
}

impl BodyOnGround<'_> {
    /// Runs the simulation (see the type) and returns the trajectory's dict.
    pub(crate) fn run<'py>(&self, py: Python<'py>, func: &str) -> PyResult<Bound<'py, PyDict>> {
        let err = |e: SimulationError| value_error(func, e);
        let steps = step_count(self.duration, self.dt).map_err(err)?;
        let (mut model, geometries, warnings) =
            rigid::io::collision::spec_body(self.path).map_err(|e| value_error(func, e))?;
        if let Some(g) = self.gravity {
            model = model.with_gravity(g);
        }
        warn_all(py, func, &warnings)?;
        let cm = ground_model(
            Some(self.height),
            self.friction,
            self.restitution,
            geometries,
        )
        .map_err(|e| value_error(func, e))?;
        let mut s = Scenario::new(model);
        s.q0 = self.q0.clone();
        s.v0 = Some(self.twist.to_vec());
        s.options.dt = self.dt;
        s.collision = Some(cm);
        let mut sim = s.build().map_err(err)?;
        let mut rec = Record::default();
        py.detach(|| run(&mut sim, steps, self.every, &mut rec))
            .map_err(err)?;
        let n = rec.t.len();
        let cols = |x: &[f64], stride: usize, r: std::ops::Range<usize>| -> Vec<f64> {
            x.chunks_exact(stride)
                .flat_map(|row| row[r.clone()].to_vec())
                .collect()
        };
        let d = PyDict::new(py);
        d.set_item("t", PyArray1::from_vec(py, rec.t))?;
        d.set_item("position", rows_array(py, cols(&rec.q, 7, 0..3), n, 3)?)?;
        d.set_item("quaternion", rows_array(py, cols(&rec.q, 7, 3..7), n, 4)?)?;
        d.set_item("omega", rows_array(py, cols(&rec.v, 6, 0..3), n, 3)?)?;
        d.set_item("velocity", rows_array(py, cols(&rec.v, 6, 3..6), n, 3)?)?;
        d.set_item("energy", PyArray1::from_vec(py, rec.energy))?;
        d.set_item("contacts", PyArray1::from_vec(py, rec.contacts))?;
        d.set_item("normal_force", PyArray1::from_vec(py, rec.normal_force))?;
        Ok(d)
    }
}
