//! `rigid.mobile`'s runs and chains: the capstone's reference and whole run, a wheeled robot on
//! the ground (`drive`), and the product of exponentials of screw axes. The library does the work
//! (`rigid::mobile`, `rigid::kinematics::poe`); this file converts arrays in and out.

#![allow(non_snake_case)] // the notes' names: Blist, Kp, M

use crate::convert::{array1, finite_vector, pose, rows_array, value_error};
use crate::mobile::{dmatrix, err, gain, homogeneous, screw_axes};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rigid::kinematics::poe;
use rigid::mobile as mb;

fn reference_rows(points: &[mb::ReferencePoint]) -> Vec<f64> {
    points.iter().flat_map(mb::ReferencePoint::row).collect()
}

fn task(
    cube_initial: Option<&Bound<'_, PyAny>>,
    cube_final: Option<&Bound<'_, PyAny>>,
    grasp: Option<&Bound<'_, PyAny>>,
    standoff: Option<&Bound<'_, PyAny>>,
    func: &str,
) -> PyResult<mb::PickAndPlace> {
    let mut t = mb::PickAndPlace::course();
    for (x, slot, name) in [
        (cube_initial, &mut t.cube_initial, "cube_initial"),
        (cube_final, &mut t.cube_final, "cube_final"),
        (grasp, &mut t.grasp, "grasp"),
        (standoff, &mut t.standoff, "standoff"),
    ] {
        if let Some(x) = x {
            *slot = pose(x, func, name)?;
        }
    }
    Ok(t)
}

/// The capstone's reference (TrajectoryGenerator): rows `r11, r12, r13, r21, ..., r33, px, py,
/// pz, gripper` (N × 13, the course's CSV), from `start` through the eight segments of the
/// pick-and-place, every `dt`. Cube poses and the grasp default to the course's.
#[pyfunction]
#[pyo3(signature = (start, cube_initial = None, cube_final = None, grasp = None, standoff = None, dt = 0.01))]
pub fn pick_and_place<'py>(
    py: Python<'py>,
    start: &Bound<'py, PyAny>,
    cube_initial: Option<&Bound<'py, PyAny>>,
    cube_final: Option<&Bound<'py, PyAny>>,
    grasp: Option<&Bound<'py, PyAny>>,
    standoff: Option<&Bound<'py, PyAny>>,
    dt: f64,
) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    const F: &str = "pick_and_place";
    let t = task(cube_initial, cube_final, grasp, standoff, F)?;
    let r = t.reference(&pose(start, F, "start")?, dt).map_err(err(F))?;
    rows_array(py, reference_rows(&r), r.len(), 13)
}

/// A whole capstone run of the youBot (the course's defaults unless given): returns a dict with
/// `states` (N × 13: phi, x, y, 5 joints, 4 wheels, gripper, the course's scene CSV), `errors`
/// (N-1 × 6: X_err each step), `reference` (N × 13, as `pick_and_place`) and `dt`.
#[pyfunction]
#[pyo3(signature = (Kp = None, Ki = None, chassis = None, arm = None, cube_initial = None, cube_final = None, limits = None, dt = 0.01, max_speed = 15.0))]
#[allow(clippy::too_many_arguments)]
pub fn capstone<'py>(
    py: Python<'py>,
    Kp: Option<&Bound<'py, PyAny>>,
    Ki: Option<&Bound<'py, PyAny>>,
    chassis: Option<&Bound<'py, PyAny>>,
    arm: Option<&Bound<'py, PyAny>>,
    cube_initial: Option<&Bound<'py, PyAny>>,
    cube_final: Option<&Bound<'py, PyAny>>,
    limits: Option<Vec<(f64, f64)>>,
    dt: f64,
    max_speed: f64,
) -> PyResult<Bound<'py, PyDict>> {
    const F: &str = "capstone";
    let mut c = mb::Capstone::youbot();
    if let Some(k) = Kp {
        c.feedback.Kp = gain(k, F, "Kp")?;
    }
    if let Some(k) = Ki {
        c.feedback.Ki = gain(k, F, "Ki")?;
    }
    if let Some(q) = chassis {
        c.start.chassis = crate::mobile::chassis(q, F, "chassis")?;
    }
    if let Some(a) = arm {
        c.start.arm = finite_vector(a, F, "arm", "5", 5)?;
    }
    c.task = task(cube_initial, cube_final, None, None, F)?;
    c.feedback.limits = limits.unwrap_or_default();
    c.dt = dt;
    c.max_speed = max_speed;
    let run = c.run().map_err(err(F))?;
    let rows: Vec<f64> = (0..run.states.len()).flat_map(|k| run.row(k)).collect();
    let errors: Vec<f64> = run
        .errors
        .iter()
        .flat_map(|e| e.to_vector().iter().copied().collect::<Vec<_>>())
        .collect();
    let d = PyDict::new(py);
    d.set_item("states", rows_array(py, rows, run.states.len(), 13)?)?;
    d.set_item("errors", rows_array(py, errors, run.errors.len(), 6)?)?;
    d.set_item(
        "reference",
        rows_array(py, reference_rows(&run.reference), run.reference.len(), 13)?,
    )?;
    d.set_item("dt", run.dt)?;
    Ok(d)
}

