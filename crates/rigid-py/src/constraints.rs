//! Constrained dynamics with Pinocchio's names: `ConstraintModel` (`RigidConstraintModel`),
//! `ConstraintData` (`initConstraintDynamics` and the constraint datas), `constraint_dynamics` /
//! `constraintDynamics`, `impulse_dynamics` / `impulseDynamics`, `contact_inverse_dynamics` /
//! `contactInverseDynamics`. Thin: the library does the work (`rigid::multibody::constraints`);
//! this file converts arguments and layouts.

use crate::convert::{array1, array2, matrix, value_error, vector};
use crate::dynamics::load;
use crate::model::{Data, Model, ModelCore};
use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rigid::multibody::constraints::{
    self as cs, ConstraintKind, ConstraintModel as Inner, ProximalSettings, UNIVERSE,
};
use rigid::multibody::{JointId, ReferenceFrame};
use rigid::spatial::{Mat3, Transform, Vec3};
use std::sync::Arc;

/// The name of an enum-like argument: a string, or a Pinocchio enum value's `name`.
fn name_of(x: &Bound<'_, PyAny>) -> PyResult<String> {
    match x.extract::<String>() {
        Ok(s) => Ok(s.to_ascii_lowercase()),
        Err(_) => Ok(x.getattr("name")?.extract::<String>()?.to_ascii_lowercase()),
    }
}

fn kind(func: &str, x: &Bound<'_, PyAny>) -> PyResult<ConstraintKind> {
    match name_of(x)?.as_str() {
        "point" | "contact_3d" => Ok(ConstraintKind::Point),
        "frame" | "contact_6d" => Ok(ConstraintKind::Frame),
        other => Err(value_error(
            func,
            format!("kind must be \"point\" or \"frame\" (Pinocchio's CONTACT_3D, CONTACT_6D), got \"{other}\""),
        )),
    }
}

fn reference(func: &str, x: &Bound<'_, PyAny>) -> PyResult<ReferenceFrame> {
    Inner::reference_named(&name_of(x)?).map_err(|e| value_error(func, e))
}

/// A placement: `None` (the identity), `(R, p)`, a 4 × 4 homogeneous matrix, or an object with
/// `rotation` and `translation` (`pin.SE3`).
fn placement(func: &str, name: &str, x: Option<&Bound<'_, PyAny>>) -> PyResult<Transform> {
    let Some(x) = x else {
        return Ok(Transform::identity());
    };
    let from = |r: &Bound<'_, PyAny>, p: &Bound<'_, PyAny>| -> PyResult<Transform> {
        let r = matrix(r, func, name, "3", 3)?;
        if r.rows != 3 {
            return Err(value_error(
                func,
                format!("{name}: the rotation must be 3 x 3"),
            ));
        }
        let p = vector(p, func, name, "3", 3)?;
        let rs = r.as_slice();
        let p = p.as_slice();
        Ok(Transform::new(
            Mat3::from_row_slice(rs),
            Vec3::new(p[0], p[1], p[2]),
        ))
    };
    if let (Ok(r), Ok(p)) = (x.getattr("rotation"), x.getattr("translation")) {
        return from(&r, &p);
    }
    if let Ok((r, p)) = x.extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>() {
        return from(&r, &p);
    }
    let h = matrix(x, func, name, "4", 4).map_err(|_| {
        value_error(
            func,
            format!("{name} must be (R, p), a 4 x 4 matrix or a pin.SE3"),
        )
    })?;
    if h.rows != 4 {
        return Err(value_error(
            func,
            format!("{name}: a homogeneous matrix is 4 x 4"),
        ));
    }
    let m = h.as_slice();
    Ok(Transform::new(
        Mat3::new(m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]),
        Vec3::new(m[3], m[7], m[11]),
    ))
}

/// A bilateral constraint between two frames (Pinocchio's `RigidConstraintModel`): a point
/// (3 rows) or a frame (6 rows) between c1 = joint1 · placement1 and c2 = joint2 · placement2
/// ("universe": the world), `λ` the force or wrench on joint1's body in c1's axes ("local") or
/// the world's ("local_world_aligned"), Baumgarte gains `kp`, `kd`.
#[pyclass(module = "rigid", name = "ConstraintModel")]
#[derive(Clone)]
pub struct ConstraintModel {
    inner: Inner,
    model: Arc<ModelCore>,
}

