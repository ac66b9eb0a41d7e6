//! The multibody verbs, with Pinocchio's names and signatures: `rnea`, `crba`, `aba`, `nle`,
//! `gravity`, `minverse`, `coriolis_matrix`, `forward_kinematics`, `jacobian`, `com`, the
//! energies. Each checks its inputs, converts them from the model's layout, calls rigid and
//! returns a fresh float64 array in the model's layout.

#[path = "dynamics_mujoco.rs"]
mod mujoco;

use crate::convert::{self, array1, array2, value_error, vector, Vector};
use crate::model::{Data, Model, ModelCore, Place};
use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rigid::multibody::{self as mb, ReferenceFrame};

/// The inputs of one call: the function's name (for messages) and the model.
struct Call<'a> {
    func: &'static str,
    core: &'a ModelCore,
}

impl<'a> Call<'a> {
    fn new(func: &'static str, model: &'a Model, data: &Data) -> PyResult<Self> {
        model.inner.check_data(func, data)?;
        Ok(Self {
            func,
            core: &model.inner,
        })
    }

    fn q<'py>(&self, x: &Bound<'py, PyAny>, name: &str) -> PyResult<Vector<'py>> {
        vector(x, self.func, name, "nq", self.core.nq())
    }

    fn v<'py>(&self, x: &Bound<'py, PyAny>, name: &str) -> PyResult<Vector<'py>> {
        vector(x, self.func, name, "nv", self.core.nv())
    }

    /// Checks `q` and the velocity-space inputs `vs` (at most two) and writes them, in rigid's
    /// layout, into `d.q`, then `d.v` and `d.a`.
    fn load(
        &self,
        d: &mut Data,
        q: &Bound<'_, PyAny>,
        vs: &[(&str, &Bound<'_, PyAny>)],
    ) -> PyResult<()> {
        let x = self.q(q, "q")?;
        self.core.q_into(&x, &mut d.q, self.func, "q")?;
        for ((name, x), out) in vs.iter().zip([&mut d.v, &mut d.a]) {
            let x = self.v(x, name)?;
            self.core.v_into(&x, out, self.func, name)?;
        }
        Ok(())
    }

    fn err(&self) -> impl Fn(mb::MultibodyError) -> PyErr + '_ {
        move |e| value_error(self.func, e)
    }
}

/// Checks that `data` was made for `model` and writes `q` and the velocity-space inputs `vs`
/// (at most two), in rigid's layout, into `data.q`, then `data.v` and `data.a` (for the verbs of
/// the other files).
pub(crate) fn load(
    func: &'static str,
    model: &Model,
    data: &mut Data,
    q: &Bound<'_, PyAny>,
    vs: &[(&str, &Bound<'_, PyAny>)],
) -> PyResult<()> {
    let c = Call::new(func, model, data)?;
    c.load(data, q, vs)
}

/// A matrix as a fresh array, as it is.
fn matrix<'py>(py: Python<'py>, m: &nalgebra::DMatrix<f64>) -> Bound<'py, PyArray2<f64>> {
    array2(py, m.nrows(), m.ncols(), |r, c| m[(r, c)])
}

/// Inverse dynamics `τ = M(q) a + C(q, v) v + g(q)` by the recursive Newton-Euler algorithm
/// (Featherstone 2008, Table 5.1).
/// With `fext`, one external wrench per moving joint, in its joint frame (`(m, f)`; linear first
/// `(f, m)` in Pinocchio's layout), acting on the body: `τ = ID(q, v, a) - Σ J_iᵀ F_i^ext`.
#[pyfunction]
#[pyo3(signature = (model, data, q, v, a, fext = None))]
pub fn rnea<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    a: &Bound<'py, PyAny>,
    fext: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let c = Call::new("rnea", &model, &data)?;
    let d = &mut *data;
    if let Some(f) = fext {
        let f = crate::pinocchio::external_wrenches(c.core, f, c.func)?;
        c.load(d, q, &[("v", v), ("a", a)])?;
        let m = &c.core.model;
        let tau = mb::rnea_with_external(m, &mut d.inner, &d.q, &d.v, &d.a, &f).map_err(c.err())?;
        return Ok(c.core.v_out(py, tau.as_slice()));
    }
    if let Some(tau) = mujoco::rnea(&c, d, q, v, a)? {
        return Ok(array1(py, tau.as_slice()));
    }
    c.load(d, q, &[("v", v), ("a", a)])?;
    let tau = mb::rnea(&c.core.model, &mut d.inner, &d.q, &d.v, &d.a).map_err(c.err())?;
    Ok(c.core.v_out(py, tau.as_slice()))
}

