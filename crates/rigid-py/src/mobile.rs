//! `rigid.mobile`: the Python side of `rigid::mobile` (wheeled bases, odometry, mobile
//! manipulators, the capstone) and `rigid::kinematics::poe`, which do the work; this file converts
//! arrays in and out. Screw-axis lists are 6 × n arrays whose columns are the axes, as in the
//! Modern Robotics code library (`Blist`); poses are 4 × 4 homogeneous matrices.

#![allow(non_snake_case)] // the notes' names: H, F, T_b0, M_0e, Blist, X, Kp

use crate::convert::{array1, array2, matrix, value_error, vector};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rigid::kinematics::poe;
use rigid::mobile::{self as mb, Kind, MobileError};
use rigid::spatial::{Mat3, Mat6, Transform, Twist, Vec3};

fn err(func: &str) -> impl Fn(MobileError) -> PyErr + '_ {
    move |e| value_error(func, e)
}

/// A 4 × 4 homogeneous matrix (any array-like) as a `Transform`; its rotation checked.
fn pose(x: &Bound<'_, PyAny>, func: &str, name: &str) -> PyResult<Transform> {
    let m = matrix(x, func, name, "4", 4).map_err(|e| {
        value_error(
            func,
            format!("{name} must be a 4 x 4 homogeneous matrix ({e})"),
        )
    })?;
    let s = m.as_slice();
    if m.rows != 4 || s[12..15].iter().any(|&v| v != 0.0) || s[15] != 1.0 {
        return Err(value_error(
            func,
            format!("{name} must be a 4 x 4 homogeneous matrix (last row 0, 0, 0, 1)"),
        ));
    }
    let r = Mat3::new(s[0], s[1], s[2], s[4], s[5], s[6], s[8], s[9], s[10]);
    rigid::spatial::so3::check(&r, 1e-6).map_err(|e| value_error(func, format!("{name}: {e}")))?;
    Ok(Transform::new(r, Vec3::new(s[3], s[7], s[11])))
}

fn homogeneous<'py>(py: Python<'py>, t: &Transform) -> Bound<'py, numpy::PyArray2<f64>> {
    let h = t.to_homogeneous();
    array2(py, 4, 4, |r, c| h[(r, c)])
}

fn dmatrix<'py>(py: Python<'py>, m: &nalgebra::DMatrix<f64>) -> Bound<'py, numpy::PyArray2<f64>> {
    array2(py, m.nrows(), m.ncols(), |r, c| m[(r, c)])
}

/// A 6 × n screw-axis list (columns) as twists.
fn screw_axes(x: &Bound<'_, PyAny>, func: &str, name: &str) -> PyResult<Vec<Twist>> {
    let np = x.py().import("numpy")?;
    let t = np.call_method1("asarray", (x,))?.getattr("T")?;
    let m = matrix(
        &t,
        func,
        &format!("{name} (transposed: its columns are the axes)"),
        "6",
        6,
    )?;
    Ok(m.as_slice().chunks(6).map(Twist::from_slice).collect())
}

/// A gain: a number (times the 6 × 6 identity), 6 numbers (the diagonal) or a 6 × 6 matrix.
fn gain(x: &Bound<'_, PyAny>, func: &str, name: &str) -> PyResult<Mat6> {
    if let Ok(k) = x.extract::<f64>() {
        return Ok(Mat6::identity() * k);
    }
    if let Ok(d) = vector(x, func, name, "6", 6) {
        return Ok(Mat6::from_diagonal(&nalgebra::Vector6::from_column_slice(
            d.as_slice(),
        )));
    }
    let m = matrix(x, func, name, "6", 6)?;
    if m.rows != 6 {
        return Err(value_error(
            func,
            format!("{name} must be a number, 6 numbers or 6 x 6"),
        ));
    }
    Ok(Mat6::from_row_slice(m.as_slice()))
}