#[pymethods]
impl ConstraintModel {
    #[new]
    #[pyo3(signature = (model, kind, joint1, placement1 = None, joint2 = UNIVERSE, placement2 = None, reference_frame = None, kp = 0.0, kd = 0.0))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        model: PyRef<'_, Model>,
        kind: &Bound<'_, PyAny>,
        joint1: &str,
        placement1: Option<&Bound<'_, PyAny>>,
        joint2: &str,
        placement2: Option<&Bound<'_, PyAny>>,
        reference_frame: Option<&Bound<'_, PyAny>>,
        kp: f64,
        kd: f64,
    ) -> PyResult<Self> {
        let f = "ConstraintModel";
        let core = &model.inner;
        let inner = Inner::on_joints(
            &core.model,
            self::kind(f, kind)?,
            joint1,
            placement(f, "placement1", placement1)?,
            joint2,
            placement(f, "placement2", placement2)?,
        )
        .map_err(|e| value_error(f, e))?;
        let rf = reference_frame.map_or(Ok(ReferenceFrame::Body), |x| reference(f, x))?;
        Ok(Self {
            inner: inner.with_reference(rf).with_baumgarte(kp, kd),
            model: Arc::clone(core),
        })
    }

    /// A point or frame constraint between two named frames (links, fixed joints; "universe":
    /// the world frame), c1 and c2 at the frames.
    #[staticmethod]
    #[pyo3(signature = (model, kind, frame1, frame2 = UNIVERSE, reference_frame = None, kp = 0.0, kd = 0.0))]
    fn on_frames(
        model: PyRef<'_, Model>,
        kind: &Bound<'_, PyAny>,
        frame1: &str,
        frame2: &str,
        reference_frame: Option<&Bound<'_, PyAny>>,
        kp: f64,
        kd: f64,
    ) -> PyResult<Self> {
        let f = "ConstraintModel.on_frames";
        let core = &model.inner;
        let inner = Inner::on_frames(&core.model, self::kind(f, kind)?, frame1, frame2)
            .map_err(|e| value_error(f, e))?;
        let rf = reference_frame.map_or(Ok(ReferenceFrame::Body), |x| reference(f, x))?;
        Ok(Self {
            inner: inner.with_reference(rf).with_baumgarte(kp, kd),
            model: Arc::clone(core),
        })
    }

    /// The `<equality>` elements of the MJCF file `model` was read from (`connect`: a point,
    /// `weld`: a frame, `joint`: a joint coordinate; hard, world-aligned; the library's
    /// `MjcfModel::constraint_models`). What is left out (tendon or inactive equalities) is an
    /// `MjcfWarning` naming the line.
    #[staticmethod]
    fn from_mjcf(py: Python<'_>, model: PyRef<'_, Model>) -> PyResult<Vec<Self>> {
        let f = "ConstraintModel.from_mjcf";
        let core = &model.inner;
        let path = core
            .source
            .as_ref()
            .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("xml")))
            .ok_or_else(|| value_error(f, "the model was not read from an MJCF file"))?;
        let shown = path.display();
        let mj = rigid::io::mjcf::load_mjcf(path)
            .map_err(|e| value_error(f, format!("{shown}: {e}")))?;
        let (constraints, skipped) = mj
            .constraint_models()
            .map_err(|e| value_error(f, format!("{shown}: {e}")))?;
        let skipped: Vec<String> = skipped.iter().map(|w| format!("{shown}: {w}")).collect();
        crate::model::warn_all(py, &py.get_type::<crate::model::MjcfWarning>(), &skipped)?;
        Ok(constraints
            .into_iter()
            .map(|inner| Self {
                inner,
                model: Arc::clone(core),
            })
            .collect())
    }

    /// The loops of the SDF file `model` was read from: each joint whose child was already in
    /// the tree (a ball joint a point, a fixed joint a weld, a revolute joint two points on its
    /// axis; the library's `SdfModel::constraints`).
    #[staticmethod]
    fn from_sdf(model: PyRef<'_, Model>) -> PyResult<Vec<Self>> {
        let f = "ConstraintModel.from_sdf";
        let core = &model.inner;
        let path = core
            .source
            .as_ref()
            .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("sdf")))
            .ok_or_else(|| value_error(f, "the model was not read from an SDF file"))?;
        let sdf = rigid::io::sdf::load_sdf(path)
            .map_err(|e| value_error(f, format!("{}: {e}", path.display())))?;
        Ok(sdf
            .constraints
            .into_iter()
            .map(|inner| Self {
                inner,
                model: Arc::clone(core),
            })
            .collect())
    }

    /// `q_joint1 = Σ_k polycoef[k] q_joint2^k` for one-dof joints (MJCF `<equality joint>`);
    /// without joint2, `q_joint1 = polycoef[0]`.
    #[staticmethod]
    #[pyo3(signature = (model, joint1, joint2 = None, polycoef = vec![0.0, 1.0], kp = 0.0, kd = 0.0))]
    fn joint_coordinate(
        model: PyRef<'_, Model>,
        joint1: &str,
        joint2: Option<&str>,
        polycoef: Vec<f64>,
        kp: f64,
        kd: f64,
    ) -> PyResult<Self> {
        let f = "ConstraintModel.joint_coordinate";
        let core = &model.inner;
        let id = |name: &str| -> PyResult<JointId> {
            core.model
                .joint_id(name)
                .ok_or_else(|| value_error(f, format!("no joint named \"{name}\"")))
        };
        if polycoef.len() > 5 {
            return Err(value_error(f, "polycoef has at most 5 coefficients"));
        }
        let mut c = [0.0; 5];
        c[..polycoef.len()].copy_from_slice(&polycoef);
        let j2 = joint2.map(id).transpose()?;
        Ok(Self {
            inner: Inner::joint_coordinate(id(joint1)?, j2, c).with_baumgarte(kp, kd),
            model: Arc::clone(core),
        })
    }

    /// The number of rows: 3 (point), 6 (frame) or 1 (joint coordinate).
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim()
    }

    fn __repr__(&self) -> String {
        let name = |j: Option<JointId>| {
            j.map_or(UNIVERSE.to_string(), |j| {
                self.model.model.joint(j).name.clone()
            })
        };
        let kind = match self.inner.kind {
            ConstraintKind::Point => "point",
            ConstraintKind::Frame => "frame",
            ConstraintKind::JointCoordinate { .. } => "joint_coordinate",
        };
        format!(
            "rigid.ConstraintModel({kind}, joint1='{}', joint2='{}')",
            name(self.inner.joint1),
            name(self.inner.joint2)
        )
    }
}