/// Forward dynamics `a = M(q)⁻¹ (τ - C(q, v) v - g(q))` by the articulated-body algorithm
/// (Featherstone 2008, Table 7.1).
/// With `fext` (as in `rnea`): `a = M⁻¹ (τ - C v - g + Σ J_iᵀ F_i^ext)`.
#[pyfunction]
#[pyo3(signature = (model, data, q, v, tau, fext = None))]
pub fn aba<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    tau: &Bound<'py, PyAny>,
    fext: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let c = Call::new("aba", &model, &data)?;
    let d = &mut *data;
    if let Some(f) = fext {
        let f = crate::pinocchio::external_wrenches(c.core, f, c.func)?;
        c.load(d, q, &[("v", v), ("tau", tau)])?;
        let m = &c.core.model;
        let ddq = mb::aba_with_external(m, &mut d.inner, &d.q, &d.v, &d.a, &f).map_err(c.err())?;
        return Ok(c.core.v_out(py, ddq.as_slice()));
    }
    if let Some(ddq) = mujoco::aba(&c, d, q, v, tau)? {
        return Ok(array1(py, ddq.as_slice()));
    }
    c.load(d, q, &[("v", v), ("tau", tau)])?;
    let ddq = mb::aba(&c.core.model, &mut d.inner, &d.q, &d.v, &d.a).map_err(c.err())?;
    Ok(c.core.v_out(py, ddq.as_slice()))
}

/// Nonlinear effects `C(q, v) v + g(q)` (Pinocchio's `nonLinearEffects`).
#[pyfunction]
pub fn nle<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let c = Call::new("nle", &model, &data)?;
    let d = &mut *data;
    if let Some(b) = mujoco::nle(&c, d, q, v)? {
        return Ok(array1(py, b.as_slice()));
    }
    c.load(d, q, &[("v", v)])?;
    let b = mb::nonlinear_effects(&c.core.model, &mut d.inner, &d.q, &d.v).map_err(c.err())?;
    Ok(c.core.v_out(py, b.as_slice()))
}

/// Generalised gravity `g(q)` (Pinocchio's `computeGeneralizedGravity`).
#[pyfunction]
pub fn gravity<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let c = Call::new("gravity", &model, &data)?;
    let d = &mut *data;
    c.load(d, q, &[])?;
    let g = mb::gravity_torques(&c.core.model, &mut d.inner, &d.q).map_err(c.err())?;
    let g = nalgebra::DMatrix::from_column_slice(g.len(), 1, g.as_slice());
    if let Some(g) = mujoco::convert(&c, &d.q, &g, mujoco::Convert::Force) {
        return Ok(array1(py, g.as_slice()));
    }
    Ok(c.core.v_out(py, g.as_slice()))
}

/// The joint-space mass matrix `M(q)`, full and symmetric, by the composite rigid-body algorithm
/// (Featherstone 2008, Table 6.2).
#[pyfunction]
pub fn crba<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let c = Call::new("crba", &model, &data)?;
    let d = &mut *data;
    c.load(d, q, &[])?;
    let m = mb::crba(&c.core.model, &mut d.inner, &d.q).map_err(c.err())?;
    if let Some(m) = mujoco::convert(&c, &d.q, m, mujoco::Convert::Matrix) {
        return Ok(matrix(py, &m));
    }
    Ok(c.core.matrix_out(py, m))
}

/// `M(q)⁻¹`, full and symmetric (Pinocchio's `computeMinverse`).
#[pyfunction]
pub fn minverse<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let c = Call::new("minverse", &model, &data)?;
    let d = &mut *data;
    c.load(d, q, &[])?;
    let m = mb::compute_minverse(&c.core.model, &mut d.inner, &d.q).map_err(c.err())?;
    if let Some(m) = mujoco::convert(&c, &d.q, m, mujoco::Convert::Inverse) {
        return Ok(matrix(py, &m));
    }
    Ok(c.core.matrix_out(py, m))
}

/// The Coriolis matrix `C(q, v)`: `C v` the Coriolis and centrifugal torques, `Ṁ - 2C` skew
/// (Pinocchio's `computeCoriolisMatrix`).
#[pyfunction]
pub fn coriolis_matrix<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let c = Call::new("coriolis_matrix", &model, &data)?;
    let d = &mut *data;
    c.load(d, q, &[("v", v)])?;
    let m = mb::coriolis_matrix(&c.core.model, &mut d.inner, &d.q, &d.v).map_err(c.err())?;
    Ok(c.core.matrix_out(py, m))
}