fn chassis(x: &Bound<'_, PyAny>, func: &str, name: &str) -> PyResult<[f64; 3]> {
    let v = vector(x, func, name, "3 (phi, x, y)", 3)?;
    let s = v.as_slice();
    Ok([s[0], s[1], s[2]])
}

/// A wheeled base (Lynch & Park ch. 13): `Base.mecanum(r, l, w)`, `Base.omni3(r, d)`,
/// `Base.diff_drive(r, track)`, `Base.car(r, track, wheelbase)`. Chassis configurations are
/// `q = (phi, x, y)`, planar body twists `(omega_z, v_x, v_y)`.
#[pyclass(module = "rigid.mobile", name = "Base", frozen)]
pub struct Base(pub mb::Base);

#[pymethods]
impl Base {
    /// Four mecanum wheels at (±l, ±w), radius r; front-left, front-right, rear-right, rear-left
    /// (eq. 13.10).
    #[staticmethod]
    fn mecanum(r: f64, l: f64, w: f64) -> PyResult<Self> {
        mb::Base::mecanum(r, l, w)
            .map(Self)
            .map_err(err("Base.mecanum"))
    }
    /// Three omniwheels at distance d, 120° apart (eq. 13.9).
    #[staticmethod]
    fn omni3(r: f64, d: f64) -> PyResult<Self> {
        mb::Base::omni3(r, d).map(Self).map_err(err("Base.omni3"))
    }
    /// A differential drive: left and right wheels `track` apart, radius r.
    #[staticmethod]
    fn diff_drive(r: f64, track: f64) -> PyResult<Self> {
        mb::Base::diff_drive(r, track)
            .map(Self)
            .map_err(err("Base.diff_drive"))
    }
    /// A car: the rear axle drives (as a differential drive), the front axle `wheelbase` ahead steers.
    #[staticmethod]
    fn car(r: f64, track: f64, wheelbase: f64) -> PyResult<Self> {
        mb::Base::car(r, track, wheelbase)
            .map(Self)
            .map_err(err("Base.car"))
    }
    /// `mecanum`, `omni3`, `diff-drive` or `car`.
    #[getter]
    fn name(&self) -> &'static str {
        self.0.name()
    }
    /// `omnidirectional` or `nonholonomic`.
    #[getter]
    fn kind(&self) -> &'static str {
        match self.0.kind() {
            Kind::Omnidirectional => "omnidirectional",
            Kind::DiffDrive { .. } | Kind::Car { .. } => "nonholonomic",
        }
    }
    /// The number of wheels m.
    #[getter]
    fn n_wheels(&self) -> usize {
        self.0.wheels().len()
    }
    /// H(phi) (m × 3): wheel speeds `u = H(phi) q̇` (eq. 13.5).
    #[pyo3(signature = (phi = 0.0))]
    fn H<'py>(&self, py: Python<'py>, phi: f64) -> Bound<'py, numpy::PyArray2<f64>> {
        dmatrix(py, &self.0.H(phi))
    }
    /// F = H(0)† (3 × m): the planar body twist from wheel speeds.
    #[getter]
    fn F<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray2<f64>> {
        dmatrix(py, self.0.F())
    }
    /// F6 = [0; 0; F; 0] (6 × m).
    #[getter]
    fn F6<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray2<f64>> {
        dmatrix(py, &self.0.F6())
    }
    /// `V_b = F u` (3,).
    fn body_twist<'py>(
        &self,
        py: Python<'py>,
        u: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        let u = vector(
            u,
            "Base.body_twist",
            "u",
            "the number of wheels",
            self.0.wheels().len(),
        )?;
        let v = self
            .0
            .body_twist(u.as_slice())
            .map_err(err("Base.body_twist"))?;
        Ok(array1(py, &v))
    }
    /// Odometry (§13.4): the chassis configuration after the wheels turned by `dtheta`.
    fn odometry<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        dtheta: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        const F: &str = "Base.odometry";
        let q = chassis(q, F, "q")?;
        let d = vector(
            dtheta,
            F,
            "dtheta",
            "the number of wheels",
            self.0.wheels().len(),
        )?;
        Ok(array1(
            py,
            &self.0.odometry(q, d.as_slice()).map_err(err(F))?,
        ))
    }
    /// `A(q)` of the nonholonomic constraint `A(q) q̇ = 0` (3,), or None (omnidirectional).
    fn constraint<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
    ) -> PyResult<Option<Bound<'py, numpy::PyArray1<f64>>>> {
        let q = chassis(q, "Base.constraint", "q")?;
        Ok(self.0.constraint(q).map(|a| array1(py, &a)))
    }
    /// A car's steering angle for the planar body twist (omega, v, 0); None otherwise.
    fn steering(&self, twist: &Bound<'_, PyAny>) -> PyResult<Option<f64>> {
        let t = vector(twist, "Base.steering", "twist", "3", 3)?;
        let s = t.as_slice();
        Ok(self.0.steering([s[0], s[1], s[2]]))
    }
    fn __repr__(&self) -> String {
        format!(
            "rigid.mobile.Base({}, {} wheels)",
            self.0.name(),
            self.0.wheels().len()
        )
    }
}