/// The workspace of a constraint set on a model (Pinocchio's `initConstraintDynamics` with its
/// constraint datas), made once; the results of the last call in `lambda_c`, `impulse_c`.
#[pyclass(module = "rigid", name = "ConstraintData")]
pub struct ConstraintData {
    inner: cs::ConstraintData,
    model: Arc<ModelCore>,
}

impl ConstraintData {
    /// An `m × nv` matrix of constraint rows (`J`, `∂λ/∂q`, …) as a fresh array in the model's
    /// layout: columns permuted as velocities, and in Pinocchio's layout each frame
    /// constraint's rows force first.
    fn rows_out<'py>(
        &self,
        py: Python<'py>,
        j: &nalgebra::DMatrix<f64>,
    ) -> Bound<'py, PyArray2<f64>> {
        let force_first = self.model.layout.is_some();
        array2(py, j.nrows(), j.ncols(), |r, c| {
            j[(self.inner.source_row(r, force_first), self.model.v_index(c))]
        })
    }

    /// `λ`-like numbers in the model's layout: each frame's wrench force first in Pinocchio's.
    fn out<'py>(&self, py: Python<'py>, x: &[f64]) -> Bound<'py, PyArray1<f64>> {
        if self.model.layout.is_none() {
            return array1(py, x);
        }
        let mut y = vec![0.0; x.len()];
        self.inner.force_first(x, &mut y);
        PyArray1::from_vec(py, y)
    }

    fn check(&self, func: &str, model: &Model) -> PyResult<()> {
        if self.model.id == model.inner.id {
            Ok(())
        } else {
            Err(value_error(
                func,
                "constraint data was made for another model",
            ))
        }
    }
}