/// Forward kinematics: the world pose of every joint (then `data.placement(name)`), and with
/// `v` (and `a`) the body twists (and accelerations).
#[pyfunction]
#[pyo3(signature = (model, data, q, v = None, a = None))]
pub fn forward_kinematics<'py>(
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: Option<&Bound<'py, PyAny>>,
    a: Option<&Bound<'py, PyAny>>,
) -> PyResult<()> {
    let c = Call::new("forward_kinematics", &model, &data)?;
    let d = &mut *data;
    let m = &c.core.model;
    match (v, a) {
        (Some(v), Some(a)) => {
            c.load(d, q, &[("v", v), ("a", a)])?;
            mb::forward_kinematics(m, &mut d.inner, &d.q, &d.v, &d.a)
        }
        (Some(v), None) => {
            c.load(d, q, &[("v", v)])?;
            mb::forward_kinematics_qv(m, &mut d.inner, &d.q, &d.v)
        }
        (None, None) => {
            c.load(d, q, &[])?;
            mb::forward_kinematics_q(m, &mut d.inner, &d.q)
        }
        (None, Some(_)) => {
            return Err(PyValueError::new_err(
                "forward_kinematics: a given without v",
            ))
        }
    }
    .map_err(c.err())
}

pub(crate) fn reference_frame(frame: &Bound<'_, PyAny>) -> PyResult<ReferenceFrame> {
    // a string, or an enum value with a `name` (Pinocchio's `pin.ReferenceFrame.LOCAL`)
    let name: String = match frame.extract::<String>() {
        Ok(s) => s,
        Err(_) => frame.getattr("name")?.extract()?,
    };
    name.parse()
        .map_err(|e: String| PyValueError::new_err(format!("jacobian: {e}")))
}

/// The Jacobian (6 × nv) of a joint's frame or a named frame, `V = J v`: in `frame`
/// `"world_aligned"` (the angular velocity and the velocity of the frame's origin, world axes),
/// `"body"` (the frame's body twist) or `"spatial"` (the spatial twist, world frame).
#[pyfunction]
#[pyo3(signature = (model, data, q, name, frame = None))]
pub fn jacobian<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    name: &str,
    frame: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let c = Call::new("jacobian", &model, &data)?;
    let rf = frame.map_or(Ok(ReferenceFrame::WorldAligned), reference_frame)?;
    let place = c.core.lookup(c.func, name)?;
    let d = &mut *data;
    c.load(d, q, &[])?;
    let m = &c.core.model;
    let j = match place {
        Place::Joint(j) => mb::joint_jacobian(m, &mut d.inner, &d.q, j, rf),
        Place::Frame(f) => mb::frame_jacobian(m, &mut d.inner, &d.q, f, rf),
    }
    .map_err(c.err())?;
    if let Some(j) = mujoco::convert(&c, &d.q, j, mujoco::Convert::Jacobian) {
        return Ok(matrix(py, &j));
    }
    Ok(c.core.jacobian_out(py, j))
}

/// The centre of mass of the moving bodies in the world (m; Pinocchio's `centerOfMass`).
#[pyfunction]
pub fn com<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let c = Call::new("com", &model, &data)?;
    let d = &mut *data;
    c.load(d, q, &[])?;
    let x = mb::center_of_mass(&c.core.model, &mut d.inner, &d.q).map_err(c.err())?;
    Ok(array1(py, &[x.x, x.y, x.z]))
}

/// Kinetic energy `½ vᵀ M(q) v` (J; Pinocchio's `computeKineticEnergy`).
#[pyfunction]
pub fn kinetic_energy(
    model: PyRef<'_, Model>,
    mut data: PyRefMut<'_, Data>,
    q: &Bound<'_, PyAny>,
    v: &Bound<'_, PyAny>,
) -> PyResult<f64> {
    let c = Call::new("kinetic_energy", &model, &data)?;
    let d = &mut *data;
    if let Some(k) = mujoco::kinetic_energy(&c, d, q, v)? {
        return Ok(k);
    }
    c.load(d, q, &[("v", v)])?;
    mb::kinetic_energy(&c.core.model, &mut d.inner, &d.q, &d.v).map_err(c.err())
}