/// An arm (screw axes `Blist`, 6 × n columns, in the end-effector frame; home `M_0e`) on a wheeled
/// base at `T_b0`, the chassis frame `height` above the floor (§13.5). `MobileManipulator.youbot()`
/// is the capstone's.
#[pyclass(module = "rigid.mobile", name = "MobileManipulator", frozen)]
pub struct MobileManipulator(pub mb::MobileManipulator);

#[pymethods]
impl MobileManipulator {
    #[new]
    #[pyo3(signature = (base, T_b0, M_0e, Blist, height = 0.0))]
    fn new(
        base: &Base,
        T_b0: &Bound<'_, PyAny>,
        M_0e: &Bound<'_, PyAny>,
        Blist: &Bound<'_, PyAny>,
        height: f64,
    ) -> PyResult<Self> {
        const F: &str = "MobileManipulator";
        if !height.is_finite() {
            return Err(value_error(
                F,
                format!("height must be finite, got {height}"),
            ));
        }
        let mut m = mb::MobileManipulator::new(
            base.0.clone(),
            pose(T_b0, F, "T_b0")?,
            pose(M_0e, F, "M_0e")?,
            screw_axes(Blist, F, "Blist")?,
        );
        m.height = height;
        Ok(Self(m))
    }
    /// The KUKA youBot of the capstone.
    #[staticmethod]
    fn youbot() -> Self {
        Self(mb::MobileManipulator::youbot())
    }
    /// The wheeled base.
    #[getter]
    fn base(&self) -> Base {
        Base(self.0.base.clone())
    }
    /// The number of arm joints n.
    #[getter]
    fn n_arm(&self) -> usize {
        self.0.n_arm()
    }
    /// The number of wheels m.
    #[getter]
    fn n_wheels(&self) -> usize {
        self.0.n_wheels()
    }
    /// `T_sb(q)` (4 × 4) for the chassis configuration q = (phi, x, y).
    fn chassis_pose<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        Ok(homogeneous(
            py,
            &self.0.chassis_pose(chassis(q, "chassis_pose", "q")?),
        ))
    }
    /// `X = T_se = T_sb(q) T_b0 M_0e e^{[B_1]θ_1} ⋯ e^{[B_n]θ_n}` (4 × 4).
    fn forward<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        theta: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        const F: &str = "MobileManipulator.forward";
        let theta = vector(theta, F, "theta", "n", self.0.n_arm())?;
        let x = self
            .0
            .forward(chassis(q, F, "q")?, theta.as_slice())
            .map_err(err(F))?;
        Ok(homogeneous(py, &x))
    }
    /// `J_e(θ) = [J_base, J_arm]` (6 × (m + n)), wheels first.
    fn jacobian<'py>(
        &self,
        py: Python<'py>,
        theta: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        const F: &str = "MobileManipulator.jacobian";
        let theta = vector(theta, F, "theta", "n", self.0.n_arm())?;
        Ok(dmatrix(
            py,
            &self.0.jacobian(theta.as_slice()).map_err(err(F))?,
        ))
    }
    /// One Euler step (the capstone's NextState): returns the new `(chassis, arm, wheels)`;
    /// `speeds` = (u, θ̇), wheels first, clipped to ±max_speed.
    #[pyo3(signature = (chassis_q, arm, wheels, speeds, dt, max_speed = f64::INFINITY))]
    #[allow(clippy::too_many_arguments, clippy::type_complexity)]
    fn next_state<'py>(
        &self,
        py: Python<'py>,
        chassis_q: &Bound<'py, PyAny>,
        arm: &Bound<'py, PyAny>,
        wheels: &Bound<'py, PyAny>,
        speeds: &Bound<'py, PyAny>,
        dt: f64,
        max_speed: f64,
    ) -> PyResult<(
        Bound<'py, numpy::PyArray1<f64>>,
        Bound<'py, numpy::PyArray1<f64>>,
        Bound<'py, numpy::PyArray1<f64>>,
    )> {
        const F: &str = "MobileManipulator.next_state";
        let (m, n) = (self.0.n_wheels(), self.0.n_arm());
        let state = mb::MobileState {
            chassis: chassis(chassis_q, F, "chassis")?,
            arm: vector(arm, F, "arm", "n", n)?.as_slice().to_vec(),
            wheels: vector(wheels, F, "wheels", "m", m)?.as_slice().to_vec(),
        };
        let speeds = vector(speeds, F, "speeds", "m + n", m + n)?;
        let s = self
            .0
            .next_state(&state, speeds.as_slice(), dt, max_speed)
            .map_err(err(F))?;
        Ok((
            array1(py, &s.chassis),
            array1(py, &s.arm),
            array1(py, &s.wheels),
        ))
    }
    /// One step of the task-space feedback from a zero integral (eq. 13.37):
    /// returns `(V, speeds, X_err)`; `Kp`, `Ki` a number, 6 numbers or 6 × 6. For an integral
    /// kept across steps, use `Feedback`.
    #[pyo3(signature = (X, Xd, Xd_next, Kp, Ki, dt, theta, limits = None, tolerance = 1e-4))]
    #[allow(clippy::too_many_arguments)]
    fn feedback<'py>(
        &self,
        py: Python<'py>,
        X: &Bound<'py, PyAny>,
        Xd: &Bound<'py, PyAny>,
        Xd_next: &Bound<'py, PyAny>,
        Kp: &Bound<'py, PyAny>,
        Ki: &Bound<'py, PyAny>,
        dt: f64,
        theta: &Bound<'py, PyAny>,
        limits: Option<Vec<(f64, f64)>>,
        tolerance: f64,
    ) -> PyResult<Command<'py>> {
        let mut fb = Feedback::new(Kp, Ki, limits, tolerance)?;
        fb.command(py, self, X, Xd, Xd_next, dt, theta)
    }
    fn __repr__(&self) -> String {
        format!(
            "rigid.mobile.MobileManipulator({} base, {} wheels, {} arm joints)",
            self.0.base.name(),
            self.0.n_wheels(),
            self.0.n_arm()
        )
    }
}

