//! Configurations: `neutral`, `random_configuration` (and `seed`), `integrate`, `difference`,
//! joint by joint on each joint's Lie group, in the model's layout.

use crate::convert::{value_error, vector};
use crate::model::Model;
use numpy::PyArray1;
use pyo3::prelude::*;
use rigid::multibody::{self as mb, Rng};
use std::sync::Mutex;

/// The generator of `random_configuration`, seeded by `seed` (SplitMix64).
static RNG: Mutex<Option<Rng>> = Mutex::new(None);

/// Seed the generator of `random_configuration` (Pinocchio's `pin.seed`).
#[pyfunction]
pub fn seed(seed: u64) {
    *RNG.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner) = Some(Rng::new(seed));
}

/// The neutral configuration: zeros, identity quaternions (and `(cos 0, sin 0) = (1, 0)` in
/// Pinocchio's layout).
#[pyfunction]
pub fn neutral<'py>(py: Python<'py>, model: PyRef<'py, Model>) -> Bound<'py, PyArray1<f64>> {
    let core = &model.inner;
    core.q_out(py, &mb::neutral(&core.model))
}

/// A random configuration within the position limits (angles in `[-π, π]` and translations in
/// `[-1, 1]` m where a limit is infinite; uniform quaternions).
///
/// With `lower` and `upper` (the model's layout, `nq` each): within these bounds instead of the
/// model's limits (Pinocchio's `randomConfiguration(model, lower, upper)`; a continuous joint's
/// `(cos θ, sin θ)` bounds are not used, and `±1e300` or beyond is no bound).
#[pyfunction]
#[pyo3(signature = (model, lower = None, upper = None))]
pub fn random_configuration<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    lower: Option<&Bound<'py, PyAny>>,
    upper: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    const F: &str = "random_configuration";
    let core = &model.inner;
    let bounds = match (lower, upper) {
        (None, None) => None,
        (Some(lo), Some(up)) => Some((
            crate::pinocchio::bounds_to_rigid(core, lo, F, "lower", -1.0)?,
            crate::pinocchio::bounds_to_rigid(core, up, F, "upper", 1.0)?,
        )),
        _ => return Err(value_error(F, "give both lower and upper, or neither")),
    };
    let q = {
        let mut rng = RNG
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let rng = rng.get_or_insert_with(|| {
            // not seeded: from the clock, as Pinocchio without `pin.seed`
            let t = std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_nanos() as u64);
            Rng::new(t)
        });
        match &bounds {
            None => mb::random_configuration(&core.model, rng),
            Some((lo, up)) => mb::random_configuration_within(&core.model, rng, lo, up)
                .map_err(|e| value_error(F, e))?,
        }
    };
    Ok(core.q_out(py, &q))
}

/// `q ⊕ v`: the configuration reached from `q` moving with the constant velocity `v` for one
/// second (Pinocchio's `integrate`).
#[pyfunction]
pub fn integrate<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    const F: &str = "integrate";
    let core = &model.inner;
    let q = vector(q, F, "q", "nq", core.nq())?;
    let v = vector(v, F, "v", "nv", core.nv())?;
    let (mut qr, mut vr) = (Vec::new(), Vec::new());
    core.q_into(&q, &mut qr, F, "q")?;
    core.v_into(&v, &mut vr, F, "v")?;
    let mut out = vec![0.0; core.model.nq()];
    mb::integrate(&core.model, &qr, &vr, 1.0, &mut out).map_err(|e| value_error(F, e))?;
    if let Some(l) = &core.layout {
        l.integrate_signs(&qr, &vr, 1.0, &mut out);
    }
    Ok(core.q_out(py, &out))
}

/// `q1 ⊖ q0`: the velocity `v` with `integrate(q0, v) = q1` (Pinocchio's `difference`).
#[pyfunction]
pub fn difference<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    q0: &Bound<'py, PyAny>,
    q1: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    const F: &str = "difference";
    let core = &model.inner;
    let q0 = vector(q0, F, "q0", "nq", core.nq())?;
    let q1 = vector(q1, F, "q1", "nq", core.nq())?;
    let (mut r0, mut r1) = (Vec::new(), Vec::new());
    core.q_into(&q0, &mut r0, F, "q0")?;
    core.q_into(&q1, &mut r1, F, "q1")?;
    if let Some(l) = &core.layout {
        l.nearest_angles(&r0, &mut r1);
    }
    let mut v = vec![0.0; core.nv()];
    mb::difference(&core.model, &r0, &r1, &mut v).map_err(|e| value_error(F, e))?;
    Ok(core.v_out(py, &v))
}