/// The library's constraints of `constraints`, each made for the model of `core`.
pub(crate) fn rigid_constraints(
    func: &str,
    core: &ModelCore,
    constraints: &[PyRef<'_, ConstraintModel>],
) -> PyResult<Vec<cs::ConstraintModel>> {
    constraints
        .iter()
        .enumerate()
        .map(|(i, c)| {
            if c.model.id == core.id {
                Ok(c.inner.clone())
            } else {
                Err(value_error(
                    func,
                    format!("constraint {i} was made for another model"),
                ))
            }
        })
        .collect()
}

#[pymethods]
impl ConstraintData {
    #[new]
    fn new(
        model: PyRef<'_, Model>,
        constraints: Vec<PyRef<'_, ConstraintModel>>,
    ) -> PyResult<Self> {
        let core = &model.inner;
        let set = rigid_constraints("ConstraintData", core, &constraints)?;
        Ok(Self {
            inner: cs::ConstraintData::new(&core.model, &set)
                .map_err(|e| value_error("ConstraintData", e))?,
            model: Arc::clone(core),
        })
    }

    /// The total number of constraint rows.
    #[getter]
    fn dim(&self) -> usize {
        self.inner.dim()
    }

    /// `λ` of the last `constraint_dynamics` or `contact_inverse_dynamics` (N, N·m; per
    /// constraint in its reference frame; a wrench moment first in rigid's layout, force first
    /// in Pinocchio's: Pinocchio's `data.lambda_c`).
    #[getter]
    fn lambda_c<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.out(py, self.inner.lambda.as_slice())
    }

    /// The impulse of the last `impulse_dynamics` (N·s, N·m·s; Pinocchio's `data.impulse_c`).
    #[getter]
    fn impulse_c<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.out(py, self.inner.impulse.as_slice())
    }

    /// The drift `γ` of the last `constraint_dynamics` (`J q̈ + γ = 0`).
    #[getter]
    fn gamma<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.out(py, self.inner.gamma.as_slice())
    }

    /// The constraint Jacobian `J` (dim × nv) at the last `q`, in the model's layout.
    #[getter]
    fn jacobian<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        self.rows_out(py, &self.inner.jacobian)
    }

    /// The largest constraint error `‖e‖∞` at the last `q` (m, rad).
    #[getter]
    fn violation(&self) -> f64 {
        self.inner.violation()
    }

    /// The last solve: `{"iterations", "absolute_residual", "relative_residual", "converged",
    /// "dynamics_residual"}`.
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = self.inner.stats;
        let d = PyDict::new(py);
        d.set_item("iterations", s.iterations)?;
        d.set_item("absolute_residual", s.absolute_residual)?;
        d.set_item("relative_residual", s.relative_residual)?;
        d.set_item("converged", s.converged)?;
        d.set_item("dynamics_residual", s.dynamics_residual)?;
        Ok(d)
    }
}

fn settings(func: &str, mu: f64, max_iter: usize, accuracy: f64) -> PyResult<ProximalSettings> {
    let s = ProximalSettings::new(accuracy, mu, max_iter);
    if mu.is_nan() || mu < 0.0 || max_iter == 0 || accuracy.is_nan() || accuracy < 0.0 {
        return Err(PyValueError::new_err(format!(
            "{func}: mu and accuracy must be >= 0 and max_iter >= 1"
        )));
    }
    Ok(s)
}

