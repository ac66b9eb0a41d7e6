//! Identification of inertial parameters (see `rigid::identification`): the joint-torque
//! regressor (Pinocchio's `computeJointTorqueRegressor`), the model's parameter vector, an
//! exciting trajectory, and the estimate from samples (least squares on the base parameters,
//! and the physically consistent semidefinite program when the module is built with `sdp`).
//!
//! Parameters come ten per body, `(m, m cx, m cy, m cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz)` about the
//! body's joint frame (Pinocchio's `toDynamicParameters` order), bodies in the model's joint
//! order (the same in both layouts); rows of the regressor are in the model's velocity layout.

use crate::batch::{check_finite, inputs};
use crate::convert::{array1, array2, io_error, rows_array, value_error, vector};
use crate::model::{Data, Model, ModelCore};
use numpy::PyArray2;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rigid::identification::excitation::{optimize, ExcitationOptions};
use rigid::identification::{
    model_parameters, Estimate, Identification, JointTerms, PhysicalOptions, Regressor, Samples,
    Weighting,
};
use rigid::mass::Consistency;

/// `Y(q, v, a)` (`nv × 10·nb`) with `τ = Y π` (`π`: [`dynamic_parameters`]), gravity included.
#[pyfunction]
pub fn regressor<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    mut data: PyRefMut<'py, Data>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    a: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let func = "regressor";
    let core = &*model.inner;
    crate::dynamics::load(func, &model, &mut data, q, &[("v", v), ("a", a)])?;
    let d = &*data;
    let mut reg = Regressor::new(&core.model);
    let y = reg
        .compute(&core.model, &d.q, &d.v, &d.a)
        .map_err(|e| value_error(func, e))?;
    Ok(array2(py, y.nrows(), y.ncols(), |r, c| {
        y[(core.v_index(r), c)]
    }))
}

/// The model's inertial parameters `π` (`10·nb`), ten per body.
#[pyfunction]
pub fn dynamic_parameters<'py>(py: Python<'py>, model: PyRef<'py, Model>) -> Bound<'py, PyAny> {
    array1(py, model_parameters(&model.inner.model).as_slice()).into_any()
}

/// An exciting trajectory for identification: a finite Fourier series per joint within the
/// joint limits, optimised for the condition number of the base regressor.
#[pyfunction]
#[pyo3(signature = (model, duration = 10.0, rate = 100.0, harmonics = 5, iterations = 300,
                    friction = false, seed = 1, out = None))]
#[allow(clippy::too_many_arguments)]
pub fn excite<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    duration: f64,
    rate: f64,
    harmonics: usize,
    iterations: usize,
    friction: bool,
    seed: u64,
    out: Option<std::path::PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let func = "excite";
    for (name, x) in [("duration", duration), ("rate", rate)] {
        if !(x.is_finite() && x > 0.0) {
            return Err(value_error(
                func,
                format!("{name} must be positive, got {x}"),
            ));
        }
    }
    if harmonics == 0 || iterations == 0 {
        return Err(value_error(
            func,
            "harmonics and iterations must be at least 1",
        ));
    }
    let core = &*model.inner;
    let opts = ExcitationOptions {
        duration,
        harmonics,
        iterations,
        terms: JointTerms {
            friction,
            rotor_inertia: false,
        },
        seed,
        ..ExcitationOptions::default()
    };
    let (traj, cond) = py
        .detach(|| optimize(&core.model, &opts))
        .map_err(|e| value_error(func, e))?;
    let s = traj
        .samples(&core.model, 1.0 / rate)
        .map_err(|e| value_error(func, e))?;
    if let Some(path) = &out {
        std::fs::write(path, s.to_csv(&core.model))
            .map_err(|e| io_error(&e, format!("{func}: cannot write {}: {e}", path.display())))?;
    }
    let dict = samples_dict(py, core, &s)?;
    dict.set_item("condition_number", cond)?;
    Ok(dict)
}

/// `{t, q, v, a, tau}` of samples, rows in the model's layout.
fn samples_dict<'py>(
    py: Python<'py>,
    core: &ModelCore,
    s: &Samples,
) -> PyResult<Bound<'py, PyDict>> {
    let (n, nq, nv) = (s.len(), core.model.nq(), core.nv());
    let d = PyDict::new(py);
    d.set_item("t", array1(py, &s.t))?;
    let q: Vec<f64> =
        s.q.chunks_exact(nq.max(1))
            .flat_map(|q| core.q_to_layout(q))
            .collect();
    d.set_item("q", rows_array(py, q, n, core.nq())?)?;
    for (name, x) in [("v", &s.v), ("a", &s.a), ("tau", &s.tau)] {
        let rows: Vec<f64> = x
            .chunks_exact(nv.max(1))
            .flat_map(|r| core.v_to_layout(r))
            .collect();
        d.set_item(name, rows_array(py, rows, n, nv)?)?;
    }
    Ok(d)
}