/// Potential energy `-Σ mᵢ gᵀ cᵢ` (J, zero at the world origin; Pinocchio's
/// `computePotentialEnergy`).
#[pyfunction]
pub fn potential_energy(
    model: PyRef<'_, Model>,
    mut data: PyRefMut<'_, Data>,
    q: &Bound<'_, PyAny>,
) -> PyResult<f64> {
    let c = Call::new("potential_energy", &model, &data)?;
    let d = &mut *data;
    c.load(d, q, &[])?;
    mb::potential_energy(&c.core.model, &mut d.inner, &d.q).map_err(c.err())
}

/// Two vectors returned together.
type Pair<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// Forward dynamics under constraints given by their Jacobian `J` (m x nv, columns in the
/// model's layout) and drift `γ`: `q̈` and `λ` with `M q̈ + c + g = τ + Jᵀ λ` and
/// `J q̈ + γ = −damping λ` (Featherstone's range-space method, as Pinocchio's
/// `forwardDynamics(model, data, q, v, tau, J, gamma, damping)`). Returns `(q̈, λ)`; `q̈` also
/// in `data.ddq`.
#[pyfunction]
#[pyo3(signature = (model, data, q, v, tau, J, gamma, damping = 0.0))]
#[allow(clippy::too_many_arguments, non_snake_case)]
pub fn jacobian_dynamics<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    tau: &Bound<'py, PyAny>,
    J: &Bound<'py, PyAny>,
    gamma: &Bound<'py, PyAny>,
    damping: f64,
) -> PyResult<Pair<'py>> {
    let c = Call::new("jacobian_dynamics", &model, &data)?;
    let d = &mut *data;
    c.load(d, q, &[("v", v), ("tau", tau)])?;
    let (jac, gamma) = constraint_rows(&c, J, gamma)?;
    let m = &c.core.model;
    let lambda = mb::constraints::jacobian_dynamics(
        m,
        &mut d.inner,
        &d.q,
        &d.v,
        &d.a,
        &jac,
        &gamma,
        damping,
    )
    .map_err(|e| value_error(c.func, e))?;
    Ok((
        c.core.v_out(py, d.inner.ddq.as_slice()),
        array1(py, lambda.as_slice()),
    ))
}

/// [`jacobian_dynamics`] on the mass matrix and bias of the last `crba` and `nle` on `data`
/// (Pinocchio's `forwardDynamics(model, data, tau, J, gamma, damping)` after
/// `computeAllTerms`). Returns `(q̈, λ)`; `q̈` also in `data.ddq`.
#[pyfunction]
#[pyo3(signature = (model, data, tau, J, gamma, damping = 0.0))]
#[allow(non_snake_case)]
pub fn jacobian_dynamics_from_terms<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    tau: &Bound<'py, PyAny>,
    J: &Bound<'py, PyAny>,
    gamma: &Bound<'py, PyAny>,
    damping: f64,
) -> PyResult<Pair<'py>> {
    let c = Call::new("jacobian_dynamics_from_terms", &model, &data)?;
    let d = &mut *data;
    let x = c.v(tau, "tau")?;
    c.core.v_into(&x, &mut d.a, c.func, "tau")?;
    let (jac, gamma) = constraint_rows(&c, J, gamma)?;
    let m = &c.core.model;
    let lambda =
        mb::constraints::jacobian_dynamics_from_terms(m, &mut d.inner, &d.a, &jac, &gamma, damping)
            .map_err(|e| value_error(c.func, e))?;
    Ok((
        c.core.v_out(py, d.inner.ddq.as_slice()),
        array1(py, lambda.as_slice()),
    ))
}

/// `J` (its columns from the model's layout into rigid's) and `γ`, checked against each other.
#[allow(non_snake_case)]
fn constraint_rows(
    c: &Call<'_>,
    J: &Bound<'_, PyAny>,
    gamma: &Bound<'_, PyAny>,
) -> PyResult<(nalgebra::DMatrix<f64>, Vec<f64>)> {
    let nv = c.core.nv();
    let rows = convert::matrix(J, c.func, "J", "nv", nv)?;
    let m = rows.rows;
    let gamma = vector(gamma, c.func, "gamma", "the rows of J", m)?;
    let mut jac = nalgebra::DMatrix::zeros(m, nv);
    let mut row = Vec::with_capacity(nv);
    for (r, x) in rows.as_slice().chunks_exact(nv.max(1)).take(m).enumerate() {
        let name = format!("J[{r}]");
        c.core
            .v_into(&Vector::Owned(x.to_vec()), &mut row, c.func, &name)?;
        for (k, &x) in row.iter().enumerate() {
            jac[(r, k)] = x;
        }
    }
    Ok((jac, gamma.as_slice().to_vec()))
}
