//! `rigid.mobile`: the Python side of `rigid::mobile` (wheeled bases, odometry, mobile
//! manipulators, the capstone) and `rigid::kinematics::poe`, which do the work; this file converts
//! arrays in and out. Screw-axis lists are 6 × n arrays whose columns are the axes, as in the
//! Modern Robotics code library (`Blist`); poses are 4 × 4 homogeneous matrices.

#![allow(non_snake_case)] // the notes' names: H, F, T_b0, M_0e, Blist, X, Kp

use crate::convert::{array1, array2, finite_vector, matrix, pose, value_error};
use pyo3::prelude::*;
use rigid::mobile::{self as mb, Kind, MobileError};
use rigid::spatial::{Mat6, Transform, Twist};

pub(crate) fn err(func: &str) -> impl Fn(MobileError) -> PyErr + '_ {
    move |e| value_error(func, e)
}

pub(crate) fn homogeneous<'py>(py: Python<'py>, t: &Transform) -> Bound<'py, numpy::PyArray2<f64>> {
    let h = t.to_homogeneous();
    array2(py, 4, 4, |r, c| h[(r, c)])
}

pub(crate) fn dmatrix<'py>(
    py: Python<'py>,
    m: &nalgebra::DMatrix<f64>,
) -> Bound<'py, numpy::PyArray2<f64>> {
    array2(py, m.nrows(), m.ncols(), |r, c| m[(r, c)])
}

/// A 6 × n screw-axis list (columns) as twists.
pub(crate) fn screw_axes(x: &Bound<'_, PyAny>, func: &str, name: &str) -> PyResult<Vec<Twist>> {
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
pub(crate) fn gain(x: &Bound<'_, PyAny>, func: &str, name: &str) -> PyResult<Mat6> {
    if let Ok(k) = x.extract::<f64>() {
        return Ok(Mat6::identity() * k);
    }
    if let Ok(d) = finite_vector(x, func, name, "6", 6) {
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

pub(crate) fn chassis(x: &Bound<'_, PyAny>, func: &str, name: &str) -> PyResult<[f64; 3]> {
    let v = finite_vector(x, func, name, "3 (phi, x, y)", 3)?;
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
    fn H<'py>(&self, py: Python<'py>, phi: f64) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        if !phi.is_finite() {
            return Err(value_error(
                "Base.H",
                format!("phi must be finite, got {phi}"),
            ));
        }
        Ok(dmatrix(py, &self.0.H(phi)))
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
        let u = finite_vector(
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
        let d = finite_vector(
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
        let t = finite_vector(twist, "Base.steering", "twist", "3", 3)?;
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
        )
        .map_err(err(F))?;
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
        let theta = finite_vector(theta, F, "theta", "n", self.0.n_arm())?;
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
        let theta = finite_vector(theta, F, "theta", "n", self.0.n_arm())?;
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
            arm: finite_vector(arm, F, "arm", "n", n)?.as_slice().to_vec(),
            wheels: finite_vector(wheels, F, "wheels", "m", m)?
                .as_slice()
                .to_vec(),
        };
        let speeds = finite_vector(speeds, F, "speeds", "m + n", m + n)?;
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
        let theta = finite_vector(theta, F, "theta", "n", robot.0.n_arm())?;
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

/// The native submodule `rigid.rigid._mobile`, re-exported by `rigid/mobile.py`.
pub fn register(parent: &Bound<'_, PyModule>) -> PyResult<()> {
    let m = PyModule::new(parent.py(), "_mobile")?;
    m.add_class::<Base>()?;
    m.add_class::<MobileManipulator>()?;
    m.add_class::<Feedback>()?;
    crate::mobile_tasks::register(&m)?;
    parent.add_submodule(&m)
}