/// A robot file (URDF or MJCF, loaded with a free-flyer root, set down on the ground z = 0) with
/// its wheels under velocity control, `tau = gain (u_d - u)` (`rigid::mobile::drive`, as `rigid
/// mobile drive`): returns a dict of `t`, `x`, `y`, `yaw`, `v` (speed along the heading), `omega`
/// (yaw rate), each (N,), `wheel_speeds` (N × m) and `q` (N × nq), at t = 0 and after each step.
/// `friction` is the ground's; `wheel_friction` the wheels' shapes' (a shape's friction with the
/// ground is the larger: `friction=0, wheel_friction=1` lets fixed casters slide); `hold` holds
/// the other joints with the stance controller.
#[pyfunction]
#[pyo3(signature = (path, wheels, speeds, time = 3.0, dt = 1e-3, gain = 20.0, friction = 1.0, wheel_friction = None, hold = false))]
#[allow(clippy::too_many_arguments)]
pub fn drive<'py>(
    py: Python<'py>,
    path: std::path::PathBuf,
    wheels: Vec<String>,
    speeds: Vec<f64>,
    time: f64,
    dt: f64,
    gain: f64,
    friction: f64,
    wheel_friction: Option<f64>,
    hold: bool,
) -> PyResult<Bound<'py, PyDict>> {
    const F: &str = "drive";
    let model = if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"))
    {
        rigid::io::mjcf::load_mjcf(&path)
            .map_err(|e| value_error(F, e))?
            .model
    } else {
        rigid::io::urdf::load_urdf(&path, true).map_err(|e| value_error(F, e))?
    };
    let world_options = rigid::io::collision::WorldOptions {
        ground: Some(0.0),
        friction: Some(friction),
        ..Default::default()
    };
    let world = rigid::io::collision::file_world(&path, &model, &world_options)
        .map_err(|e| value_error(F, e))?;
    let cm = world
        .collision
        .ok_or_else(|| value_error(F, "the robot file has no collision geometry"))?;
    let options = mb::DriveOptions {
        wheels,
        speeds,
        gain,
        wheel_friction,
        hold,
        dt,
    };
    let record = mb::drive(&model, cm, &options, time, |_, _| Ok(())).map_err(err(F))?;
    let n = record.motion.len();
    let d = PyDict::new(py);
    let t: Vec<f64> = (0..n).map(|k| k as f64 * dt).collect();
    d.set_item("t", array1(py, &t))?;
    for (i, name) in ["x", "y", "yaw", "v", "omega"].iter().enumerate() {
        let col: Vec<f64> = record.motion.iter().map(|m| m[i]).collect();
        d.set_item(*name, array1(py, &col))?;
    }
    let m = options.wheels.len();
    d.set_item(
        "wheel_speeds",
        rows_array(py, record.wheel_speeds.concat(), n, m)?,
    )?;
    d.set_item("q", rows_array(py, record.q.concat(), n, model.nq())?)?;
    Ok(d)
}

/// `FKinBody(M, Blist, theta)`: `M e^{[B_1]θ_1} ⋯ e^{[B_n]θ_n}` (4 × 4).
#[pyfunction]
pub fn fkin_body<'py>(
    py: Python<'py>,
    M: &Bound<'py, PyAny>,
    Blist: &Bound<'py, PyAny>,
    theta: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    const F: &str = "fkin_body";
    let b = screw_axes(Blist, F, "Blist")?;
    let theta = finite_vector(theta, F, "theta", "n", b.len())?;
    let t = poe::fkin_body(&pose(M, F, "M")?, &b, &theta).map_err(|e| value_error(F, e))?;
    Ok(homogeneous(py, &t))
}

/// `FKinSpace(M, Slist, theta)`: `e^{[S_1]θ_1} ⋯ e^{[S_n]θ_n} M` (4 × 4).
#[pyfunction]
pub fn fkin_space<'py>(
    py: Python<'py>,
    M: &Bound<'py, PyAny>,
    Slist: &Bound<'py, PyAny>,
    theta: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    const F: &str = "fkin_space";
    let s = screw_axes(Slist, F, "Slist")?;
    let theta = finite_vector(theta, F, "theta", "n", s.len())?;
    let t = poe::fkin_space(&pose(M, F, "M")?, &s, &theta).map_err(|e| value_error(F, e))?;
    Ok(homogeneous(py, &t))
}

/// `JacobianBody(Blist, theta)` (6 × n).
#[pyfunction]
pub fn jacobian_body<'py>(
    py: Python<'py>,
    Blist: &Bound<'py, PyAny>,
    theta: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    const F: &str = "jacobian_body";
    let b = screw_axes(Blist, F, "Blist")?;
    let theta = finite_vector(theta, F, "theta", "n", b.len())?;
    Ok(dmatrix(
        py,
        &poe::jacobian_body(&b, &theta).map_err(|e| value_error(F, e))?,
    ))
}

/// `JacobianSpace(Slist, theta)` (6 × n).
#[pyfunction]
pub fn jacobian_space<'py>(
    py: Python<'py>,
    Slist: &Bound<'py, PyAny>,
    theta: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    const F: &str = "jacobian_space";
    let s = screw_axes(Slist, F, "Slist")?;
    let theta = finite_vector(theta, F, "theta", "n", s.len())?;
    Ok(dmatrix(
        py,
        &poe::jacobian_space(&s, &theta).map_err(|e| value_error(F, e))?,
    ))
}

/// Adds the runs and chains to the native submodule `_mobile`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(pick_and_place, m)?)?;
    m.add_function(wrap_pyfunction!(capstone, m)?)?;
    m.add_function(wrap_pyfunction!(drive, m)?)?;
    m.add_function(wrap_pyfunction!(fkin_body, m)?)?;
    m.add_function(wrap_pyfunction!(fkin_space, m)?)?;
    m.add_function(wrap_pyfunction!(jacobian_body, m)?)?;
    m.add_function(wrap_pyfunction!(jacobian_space, m)?)?;
    Ok(())
}