/// Forward dynamics with constraints: `q̈` with `M q̈ + c + g = τ + Jᵀ λ`, `J q̈ + γ = 0`;
/// `λ` in `constraint_data.lambda_c`. Pinocchio: `constraintDynamics`.
#[pyfunction]
#[pyo3(signature = (model, data, q, v, tau, constraint_data, mu = 0.0, max_iter = 100, accuracy = 1e-12))]
#[allow(clippy::too_many_arguments)]
pub fn constraint_dynamics<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    tau: &Bound<'py, PyAny>,
    mut constraint_data: PyRefMut<'py, ConstraintData>,
    mu: f64,
    max_iter: usize,
    accuracy: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let f = "constraint_dynamics";
    constraint_data.check(f, &model)?;
    let s = settings(f, mu, max_iter, accuracy)?;
    let d = &mut *data;
    load(f, &model, d, q, &[("v", v), ("tau", tau)])?;
    let cd = &mut constraint_data.inner;
    let m = &model.inner.model;
    let ddq = cs::constraint_dynamics(m, &mut d.inner, cd, &d.q, &d.v, &d.a, &s)
        .map_err(|e| value_error(f, e))?;
    Ok(model.inner.v_out(py, ddq.as_slice()))
}

/// The velocity just after an impact that starts the constraints: `M (q̇⁺ − q̇⁻) = Jᵀ Λ`,
/// `J q̇⁺ = −r_coeff J q̇⁻`; the impulse `Λ` in `constraint_data.impulse_c`. Pinocchio:
/// `impulseDynamics` (whose law differs for a constraint between two moving bodies).
#[pyfunction]
#[pyo3(signature = (model, data, q, v, constraint_data, r_coeff = 0.0, mu = 0.0, max_iter = 100, accuracy = 1e-12))]
#[allow(clippy::too_many_arguments)]
pub fn impulse_dynamics<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    mut constraint_data: PyRefMut<'py, ConstraintData>,
    r_coeff: f64,
    mu: f64,
    max_iter: usize,
    accuracy: f64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let f = "impulse_dynamics";
    constraint_data.check(f, &model)?;
    let s = settings(f, mu, max_iter, accuracy)?;
    let d = &mut *data;
    load(f, &model, d, q, &[("v", v)])?;
    let cd = &mut constraint_data.inner;
    let m = &model.inner.model;
    let dq = cs::impulse_dynamics(m, &mut d.inner, cd, &d.q, &d.v, r_coeff, &s)
        .map_err(|e| value_error(f, e))?;
    Ok(model.inner.v_out(py, dq.as_slice()))
}

/// The derivatives of `constraint_dynamics` at `(q, v, tau)` (which it runs): a dict of
/// `ddq_dq`, `ddq_dv`, `ddq_dtau` (nv × nv) and `dlambda_dq`, `dlambda_dv`, `dlambda_dtau`
/// (dim × nv), derivatives in `q` along `q ⊕ δ`, in the model's layout. Pinocchio:
/// `computeConstraintDynamicsDerivatives`.
#[pyfunction]
#[pyo3(signature = (model, data, q, v, tau, constraint_data, mu = 0.0, max_iter = 100, accuracy = 1e-12))]
#[allow(clippy::too_many_arguments)]
pub fn constraint_dynamics_derivatives<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    tau: &Bound<'py, PyAny>,
    mut constraint_data: PyRefMut<'py, ConstraintData>,
    mu: f64,
    max_iter: usize,
    accuracy: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let f = "constraint_dynamics_derivatives";
    constraint_data.check(f, &model)?;
    let s = settings(f, mu, max_iter, accuracy)?;
    let d = &mut *data;
    load(f, &model, d, q, &[("v", v), ("tau", tau)])?;
    let m = &model.inner.model;
    let mut out = cs::ConstraintDynamicsDerivatives::new(m, &constraint_data.inner);
    let cd = &mut constraint_data.inner;
    cs::constraint_dynamics_derivatives(m, &mut d.inner, cd, &d.q, &d.v, &d.a, &s, &mut out)
        .map_err(|e| value_error(f, e))?;
    let dict = PyDict::new(py);
    let core = &model.inner;
    dict.set_item("ddq_dq", core.matrix_out(py, &out.ddq_dq))?;
    dict.set_item("ddq_dv", core.matrix_out(py, &out.ddq_dv))?;
    dict.set_item("ddq_dtau", core.matrix_out(py, &out.ddq_dtau))?;
    dict.set_item("dlambda_dq", constraint_data.rows_out(py, &out.dlambda_dq))?;
    dict.set_item("dlambda_dv", constraint_data.rows_out(py, &out.dlambda_dv))?;
    dict.set_item(
        "dlambda_dtau",
        constraint_data.rows_out(py, &out.dlambda_dtau),
    )?;
    Ok(dict)
}