type Command<'py> = (
    Bound<'py, numpy::PyArray1<f64>>,
    Bound<'py, numpy::PyArray1<f64>>,
    Bound<'py, numpy::PyArray1<f64>>,
);

/// Feedforward plus PI on the end-effector pose, keeping its integral between calls:
/// `V = [Ad_{X⁻¹X_d}] V_d + Kp X_err + Ki ∫X_err dt`, `(u, θ̇) = J_e† V`.
#[pyclass(module = "rigid.mobile", name = "Feedback")]
pub struct Feedback(mb::Feedback);

#[pymethods]
impl Feedback {
    #[new]
    #[pyo3(signature = (Kp, Ki, limits = None, tolerance = 1e-4))]
    fn new(
        Kp: &Bound<'_, PyAny>,
        Ki: &Bound<'_, PyAny>,
        limits: Option<Vec<(f64, f64)>>,
        tolerance: f64,
    ) -> PyResult<Self> {
        const F: &str = "Feedback";
        let mut fb = mb::Feedback::new(gain(Kp, F, "Kp")?, gain(Ki, F, "Ki")?).map_err(err(F))?;
        if !(tolerance.is_finite() && tolerance >= 0.0) {
            return Err(value_error(
                F,
                format!("tolerance must be >= 0, got {tolerance}"),
            ));
        }
        fb.tolerance = tolerance;
        fb.limits = limits.unwrap_or_default();
        Ok(Self(fb))
    }
    /// One control step: `(V, speeds, X_err)`; adds `X_err dt` to the integral.
    #[allow(clippy::too_many_arguments)]
    fn command<'py>(
        &mut self,
        py: Python<'py>,
        robot: &MobileManipulator,
        X: &Bound<'py, PyAny>,
        Xd: &Bound<'py, PyAny>,
        Xd_next: &Bound<'py, PyAny>,
        dt: f64,
        theta: &Bound<'py, PyAny>,
    ) -> PyResult<Command<'py>> {
        const F: &str = "Feedback.command";
        let theta = vector(theta, F, "theta", "n", robot.0.n_arm())?;
        let c = self
            .0
            .command(
                &robot.0,
                &pose(X, F, "X")?,
                &pose(Xd, F, "Xd")?,
                &pose(Xd_next, F, "Xd_next")?,
                dt,
                theta.as_slice(),
            )
            .map_err(err(F))?;
        Ok((
            array1(py, c.V.to_vector().as_slice()),
            array1(py, &c.speeds),
            array1(py, c.X_err.to_vector().as_slice()),
        ))
    }
    /// `∫X_err dt` so far (6,).
    #[getter]
    fn integral<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        array1(py, self.0.integral.to_vector().as_slice())
    }
    /// Sets the integral back to zero.
    fn reset(&mut self) {
        self.0.integral = Twist::zero();
    }
}

