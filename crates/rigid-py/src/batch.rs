//! Many states at once, on every core, with the GIL released: `rnea_batch`, `aba_batch`,
//! `crba_batch`, `rnea_derivatives_batch` over `(N, nq)` / `(N, nv)` arrays (rigid's
//! `multibody::batch`: several states side by side in SIMD lanes). Each state's result is that
//! of the single call bit for bit, for any number of threads.
//!
//! Contiguous float64 inputs are read in place ([`Matrix`]); results are written straight into
//! arrays numpy allocates (numpy asks Linux for huge pages for large arrays: the first touch of
//! a fresh Rust vector's 4 KiB pages cost about 3 µs per page on this machine, more than CRBA
//! itself), kept for the next call when nothing refers to them any more ([`crate::outputs`]),
//! or into the caller's `out=`. In Pinocchio's layout the velocity-space numbers are
//! reordered by the library, a chunk of states at a time: the inputs into a buffer of each task,
//! the results in place ([`Batch::with_velocity_order`]).

use crate::convert::{matrix, value_error, Matrix};
use crate::model::{Model, ModelCore};
use numpy::{PyArray2, PyArray3, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rayon::prelude::*;
use rayon::ThreadPool;
use rigid::multibody::batch::Batch;
use rigid::multibody::{self as mb, Data};

/// A batch input in rigid's layout: the caller's array, read in place when it is a C-contiguous
/// float64 array already in that layout (no copy: see [`Matrix`] on reading it with the GIL
/// released), or its rows converted.
pub(crate) enum Rows<'py> {
    /// The caller's numbers.
    Caller(Matrix<'py>),
    /// The rows converted between the layouts.
    Converted(Vec<f64>),
}

impl Rows<'_> {
    /// The numbers, row-major.
    pub(crate) fn as_slice(&self) -> &[f64] {
        match self {
            Self::Caller(m) => m.as_slice(),
            Self::Converted(v) => v,
        }
    }

    /// The numbers, owned.
    pub(crate) fn into_vec(self) -> Vec<f64> {
        match self {
            Self::Caller(m) => m.as_slice().to_vec(),
            Self::Converted(v) => v,
        }
    }
}

/// The states in rigid's layout: the caller's rows, or converted rows.
fn q_rows<'py>(core: &ModelCore, func: &str, name: &str, x: Matrix<'py>) -> PyResult<Rows<'py>> {
    if let Some(l) = &core.mujoco {
        return converted(core, func, name, &x, |s, d| {
            l.q_from_mujoco(s, d).map_err(|e| e.to_string())
        });
    }
    match core.layout.as_ref().filter(|_| core.convert_q) {
        Some(l) => converted(core, func, name, &x, |s, d| {
            l.q_from_pinocchio(s, d).map_err(|e| e.to_string())
        }),
        None => Ok(Rows::Caller(x)),
    }
}

/// Each row of `x` (`nq` in the model's layout) converted into rigid's by `f`.
fn converted<'py>(
    core: &ModelCore,
    func: &str,
    name: &str,
    x: &Matrix<'_>,
    f: impl Fn(&[f64], &mut [f64]) -> Result<(), String>,
) -> PyResult<Rows<'py>> {
    let (nq, nq_r) = (core.nq(), core.model.nq());
    let mut out = vec![0.0; x.rows * nq_r];
    let rows = x
        .as_slice()
        .chunks_exact(nq)
        .zip(out.chunks_exact_mut(nq_r));
    for (k, (src, dst)) in rows.enumerate() {
        f(src, dst).map_err(|e| value_error(func, format!("{name}[{k}]: {e}")))?;
    }
    Ok(Rows::Converted(out))
}

/// States per parallel chunk when [`v_rows`] permutes velocity rows between the layouts.
const CHUNK: usize = 256;

/// `x` in rigid's velocity layout: the caller's rows, or their permutation (on `pool`).
fn v_rows<'py>(core: &ModelCore, pool: Option<&ThreadPool>, x: Matrix<'py>) -> Rows<'py> {
    let Some(l) = core.layout.as_ref().filter(|_| core.convert_v) else {
        return Rows::Caller(x);
    };
    let (nv, src) = (core.nv().max(1), x.as_slice());
    let mut out = vec![0.0; src.len()];
    crate::scale::on(pool, || {
        out.par_chunks_mut(nv * CHUNK)
            .zip(src.par_chunks(nv * CHUNK))
            .for_each(|(o, s)| {
                for (o, s) in o.chunks_exact_mut(nv).zip(s.chunks_exact(nv)) {
                    l.permute_v(s, o);
                }
            });
    });
    Rows::Converted(out)
}

