//! The analytical derivatives of the dynamics (Carpentier & Mansard, RSS 2018): `rnea_derivatives`
//! (Pinocchio's `computeRNEADerivatives`), `aba_derivatives` (`computeABADerivatives`) and
//! `gravity_derivatives` (`computeGeneralizedGravityDerivatives`). Derivatives with respect to `q`
//! are taken along the tangent perturbation `q ⊕ δ = integrate(q, δ)`, so every matrix is
//! `nv × nv`; in Pinocchio's layout its rows and columns are Pinocchio's.

use crate::convert::value_error;
use crate::model::{Data, Model};
use numpy::PyArray2;
use pyo3::prelude::*;
use rigid::multibody as mb;

type Matrix<'py> = Bound<'py, PyArray2<f64>>;

/// `(∂τ/∂q, ∂τ/∂v, ∂τ/∂a = M)` of inverse dynamics `τ = M(q) a + c(q, v) + g(q)` at `(q, v, a)`.
#[pyfunction]
pub fn rnea_derivatives<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    a: &Bound<'py, PyAny>,
) -> PyResult<(Matrix<'py>, Matrix<'py>, Matrix<'py>)> {
    let func = "rnea_derivatives";
    let core = &*model.inner;
    crate::dynamics::load(func, &model, &mut data, q, &[("v", v), ("a", a)])?;
    let d = &mut *data;
    let r = mb::rnea_derivatives(&core.model, &mut d.inner, &d.q, &d.v, &d.a)
        .map_err(|e| value_error(func, e))?;
    Ok((
        core.matrix_out(py, r.dtau_dq),
        core.matrix_out(py, r.dtau_dv),
        core.matrix_out(py, r.dtau_da),
    ))
}

/// `(∂q̈/∂q, ∂q̈/∂v, ∂q̈/∂τ = M⁻¹)` of forward dynamics `q̈ = M(q)⁻¹ (τ - c(q, v) - g(q))` at
/// `(q, v, τ)`.
#[pyfunction]
pub fn aba_derivatives<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    tau: &Bound<'py, PyAny>,
) -> PyResult<(Matrix<'py>, Matrix<'py>, Matrix<'py>)> {
    let func = "aba_derivatives";
    let core = &*model.inner;
    crate::dynamics::load(func, &model, &mut data, q, &[("v", v), ("tau", tau)])?;
    let d = &mut *data;
    let r = mb::aba_derivatives(&core.model, &mut d.inner, &d.q, &d.v, &d.a)
        .map_err(|e| value_error(func, e))?;
    Ok((
        core.matrix_out(py, r.dqdd_dq),
        core.matrix_out(py, r.dqdd_dv),
        core.matrix_out(py, r.dqdd_dtau),
    ))
}

/// `∂g/∂q` of the generalised gravity `g(q)`.
#[pyfunction]
pub fn gravity_derivatives<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
) -> PyResult<Matrix<'py>> {
    let func = "gravity_derivatives";
    let core = &*model.inner;
    crate::dynamics::load(func, &model, &mut data, q, &[])?;
    let d = &mut *data;
    let g = mb::gravity_derivatives(&core.model, &mut d.inner, &d.q)
        .map_err(|e| value_error(func, e))?;
    Ok(core.matrix_out(py, g))
}
