//! The verbs of `dynamics` for a model in MuJoCo's layout with a free joint: its velocity map
//! `v = T(q) u` depends on `q` (`rigid::interop::MujocoLayout`), so these verbs convert `q`
//! first and then call the layout's algorithms, which return MuJoCo's `qfrc_bias`, `mj_fullM`,
//! ... Each returns `Ok(None)` when the model is not such a model (the plain path applies).

use super::Call;
use crate::convert::Vector;
use crate::model::Data;
use nalgebra::{DMatrix, DVector};
use pyo3::prelude::*;
use rigid::interop::MujocoLayout;
use rigid::multibody as mb;

/// `q` (rigid's layout, in `d.q`) and the MuJoCo-layout vectors `xs`, checked.
fn inputs<'py>(
    c: &Call<'_>,
    d: &mut Data,
    q: &Bound<'py, PyAny>,
    xs: &[(&str, &Bound<'py, PyAny>)],
) -> PyResult<Vec<Vec<f64>>> {
    let x: Vector<'_> = c.q(q, "q")?;
    c.core.q_into(&x, &mut d.q, c.func, "q")?;
    xs.iter()
        .map(|(name, x)| Ok(c.v(x, name)?.as_slice().to_vec()))
        .collect()
}

fn layout<'a>(c: &Call<'a>) -> Option<&'a MujocoLayout> {
    c.core.mujoco_free()
}

/// `rnea` in MuJoCo's coordinates.
pub(super) fn rnea(
    c: &Call<'_>,
    d: &mut Data,
    q: &Bound<'_, PyAny>,
    v: &Bound<'_, PyAny>,
    a: &Bound<'_, PyAny>,
) -> PyResult<Option<DVector<f64>>> {
    let Some(l) = layout(c) else { return Ok(None) };
    let x = inputs(c, d, q, &[("v", v), ("a", a)])?;
    let m = &c.core.model;
    Ok(Some(
        l.rnea(m, &mut d.inner, &d.q, &x[0], &x[1])
            .map_err(c.err())?,
    ))
}

/// `aba` in MuJoCo's coordinates.
pub(super) fn aba(
    c: &Call<'_>,
    d: &mut Data,
    q: &Bound<'_, PyAny>,
    v: &Bound<'_, PyAny>,
    tau: &Bound<'_, PyAny>,
) -> PyResult<Option<DVector<f64>>> {
    let Some(l) = layout(c) else { return Ok(None) };
    let x = inputs(c, d, q, &[("v", v), ("tau", tau)])?;
    let m = &c.core.model;
    Ok(Some(
        l.aba(m, &mut d.inner, &d.q, &x[0], &x[1])
            .map_err(c.err())?,
    ))
}

/// `qfrc_bias`.
pub(super) fn nle(
    c: &Call<'_>,
    d: &mut Data,
    q: &Bound<'_, PyAny>,
    v: &Bound<'_, PyAny>,
) -> PyResult<Option<DVector<f64>>> {
    let Some(l) = layout(c) else { return Ok(None) };
    let x = inputs(c, d, q, &[("v", v)])?;
    let m = &c.core.model;
    Ok(Some(
        l.nonlinear_effects(m, &mut d.inner, &d.q, &x[0])
            .map_err(c.err())?,
    ))
}

/// The kinetic energy `½ uᵀ M_mj u` (the same as rigid's at `v = T u`).
pub(super) fn kinetic_energy(
    c: &Call<'_>,
    d: &mut Data,
    q: &Bound<'_, PyAny>,
    v: &Bound<'_, PyAny>,
) -> PyResult<Option<f64>> {
    let Some(l) = layout(c) else { return Ok(None) };
    let mut x = inputs(c, d, q, &[("v", v)])?;
    l.v_from_mujoco(&d.q, &mut x[0]);
    let m = &c.core.model;
    Ok(Some(
        mb::kinetic_energy(m, &mut d.inner, &d.q, &x[0]).map_err(c.err())?,
    ))
}

/// A verb's `q`-only result in MuJoCo's coordinates: a generalised force (`Tᵀ g`), the mass
/// matrix (`Tᵀ M T`), its inverse (`T⁻¹ M⁻¹ T⁻ᵀ`) or a Jacobian (`J T`), given `d.q`.
pub(super) enum Convert {
    Force,
    Matrix,
    Inverse,
    Jacobian,
}

/// Converts a rigid-layout result at `q` (rigid's layout) to MuJoCo's coordinates, when the model is
/// in MuJoCo's layout with a free joint; `None` otherwise.
pub(super) fn convert(
    c: &Call<'_>,
    q: &[f64],
    x: &DMatrix<f64>,
    how: Convert,
) -> Option<DMatrix<f64>> {
    let l = layout(c)?;
    Some(match how {
        Convert::Force => {
            let mut y = x.clone();
            l.force_to_mujoco(q, y.as_mut_slice());
            y
        }
        Convert::Matrix => l.matrix_to_mujoco(q, x),
        Convert::Inverse => l.matrix_inverse_to_mujoco(q, x),
        Convert::Jacobian => l.jacobian_to_mujoco(q, x),
    })
}