/// The first non-finite entry of the velocity-space arrays `vs` (`(N, nv)`, in the caller's
/// layout), as an error naming its row and column. The batch kernels refuse such states
/// themselves, so a caller whose kernel reads its inputs unchanged looks here only when the
/// kernel fails, which spares a pass over all of them on the way in.
pub(crate) fn check_finite(
    core: &ModelCore,
    func: &str,
    vs: &[(&str, &Bound<'_, PyAny>)],
) -> PyResult<()> {
    let cols = core.nv().max(1);
    for (name, x) in vs {
        let m = matrix(x, func, name, "nv", core.nv())?;
        if let Some(i) = mb::first_non_finite(m.as_slice()) {
            return Err(value_error(
                func,
                format!("{name}[{}, {}] is not finite", i / cols, i % cols),
            ));
        }
    }
    Ok(())
}

/// The inputs of a batch call: `Q` and the velocity-space arrays, their shapes checked (their
/// entries by [`check_finite`] or the kernel) and in rigid's layout (the velocity-space arrays
/// left in the model's when not `permute`: the caller permutes them).
pub(crate) fn inputs<'py>(
    core: &ModelCore,
    pool: Option<&ThreadPool>,
    func: &str,
    q: &Bound<'py, PyAny>,
    vs: &[(&str, &Bound<'py, PyAny>)],
    permute: bool,
) -> PyResult<(usize, Rows<'py>, Vec<Rows<'py>>)> {
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
        out.push(if permute {
            v_rows(core, pool, m)
        } else {
            Rows::Caller(m)
        });
    }
    Ok((n, q_rows(core, func, "Q", qm)?, out))
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

/// Workspaces for the model (on the current pool's threads) taking and giving velocities in
/// the model's layout: the library reorders them a chunk at a time
/// ([`Batch::with_velocity_order`]), so no array is copied or permuted here.
fn layout_batch(core: &ModelCore) -> Result<Batch, mb::MultibodyError> {
    let b = Batch::new(&core.model);
    if core.layout.is_none() || !core.convert_v {
        return Ok(b);
    }
    let order: Vec<usize> = (0..core.nv()).map(|k| core.v_index(k)).collect();
    b.with_velocity_order(&core.model, &order)
}

/// The two `(q, v, x) ↦ nv-vector` verbs.
#[derive(Clone, Copy)]
enum Qvx {
    Rnea,
    Aba,
}

impl Qvx {
    fn run(
        self,
        b: &mut Batch,
        m: &mb::Model,
        q: &[f64],
        v: &[f64],
        x: &[f64],
        out: &mut [f64],
    ) -> MbResult {
        match self {
            Self::Rnea => b.rnea(m, q, v, x, out),
            Self::Aba => b.aba(m, q, v, x, out),
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
    (threads, out): (Option<i64>, Option<&Bound<'py, PyAny>>),
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let py = q.py();
    let pool = crate::scale::pool(func, threads)?;
    let core = &*model.inner;
    let (n, qs, vx) = inputs(core, pool.as_deref(), func, q, &args, false)?;
    let nv = core.nv();
    let array = match out {
        Some(o) => out_array(func, o, n, nv)?,
        None => crate::outputs::fresh(py, [n, nv])?,
    };
    // rust-numpy's borrows see views of one base array, not two arrays over the same buffer
    let written = array.data() as usize..array.data() as usize + n * nv * size_of::<f64>();
    let overlaps = |x: &[f64]| {
        let r = x.as_ptr() as usize..x.as_ptr() as usize + size_of_val(x);
        r.start < written.end && written.start < r.end
    };
    if n * nv > 0 && (overlaps(qs.as_slice()) || vx.iter().any(|x| overlaps(x.as_slice()))) {
        return Err(value_error(func, "out overlaps an input".to_string()));
    }
    let mut guard = array.try_readwrite().map_err(|e| {
        value_error(
            func,
            format!("out cannot be written ({e}): pass a writeable array that is not an input"),
        )
    })?;
    let out = guard.as_slice_mut().unwrap_or(&mut []);
    let (qs, vs, xs) = (qs.as_slice(), vx[0].as_slice(), vx[1].as_slice());
    crate::scale::detach(py, pool.as_deref(), || {
        f.run(&mut layout_batch(core)?, &core.model, qs, vs, xs, out)
    })
    .map_err(|e| {
        if let Err(e) = check_finite(core, func, &args) {
            return e;
        }
        state_error(core, func, e, qs, |d, k, q| {
            let r = k * nv..(k + 1) * nv;
            // in rigid's layout (the permutation is its own inverse)
            let (v, x) = (core.v_to_layout(&vs[r.clone()]), core.v_to_layout(&xs[r]));
            f.single(&core.model, d, q, &v, &x)
        })
    })?;
    drop(guard);
    Ok(array)
}

/// The caller's `out=` array: a writeable, C-contiguous float64 array of shape `(n, nv)`.
fn out_array<'py>(
    func: &str,
    o: &Bound<'py, PyAny>,
    n: usize,
    nv: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let wrong = || {
        value_error(
            func,
            format!("out must be a writeable, C-contiguous float64 array of shape ({n}, {nv})"),
        )
    };
    let a = o.cast::<PyArray2<f64>>().map_err(|_| wrong())?;
    if a.shape() != [n, nv] || !a.is_c_contiguous() || !a.is_aligned() {
        return Err(wrong());
    }
    Ok(a.clone())
}

/// Inverse dynamics for every row: `TAU[k] = rnea(Q[k], V[k], A[k])`, an `(N, nv)` array, on
/// `threads` threads (None: every core), written to `out` when given (a writeable C-contiguous
/// float64 `(N, nv)` array that overlaps no input, returned: repeated calls then allocate
/// nothing; on an error its contents are unspecified).
#[pyfunction]
#[pyo3(signature = (model, q, v, a, *, threads = None, out = None))]
pub fn rnea_batch<'py>(
    model: PyRef<'py, Model>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    a: &Bound<'py, PyAny>,
    threads: Option<i64>,
    out: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    qvx_batch(
        &model,
        "rnea_batch",
        Qvx::Rnea,
        q,
        [("V", v), ("A", a)],
        (threads, out),
    )
}

/// Forward dynamics for every row: `DDQ[k] = aba(Q[k], V[k], TAU[k])`, an `(N, nv)` array, on
/// `threads` threads (None: every core), written to `out` when given (as `rnea_batch`).
#[pyfunction]
#[pyo3(signature = (model, q, v, tau, *, threads = None, out = None))]
pub fn aba_batch<'py>(
    model: PyRef<'py, Model>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    tau: &Bound<'py, PyAny>,
    threads: Option<i64>,
    out: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    qvx_batch(
        &model,
        "aba_batch",
        Qvx::Aba,
        q,
        [("V", v), ("TAU", tau)],
        (threads, out),
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
    let (n, qs, _) = inputs(core, pool.as_deref(), F, q, &[], true)?;
    let qs = qs.as_slice();
    let nv = core.nv();
    let array = crate::outputs::fresh(py, [n, nv, nv])?;
    let mut guard = array.readwrite(); // a fresh array: nothing else borrows it
    let out = guard.as_slice_mut().unwrap_or(&mut []);
    crate::scale::detach(py, pool.as_deref(), || {
        layout_batch(core)?.crba(&core.model, qs, out)
    })
    .map_err(|e| {
        state_error(core, F, e, qs, |d, _, q| {
            mb::crba(&core.model, d, q).map(|_| ())
        })
    })?;
    drop(guard);
    Ok(array)
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
    let args = [("V", v), ("A", a)];
    let (n, qs, va) = inputs(core, pool.as_deref(), F, q, &args, false)?;
    let (qs, vs, as_) = (qs.as_slice(), va[0].as_slice(), va[1].as_slice());
    let nv = core.nv();
    let arrays = [
        crate::outputs::fresh(py, [n, nv, nv])?,
        crate::outputs::fresh(py, [n, nv, nv])?,
    ];
    let mut guards = arrays.each_ref().map(|a| a.readwrite()); // fresh arrays
    let [dq, dv] = guards
        .each_mut()
        .map(|g| g.as_slice_mut().unwrap_or(&mut []));
    crate::scale::detach(py, pool.as_deref(), || {
        layout_batch(core)?.rnea_derivatives(&core.model, qs, vs, as_, dq, dv)
    })
    .map_err(|e| {
        if let Err(e) = check_finite(core, F, &args) {
            return e;
        }
        state_error(core, F, e, qs, |d, k, q| {
            let r = k * nv..(k + 1) * nv;
            let (v, a) = (core.v_to_layout(&vs[r.clone()]), core.v_to_layout(&as_[r]));
            mb::rnea_derivatives(&core.model, d, q, &v, &a).map(|_| ())
        })
    })?;
    drop(guards);
    let [dq, dv] = arrays;
    Ok((dq, dv))
}