/// The derivatives of `impulse_dynamics` at `(q, v)` (which it runs): a dict of `dvplus_dq`,
/// `dvplus_dv` (the full `∂q̇⁺/∂q̇⁻`; Pinocchio's `ddq_dv` is this minus the identity) and
/// `dimpulse_dq`, `dimpulse_dv`, in the model's layout. Pinocchio:
/// `computeImpulseDynamicsDerivatives`.
#[pyfunction]
#[pyo3(signature = (model, data, q, v, constraint_data, r_coeff = 0.0, mu = 0.0, max_iter = 100, accuracy = 1e-12))]
#[allow(clippy::too_many_arguments)]
pub fn impulse_dynamics_derivatives<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    mut constraint_data: PyRefMut<'py, ConstraintData>,
    r_coeff: f64,
    mu: f64,
    max_iter: usize,
    accuracy: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let f = "impulse_dynamics_derivatives";
    constraint_data.check(f, &model)?;
    let s = settings(f, mu, max_iter, accuracy)?;
    let d = &mut *data;
    load(f, &model, d, q, &[("v", v)])?;
    let m = &model.inner.model;
    let mut out = cs::ImpulseDynamicsDerivatives::new(m, &constraint_data.inner);
    let cd = &mut constraint_data.inner;
    cs::impulse_dynamics_derivatives(m, &mut d.inner, cd, &d.q, &d.v, r_coeff, &s, &mut out)
        .map_err(|e| value_error(f, e))?;
    let dict = PyDict::new(py);
    let core = &model.inner;
    dict.set_item("dvplus_dq", core.matrix_out(py, &out.dvplus_dq))?;
    dict.set_item("dvplus_dv", core.matrix_out(py, &out.dvplus_dv))?;
    dict.set_item(
        "dimpulse_dq",
        constraint_data.rows_out(py, &out.dimpulse_dq),
    )?;
    dict.set_item(
        "dimpulse_dv",
        constraint_data.rows_out(py, &out.dimpulse_dv),
    )?;
    Ok(dict)
}

/// Inverse dynamics with constraints: the least-norm `(τ, λ)` (τ zero on a free-flyer) with
/// `M a + c + g = τ + Jᵀ λ`; returns `τ`, `λ` in `constraint_data.lambda_c`. Not Pinocchio 4.1's
/// `contactInverseDynamics`, which takes λ from a compliant contact law (see the stubs).
#[pyfunction]
pub fn contact_inverse_dynamics<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    a: &Bound<'py, PyAny>,
    mut constraint_data: PyRefMut<'py, ConstraintData>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let f = "contact_inverse_dynamics";
    constraint_data.check(f, &model)?;
    let d = &mut *data;
    load(f, &model, d, q, &[("v", v), ("a", a)])?;
    let cd = &mut constraint_data.inner;
    let m = &model.inner.model;
    let tau = cs::contact_inverse_dynamics(m, &mut d.inner, cd, &d.q, &d.v, &d.a)
        .map_err(|e| value_error(f, e))?;
    Ok(model.inner.v_out(py, tau.as_slice()))
}

/// Registers the classes, the verbs and their Pinocchio names.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<ConstraintModel>()?;
    m.add_class::<ConstraintData>()?;
    m.add_function(wrap_pyfunction!(constraint_dynamics, m)?)?;
    m.add_function(wrap_pyfunction!(impulse_dynamics, m)?)?;
    m.add_function(wrap_pyfunction!(contact_inverse_dynamics, m)?)?;
    m.add_function(wrap_pyfunction!(constraint_dynamics_derivatives, m)?)?;
    m.add_function(wrap_pyfunction!(impulse_dynamics_derivatives, m)?)?;
    for (alias, name) in [
        ("constraintDynamics", "constraint_dynamics"),
        ("impulseDynamics", "impulse_dynamics"),
        ("contactInverseDynamics", "contact_inverse_dynamics"),
    ] {
        m.add(alias, m.getattr(name)?)?;
    }
    Ok(())
}
