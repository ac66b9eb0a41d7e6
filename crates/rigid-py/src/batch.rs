//! Many states at once, on every core, with the GIL released: `rnea_batch`, `aba_batch`,
//! `crba_batch`, `rnea_derivatives_batch` over `(N, nq)` / `(N, nv)` arrays (rigid's
//! `multibody::batch`: several states side by side in SIMD lanes). Each state's result is that
//! of the single call to round-off, and the same bits for any number of threads.

use crate::convert::{matrix, rows_array, value_error, Matrix};
use crate::model::{Model, ModelCore};
use numpy::{PyArray2, PyArray3, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rigid::multibody::{self as mb, batch, Data};

/// The states in rigid's layout: the caller's rows, or converted rows.
fn q_rows(core: &ModelCore, func: &str, name: &str, x: &Matrix<'_>) -> PyResult<Vec<f64>> {
    let (nq, nq_r) = (core.nq(), core.model.nq());
    if let Some(l) = &core.mujoco {
        let mut out = vec![0.0; x.rows * nq_r];
        for (k, (src, dst)) in x
            .as_slice()
            .chunks_exact(nq)
            .zip(out.chunks_exact_mut(nq_r))
            .enumerate()
        {
            l.q_from_mujoco(src, dst)
                .map_err(|e| value_error(func, format!("{name}[{k}]: {e}")))?;
        }
        return Ok(out);
    }
    let l = core.layout.as_ref().filter(|_| core.convert_q);
    let Some(l) = l else {
        return Ok(x.as_slice().to_vec());
    };
    let mut out = vec![0.0; x.rows * nq_r];
    for (k, (src, dst)) in x
        .as_slice()
        .chunks_exact(nq)
        .zip(out.chunks_exact_mut(nq_r))
        .enumerate()
    {
        l.q_from_pinocchio(src, dst)
            .map_err(|e| value_error(func, format!("{name}[{k}]: {e}")))?;
    }
    Ok(out)
}

/// Velocity-space rows (`V`, `A`, `TAU`, results) permuted between the layouts.
fn permute_rows(core: &ModelCore, x: &mut [f64]) {
    let Some(l) = core.layout.as_ref().filter(|_| core.convert_v) else {
        return;
    };
    let nv = core.nv();
    let mut row = vec![0.0; nv];
    for r in x.chunks_exact_mut(nv) {
        l.permute_v(r, &mut row);
        r.copy_from_slice(&row);
    }
}

fn v_rows(core: &ModelCore, x: &Matrix<'_>) -> Vec<f64> {
    let mut out = x.as_slice().to_vec();
    permute_rows(core, &mut out);
    out
}

/// The inputs of a batch call: `Q` and the velocity-space arrays, checked and in rigid's layout.
pub(crate) fn inputs(
    core: &ModelCore,
    func: &str,
    q: &Bound<'_, PyAny>,
    vs: &[(&str, &Bound<'_, PyAny>)],
) -> PyResult<(usize, Vec<f64>, Vec<Vec<f64>>)> {
    if core.mujoco_free().is_some() {
        return Err(value_error(
            func,
            "not available in the mujoco layout for a model with a free joint (its velocity map \
             depends on q); use layout=\"rigid\""
                .to_string(),
        ));
    }
    crate::scale::refuse_dask(func, "Q", q)?;
    for (name, x) in vs {
        crate::scale::refuse_dask(func, name, x)?;
    }
    let qm = matrix(q, func, "Q", "nq", core.nq())?;
    let n = qm.rows;
    let mut out = Vec::with_capacity(vs.len());
    for (name, x) in vs {
        let m = matrix(x, func, name, "nv", core.nv())?;
        if m.rows != n {
            return Err(PyValueError::new_err(format!(
                "{func}: {name} has {} rows, Q has {n} (one state per row)",
                m.rows
            )));
        }
        let cols = core.nv().max(1);
        if let Some(i) = m.as_slice().iter().position(|x| !x.is_finite()) {
            return Err(value_error(
                func,
                format!("{name}[{}, {}] is not finite", i / cols, i % cols),
            ));
        }
        out.push(v_rows(core, &m));
    }
    Ok((n, q_rows(core, func, "Q", &qm)?, out))
}

/// The first failing state's error, with its row (the batch error does not say which state).
fn state_error(
    core: &ModelCore,
    func: &str,
    e: mb::MultibodyError,
    qs: &[f64],
    check: impl Fn(&mut Data, usize, &[f64]) -> Result<(), mb::MultibodyError>,
) -> PyErr {
    let nq = core.model.nq();
    let mut data = Data::new(&core.model);
    for (k, q) in qs.chunks_exact(nq).enumerate() {
        if let Err(e) = check(&mut data, k, q) {
            return value_error(func, format!("state {k} (row {k} of the inputs): {e}"));
        }
    }
    value_error(func, e)
}

/// The two `(q, v, x) ↦ nv-vector` verbs.
#[derive(Clone, Copy)]
enum Qvx {
    Rnea,
    Aba,
}

impl Qvx {
    fn batch(self, m: &mb::Model, q: &[f64], v: &[f64], x: &[f64], out: &mut [f64]) -> MbResult {
        match self {
            Self::Rnea => batch::rnea_batch(m, q, v, x, out),
            Self::Aba => batch::aba_batch(m, q, v, x, out),
        }
    }

    fn single(self, m: &mb::Model, d: &mut Data, q: &[f64], v: &[f64], x: &[f64]) -> MbResult {
        match self {
            Self::Rnea => mb::rnea(m, d, q, v, x).map(|_| ()),
            Self::Aba => mb::aba(m, d, q, v, x).map(|_| ()),
        }
    }
}

type MbResult = Result<(), mb::MultibodyError>;

/// `f(Q[k], V[k], X[k])` for every row `k` (`args`: the names and values of `V` and `X`).
fn qvx_batch<'py>(
    model: &Model,
    func: &'static str,
    f: Qvx,
    q: &Bound<'py, PyAny>,
    args: [(&str, &Bound<'py, PyAny>); 2],
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let py = q.py();
    let pool = crate::scale::pool(func, threads)?;
    let core = &*model.inner;
    let (n, qs, vx) = inputs(core, func, q, &args)?;
    let nv = core.nv();
    let mut out = vec![0.0; n * nv];
    let (vs, xs) = (&vx[0], &vx[1]);
    crate::scale::detach(py, pool.as_deref(), || {
        f.batch(&core.model, &qs, vs, xs, &mut out)
    })
    .map_err(|e| {
        state_error(core, func, e, &qs, |d, k, q| {
            let r = k * nv..(k + 1) * nv;
            f.single(&core.model, d, q, &vs[r.clone()], &xs[r])
        })
    })?;
    permute_rows(core, &mut out);
    rows_array(py, out, n, nv)
}

/// Inverse dynamics for every row: `TAU[k] = rnea(Q[k], V[k], A[k])`, an `(N, nv)` array, on
/// `threads` threads (None: every core).
#[pyfunction]
#[pyo3(signature = (model, q, v, a, *, threads = None))]
pub fn rnea_batch<'py>(
    model: PyRef<'py, Model>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    a: &Bound<'py, PyAny>,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    qvx_batch(
        &model,
        "rnea_batch",
        Qvx::Rnea,
        q,
        [("V", v), ("A", a)],
        threads,
    )
}

/// Forward dynamics for every row: `DDQ[k] = aba(Q[k], V[k], TAU[k])`, an `(N, nv)` array, on
/// `threads` threads (None: every core).
#[pyfunction]
#[pyo3(signature = (model, q, v, tau, *, threads = None))]
pub fn aba_batch<'py>(
    model: PyRef<'py, Model>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    tau: &Bound<'py, PyAny>,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    qvx_batch(
        &model,
        "aba_batch",
        Qvx::Aba,
        q,
        [("V", v), ("TAU", tau)],
        threads,
    )
}

/// The mass matrix for every row: `M[k] = crba(Q[k])`, an `(N, nv, nv)` array, on `threads`
/// threads (None: every core).
#[pyfunction]
#[pyo3(signature = (model, q, *, threads = None))]
pub fn crba_batch<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    q: &Bound<'py, PyAny>,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    const F: &str = "crba_batch";
    let pool = crate::scale::pool(F, threads)?;
    let core = &*model.inner;
    let (n, qs, _) = inputs(core, F, q, &[])?;
    let nv = core.nv();
    let mut out = vec![0.0; n * nv * nv];
    crate::scale::detach(py, pool.as_deref(), || {
        batch::crba_batch(&core.model, &qs, &mut out)
    })
    .map_err(|e| {
        state_error(core, F, e, &qs, |d, _, q| {
            mb::crba(&core.model, d, q).map(|_| ())
        })
    })?;
    permute_matrices(core, &mut out);
    numpy::PyArray1::from_vec(py, out).reshape([n, nv, nv])
}

/// Each state's `nv x nv` blocks of `out` in the model's velocity layout:
/// `X_pin[r][c] = X[p(r)][p(c)]`.
fn permute_matrices(core: &ModelCore, out: &mut [f64]) {
    let Some(l) = core.layout.as_ref().filter(|_| core.convert_v) else {
        return;
    };
    let nv = core.nv();
    let mut m = vec![0.0; nv * nv];
    for block in out.chunks_exact_mut(nv * nv) {
        m.copy_from_slice(block);
        l.permute_matrix(&m, block);
    }
}

/// `N` matrices, `(N, rows, cols)`.
type Matrices<'py> = Bound<'py, PyArray3<f64>>;

/// The derivatives of inverse dynamics for every row: `(∂τ/∂q, ∂τ/∂v)` at `(Q[k], V[k], A[k])`,
/// two `(N, nv, nv)` arrays, on `threads` threads (None: every core).
#[pyfunction]
#[pyo3(signature = (model, q, v, a, *, threads = None))]
pub fn rnea_derivatives_batch<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    a: &Bound<'py, PyAny>,
    threads: Option<i64>,
) -> PyResult<(Matrices<'py>, Matrices<'py>)> {
    const F: &str = "rnea_derivatives_batch";
    let pool = crate::scale::pool(F, threads)?;
    let core = &*model.inner;
    let (n, qs, va) = inputs(core, F, q, &[("V", v), ("A", a)])?;
    let (vs, as_) = (&va[0], &va[1]);
    let nv = core.nv();
    let (mut dq, mut dv) = (vec![0.0; n * nv * nv], vec![0.0; n * nv * nv]);
    crate::scale::detach(py, pool.as_deref(), || {
        batch::rnea_derivatives_batch(&core.model, &qs, vs, as_, &mut dq, &mut dv)
    })
    .map_err(|e| {
        state_error(core, F, e, &qs, |d, k, q| {
            let r = k * nv..(k + 1) * nv;
            mb::rnea_derivatives(&core.model, d, q, &vs[r.clone()], &as_[r]).map(|_| ())
        })
    })?;
    permute_matrices(core, &mut dq);
    permute_matrices(core, &mut dv);
    Ok((
        numpy::PyArray1::from_vec(py, dq).reshape([n, nv, nv])?,
        numpy::PyArray1::from_vec(py, dv).reshape([n, nv, nv])?,
    ))
}