/// The samples of `identify`: a CSV file (a path) or a dict of arrays.
fn read_samples(core: &ModelCore, samples: &Bound<'_, PyAny>, window: f64) -> PyResult<Samples> {
    let func = "identify";
    if let Ok(d) = samples.cast::<PyDict>() {
        let get = |k: &str| -> PyResult<Bound<'_, PyAny>> {
            d.get_item(k)?.ok_or_else(|| {
                PyValueError::new_err(format!(
                    "{func}: the samples need the key \"{k}\" (t, q, v, a, tau: one row per sample)"
                ))
            })
        };
        let (q, v, a, tau) = (get("q")?, get("v")?, get("a")?, get("tau")?);
        let args = [("v", &v), ("a", &a), ("tau", &tau)];
        let (n, q, mut rest) = inputs(core, None, func, &q, &args, true)?;
        check_finite(core, func, &args)?;
        let t = vector(&get("t")?, func, "samples[\"t\"]", "the rows of q", n)?;
        let (tau, a, v) = (
            rest.pop().unwrap(),
            rest.pop().unwrap(),
            rest.pop().unwrap(),
        );
        return Ok(Samples {
            t: t.as_slice().to_vec(),
            q: q.into_vec(),
            v: v.into_vec(),
            a: a.into_vec(),
            tau: tau.into_vec(),
        });
    }
    let path: std::path::PathBuf = samples.extract().map_err(|_| {
        pyo3::exceptions::PyTypeError::new_err(format!(
            "{func}: samples must be a CSV file (a path) or a dict of arrays t, q, v, a, tau"
        ))
    })?;
    let text = std::fs::read_to_string(&path)
        .map_err(|e| io_error(&e, format!("{func}: cannot read {}: {e}", path.display())))?;
    Samples::from_csv(&core.model, &text, Some(window))
        .map_err(|e| value_error(func, format!("{}: {e}", path.display())))
}

fn estimate_dict<'py>(
    py: Python<'py>,
    id: &Identification,
    e: &Estimate,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("base", array1(py, e.base.as_slice()))?;
    d.set_item("base_std", array1(py, e.base_std.as_slice()))?;
    d.set_item("parameters", array1(py, e.parameters.as_slice()))?;
    d.set_item("residual_rms", e.residual_rms)?;
    d.set_item("residual_rms_per_dof", array1(py, &e.residual_rms_per_dof))?;
    d.set_item("relative_residual", e.relative_residual)?;
    d.set_item("condition_number", e.condition_number)?;
    let consistent: Vec<bool> = id
        .layout
        .body_inertias(e.parameters.as_slice())
        .iter()
        .map(|g| Consistency::of(g).is_consistent())
        .collect();
    d.set_item("consistent", consistent)?;
    Ok(d)
}

/// The inertial parameters of `model` from measured motion.
#[pyfunction]
#[pyo3(signature = (model, samples, physical = false, friction = false, rotor_inertia = false,
                    weighted = false, regularization = 1e-4, mass_tolerance = None,
                    window = 0.05))]
#[allow(clippy::too_many_arguments)]
pub fn identify<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    samples: &Bound<'py, PyAny>,
    physical: bool,
    friction: bool,
    rotor_inertia: bool,
    weighted: bool,
    regularization: f64,
    mass_tolerance: Option<f64>,
    window: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let func = "identify";
    if !(window.is_finite() && window > 0.0) {
        return Err(value_error(
            func,
            format!("window must be positive, got {window}"),
        ));
    }
    if let Some(f) = mass_tolerance {
        if !(f.is_finite() && (0.0..1.0).contains(&f)) {
            return Err(value_error(
                func,
                format!("mass_tolerance must be in [0, 1), got {f}"),
            ));
        }
        if !physical {
            return Err(value_error(
                func,
                "mass_tolerance bounds the physically consistent estimate: add physical=True",
            ));
        }
    }
    let core = &*model.inner;
    let s = read_samples(core, samples, window)?;
    let terms = JointTerms {
        friction,
        rotor_inertia,
    };
    let err = |e| value_error(func, e);
    let (id, prior, ls, pc) = py
        .detach(|| {
            let id = Identification::new(&core.model, &s, terms)?;
            let weighting = if weighted {
                Weighting::PerJoint
            } else {
                Weighting::None
            };
            let ls = id.least_squares(weighting)?;
            let prior = id.evaluate(&id.prior)?;
            let pc = if physical {
                let opts = PhysicalOptions {
                    regularization,
                    mass_bounds: mass_tolerance
                        .map(|f| PhysicalOptions::mass_bounds_within(&core.model, f)),
                    ..PhysicalOptions::default()
                };
                Some(id.physically_consistent(&opts)?)
            } else {
                None
            };
            Ok::<_, rigid::identification::IdentificationError>((id, prior, ls, pc))
        })
        .map_err(err)?;
    let d = PyDict::new(py);
    d.set_item("samples", id.samples())?;
    d.set_item("parameter_names", id.base.names.clone())?;
    let exprs: Vec<String> = (0..id.base.len()).map(|i| id.base.expression(i)).collect();
    d.set_item("base_parameters", exprs)?;
    d.set_item("model_values", estimate_dict(py, &id, &prior)?)?;
    d.set_item("least_squares", estimate_dict(py, &id, &ls)?)?;
    match &pc {
        Some(p) => d.set_item("physical", estimate_dict(py, &id, p)?)?,
        None => d.set_item("physical", py.None())?,
    }
    Ok(d)
}