fn reference_rows(points: &[mb::ReferencePoint]) -> Vec<f64> {
    let mut out = Vec::with_capacity(points.len() * 13);
    for p in points {
        let (r, t) = (p.X.rotation, p.X.translation);
        for i in 0..3 {
            for j in 0..3 {
                out.push(r[(i, j)]);
            }
        }
        out.extend_from_slice(t.as_slice());
        out.push(if p.closed { 1.0 } else { 0.0 });
    }
    out
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
    crate::convert::rows_array(py, reference_rows(&r), r.len(), 13)
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
        c.start.chassis = self::chassis(q, F, "chassis")?;
    }
    if let Some(a) = arm {
        c.start.arm = vector(a, F, "arm", "5", 5)?.as_slice().to_vec();
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
    d.set_item(
        "states",
        crate::convert::rows_array(py, rows, run.states.len(), 13)?,
    )?;
    d.set_item(
        "errors",
        crate::convert::rows_array(py, errors, run.errors.len(), 6)?,
    )?;
    d.set_item(
        "reference",
        crate::convert::rows_array(py, reference_rows(&run.reference), run.reference.len(), 13)?,
    )?;
    d.set_item("dt", run.dt)?;
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
    let theta = vector(theta, F, "theta", "n", b.len())?;
    let t =
        poe::fkin_body(&pose(M, F, "M")?, &b, theta.as_slice()).map_err(|e| value_error(F, e))?;
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
    let theta = vector(theta, F, "theta", "n", s.len())?;
    let t =
        poe::fkin_space(&pose(M, F, "M")?, &s, theta.as_slice()).map_err(|e| value_error(F, e))?;
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
    let theta = vector(theta, F, "theta", "n", b.len())?;
    Ok(dmatrix(
        py,
        &poe::jacobian_body(&b, theta.as_slice()).map_err(|e| value_error(F, e))?,
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
    let theta = vector(theta, F, "theta", "n", s.len())?;
    Ok(dmatrix(
        py,
        &poe::jacobian_space(&s, theta.as_slice()).map_err(|e| value_error(F, e))?,
    ))
}

/// A robot file (URDF or MJCF, loaded with a free-flyer root, set down on the ground z = 0) with
/// its wheels under velocity control, `tau = gain (u_d - u)` (`rigid::mobile::wheel_simulator`,
/// as `rigid mobile drive`): returns a dict of `t`, `x`, `y`, `yaw`, `v` (speed along the
/// heading), `omega` (yaw rate), each (N,), `wheel_speeds` (N × m) and `q` (N × nq), every step.
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
    if !(time.is_finite() && time > 0.0) {
        return Err(value_error(F, format!("time must be positive, got {time}")));
    }
    let is_mjcf = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"));
    let model = if is_mjcf {
        let model = rigid::io::mjcf::load_mjcf(&path)
            .map_err(|e| value_error(F, e))?
            .model;
        if model.joints().first().map(|j| j.kind) != Some(rigid::multibody::JointType::FreeFlyer) {
            return Err(value_error(
                F,
                format!("{}: its root body has no free joint", path.display()),
            ));
        }
        model
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
    let mut sim = mb::wheel_simulator(&model, cm, &options).map_err(err(F))?;
    let idx = sim.control().wheels().to_vec();
    let steps = (time / dt).round() as usize;
    let (nq, m) = (model.nq(), idx.len());
    let mut cols: [Vec<f64>; 6] = Default::default();
    let (mut qs, mut us) = (
        Vec::with_capacity((steps + 1) * nq),
        Vec::with_capacity((steps + 1) * m),
    );
    for k in 0..=steps {
        if k > 0 {
            sim.step()
                .map_err(|e| value_error(F, format!("t = {:.3} s: {e}", k as f64 * dt)))?;
        }
        let (q, v) = (sim.q(), sim.v());
        let motion = mb::chassis_motion(q, v);
        cols[0].push(k as f64 * dt);
        for (c, x) in cols[1..].iter_mut().zip(motion) {
            c.push(x);
        }
        qs.extend_from_slice(q);
        us.extend(idx.iter().map(|&i| v[i]));
    }
    let d = PyDict::new(py);
    for (name, c) in ["t", "x", "y", "yaw", "v", "omega"].iter().zip(&cols) {
        d.set_item(*name, array1(py, c))?;
    }
    d.set_item(
        "wheel_speeds",
        crate::convert::rows_array(py, us, steps + 1, m)?,
    )?;
    d.set_item("q", crate::convert::rows_array(py, qs, steps + 1, nq)?)?;
    Ok(d)
}

/// The native submodule `rigid.rigid._mobile`, re-exported by `rigid/mobile.py`.
pub fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = PyModule::new(parent.py(), "_mobile")?;
    m.add_class::<Base>()?;
    m.add_class::<MobileManipulator>()?;
    m.add_class::<Feedback>()?;
    m.add_function(wrap_pyfunction!(pick_and_place, &m)?)?;
    m.add_function(wrap_pyfunction!(capstone, &m)?)?;
    m.add_function(wrap_pyfunction!(drive, &m)?)?;
    m.add_function(wrap_pyfunction!(fkin_body, &m)?)?;
    m.add_function(wrap_pyfunction!(fkin_space, &m)?)?;
    m.add_function(wrap_pyfunction!(jacobian_body, &m)?)?;
    m.add_function(wrap_pyfunction!(jacobian_space, &m)?)?;
    parent.add_submodule(&m)
}
