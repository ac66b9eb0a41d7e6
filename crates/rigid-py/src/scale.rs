//! Scaling out (issue 27): the thread pools of the batch verbs' `threads=` (one rayon pool per
//! size, made once and kept), the regressor of many states (`regressor_batch`), models with other
//! inertial parameters (`Model.with_dynamic_parameters`), many rollouts at once
//! (`simulate_batch`), and the refusal of a dask array by the plain batch verbs. The algorithms
//! are the `rigid` crate's; this file parses and prints.

use crate::batch::{check_finite, inputs};
use crate::convert::{matrix, value_error, vector, Vector};
use crate::model::{Model, ModelCore};
use crate::simulation::{run, Record};
use numpy::{PyArray1, PyArray3, PyArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rayon::prelude::*;
use rayon::{ThreadPool, ThreadPoolBuilder};
use rigid::simulation::{
    step_count, ControlKind, Integrator, JointLimits, Scenario, SimulationError, SimulationOptions,
    TimeScaling,
};
use std::sync::{Arc, Mutex, PoisonError};

/// The most threads `threads=` takes (a typo should not start ten thousand threads).
const MAX_THREADS: i64 = 1024;

/// The pools made so far, one per size: a call with `threads=n` reuses the pool of size `n`.
static POOLS: Mutex<Vec<(usize, Arc<ThreadPool>)>> = Mutex::new(Vec::new());

/// The pool of `threads` threads (`None`: rayon's global pool, every core).
///
/// # Errors
/// `ValueError` for `threads` < 1 or over [`MAX_THREADS`].
pub fn pool(func: &str, threads: Option<i64>) -> PyResult<Option<Arc<ThreadPool>>> {
    let Some(t) = threads else { return Ok(None) };
    if !(1..=MAX_THREADS).contains(&t) {
        return Err(PyValueError::new_err(format!(
            "{func}: threads must be a number of threads from 1 to {MAX_THREADS}, got {t} \
             (leave it out, threads=None, for every core)"
        )));
    }
    let n = usize::try_from(t).expect("checked positive");
    let mut pools = POOLS.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some((_, p)) = pools.iter().find(|(k, _)| *k == n) {
        return Ok(Some(p.clone()));
    }
    let p = ThreadPoolBuilder::new()
        .num_threads(n)
        .thread_name(|i| format!("rigid-{i}"))
        .build()
        .map_err(|e| value_error(func, format!("cannot start {n} threads: {e}")))?;
    let p = Arc::new(p);
    pools.push((n, p.clone()));
    Ok(Some(p))
}

/// `f()` with the GIL released, on `pool` (or rayon's global pool).
pub fn detach<T: Send>(
    py: Python<'_>,
    pool: Option<&ThreadPool>,
    f: impl FnOnce() -> T + Send,
) -> T {
    py.detach(|| on(pool, f))
}

/// `f()` on `pool` (or rayon's global pool), the GIL kept.
pub fn on<T: Send>(pool: Option<&ThreadPool>, f: impl FnOnce() -> T + Send) -> T {
    match pool {
        Some(p) => p.install(f),
        None => f(),
    }
}

/// `TypeError` for a dask array (duck-typed: it has `__dask_graph__`), pointing to `rigid.dask`.
pub fn refuse_dask(func: &str, name: &str, x: &Bound<'_, PyAny>) -> PyResult<()> {
    if x.hasattr("__dask_graph__").unwrap_or(false) {
        let verb = func.trim_end_matches("_batch");
        return Err(PyTypeError::new_err(format!(
            "{func}: {name} is a dask array (computing it here would pull every chunk into this \
             process); use rigid.dask.{verb}(model, ...), which maps the batch over the chunks on \
             the workers and returns a dask array, or pass {name}.compute()"
        )));
    }
    Ok(())
}

/// The regressor of every row: `Y[k] = regressor(Q[k], V[k], A[k])`, an `(N, nv, 10·nb)` array
/// with `τ[k] = Y[k] @ π` (`π`: `dynamic_parameters`, rigid's `rnea` adds `armature ∘ a`).
#[pyfunction]
#[pyo3(signature = (model, q, v, a, *, threads = None))]
pub fn regressor_batch<'py>(
    py: Python<'py>,
    model: PyRef<'py, Model>,
    q: &Bound<'py, PyAny>,
    v: &Bound<'py, PyAny>,
    a: &Bound<'py, PyAny>,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyArray3<f64>>> {
    const F: &str = "regressor_batch";
    let pool = pool(F, threads)?;
    let core = &*model.inner;
    let args = [("V", v), ("A", a)];
    let (n, qs, va) = inputs(core, pool.as_deref(), F, q, &args, true)?;
    check_finite(core, F, &args)?;
    let (qs, vs, as_) = (qs.as_slice(), va[0].as_slice(), va[1].as_slice());
    let (nv, cols) = (core.nv(), 10 * core.model.njoints());
    // written in place (see outputs.rs)
    let array = crate::outputs::fresh(py, [n, nv, cols])?;
    let mut guard = array.readwrite(); // a fresh array: nothing else borrows it
    let out = guard.as_slice_mut().unwrap_or(&mut []);
    detach(py, pool.as_deref(), || {
        rigid::identification::regressor_batch(&core.model, qs, vs, as_, out)?;
        if core.convert_v {
            // rows in the model's velocity layout
            out.par_chunks_mut((nv * cols).max(1)).for_each_init(
                || vec![0.0; nv * cols],
                |block, y| {
                    block.copy_from_slice(y);
                    for (r, row) in y.chunks_exact_mut(cols).enumerate() {
                        let k = core.v_index(r);
                        row.copy_from_slice(&block[k * cols..(k + 1) * cols]);
                    }
                },
            );
        }
        Ok::<_, rigid::multibody::MultibodyError>(())
    })
    .map_err(|e| value_error(F, e))?;
    drop(guard);
    Ok(array)
}

/// `model.with_dynamic_parameters(pi)`: a new model (same layout, source, warnings) whose body
/// inertias are `pi`, each checked to be physical (unless `check` is false).
pub fn with_dynamic_parameters(
    model: &Model,
    pi: &Bound<'_, PyAny>,
    check: bool,
) -> PyResult<Model> {
    const F: &str = "with_dynamic_parameters";
    let core = &*model.inner;
    let n = 10 * core.model.njoints();
    let p = vector(pi, F, "pi", "10·nbodies", n)?;
    let m = if check {
        rigid::identification::model_with_checked_parameters(&core.model, p.as_slice()).map_err(
            |e| {
                value_error(
                    F,
                    format!("{e}; check=False takes the parameters as they are"),
                )
            },
        )?
    } else {
        rigid::identification::model_with_parameters(&core.model, p.as_slice())
            .map_err(|e| value_error(F, e))?
    };
    let mut new = ModelCore::new(m, core.layout.is_some(), core.warnings.clone());
    new.source.clone_from(&core.source);
    new.mujoco.clone_from(&core.mujoco);
    new.qpos0.clone_from(&core.qpos0);
    Ok(Model {
        inner: Arc::new(new),
    })
}

/// Rows of a configuration- or velocity-space argument for `m` rollouts: one vector for every
/// rollout, or an `(m, n)` array, one row each; converted by `into` (model layout to rigid's).
fn per_rollout(
    cores: &[Arc<ModelCore>],
    x: Option<&Bound<'_, PyAny>>,
    name: &str,
    what: &str,
    velocity: bool,
) -> PyResult<Vec<Option<Vec<f64>>>> {
    const F: &str = "simulate_batch";
    let m = cores.len();
    let Some(x) = x else { return Ok(vec![None; m]) };
    let ndim: usize = x.getattr("ndim").and_then(|d| d.extract()).unwrap_or(1);
    let width = if velocity {
        cores[0].nv()
    } else {
        cores[0].nq()
    };
    let rows: Vec<Vec<f64>> = if ndim == 2 {
        let a = matrix(x, F, name, what, width)?;
        if a.rows != m {
            return Err(PyValueError::new_err(format!(
                "{F}: {name} has {} rows for {m} rollouts (one row per rollout, or one vector for all)",
                a.rows
            )));
        }
        a.as_slice()
            .chunks_exact(width.max(1))
            .take(m)
            .map(<[f64]>::to_vec)
            .collect()
    } else {
        let v = vector(x, F, name, what, width)?;
        vec![v.as_slice().to_vec(); m]
    };
    cores
        .iter()
        .zip(rows)
        .enumerate()
        .map(|(i, (core, row))| {
            let mut out = Vec::new();
            let label = format!("{name}[{i}]");
            let row = Vector::Owned(row);
            if velocity {
                core.v_into(&row, &mut out, F, &label)?;
            } else {
                core.q_into(&row, &mut out, F, &label)?;
            }
            Ok(Some(out))
        })
        .collect()
}

/// Many rollouts at once, one per model (a list of models, as MuJoCo's `rollout`), or one model
/// from many initial states (`q0` of shape `(M, nq)`), in parallel with the GIL released; the
/// options and built-in controllers of `simulate`. Returns a dict: `t` (T), `q` (M × T × nq),
/// `v`, `tau` (M × T × nv), `energy` (M × T); rollout `i` equals `simulate` of model `i` bit for
/// bit.
#[pyfunction]
#[pyo3(signature = (
    models, q0 = None, v0 = None, duration = 1.0, dt = 1e-3, integrator = "rk4",
    controller = "none", target = None, move_time = None, profile = "quintic",
    limits = "spring", joint_dynamics = true, every = 1, *, threads = None
))]
#[allow(clippy::too_many_arguments)]
pub fn simulate_batch<'py>(
    py: Python<'py>,
    models: &Bound<'py, PyAny>,
    q0: Option<&Bound<'py, PyAny>>,
    v0: Option<&Bound<'py, PyAny>>,
    duration: f64,
    dt: f64,
    integrator: &str,
    controller: &str,
    target: Option<&Bound<'py, PyAny>>,
    move_time: Option<f64>,
    profile: &str,
    limits: &str,
    joint_dynamics: bool,
    every: u64,
    threads: Option<i64>,
) -> PyResult<Bound<'py, PyDict>> {
    const F: &str = "simulate_batch";
    let pool = pool(F, threads)?;
    let err = |e: SimulationError| value_error(F, e);
    let mut cores: Vec<Arc<ModelCore>> = if let Ok(m) = models.cast::<Model>() {
        vec![m.borrow().inner.clone()]
    } else if let Ok(list) = models.cast::<PyList>() {
        list.iter()
            .enumerate()
            .map(|(i, m)| {
                m.cast::<Model>()
                    .map(|m| m.borrow().inner.clone())
                    .map_err(|_| {
                        PyTypeError::new_err(format!("{F}: models[{i}] is not a rigid.Model"))
                    })
            })
            .collect::<PyResult<_>>()?
    } else {
        return Err(PyTypeError::new_err(format!(
            "{F}: models must be a rigid.Model or a list of them"
        )));
    };
    if cores.is_empty() {
        return Err(PyValueError::new_err(format!(
            "{F}: models is an empty list"
        )));
    }
    if let Some((i, _)) = cores
        .iter()
        .enumerate()
        .find(|(_, c)| c.nq() != cores[0].nq() || c.nv() != cores[0].nv())
    {
        return Err(PyValueError::new_err(format!(
            "{F}: models[{i}] has nq = {}, nv = {}, models[0] nq = {}, nv = {} (the rollouts are \
             stacked in one array: one kinematic structure, any parameters)",
            cores[i].nq(),
            cores[i].nv(),
            cores[0].nq(),
            cores[0].nv()
        )));
    }
    // one model, many initial states: M rollouts of it
    if cores.len() == 1 {
        if let Some(x) = q0 {
            let ndim: usize = x.getattr("ndim").and_then(|d| d.extract()).unwrap_or(1);
            if ndim == 2 {
                let rows: usize = x.getattr("shape")?.get_item(0)?.extract()?;
                cores = vec![cores[0].clone(); rows];
            }
        }
    }
    if let Some(i) = cores.iter().position(|c| c.mujoco_free().is_some()) {
        return Err(value_error(
            F,
            format!("models[{i}]: not available in the mujoco layout for a model with a free joint; use layout=\"rigid\""),
        ));
    }
    let steps = step_count(duration, dt).map_err(err)?;
    if every == 0 {
        return Err(PyValueError::new_err(format!(
            "{F}: every must be at least 1"
        )));
    }
    let q0s = per_rollout(&cores, q0, "q0", "nq", false)?;
    let v0s = per_rollout(&cores, v0, "v0", "nv", true)?;
    let targets = per_rollout(&cores, target, "target", "nq", false)?;
    let opts = SimulationOptions {
        dt,
        integrator: integrator.parse::<Integrator>().map_err(err)?,
        limits: limits.parse::<JointLimits>().map_err(err)?,
        joint_dynamics,
        ..SimulationOptions::default()
    };
    let scaling: TimeScaling = profile.parse().map_err(err)?;
    let kind: ControlKind = controller.parse().map_err(err)?;
    let time = move_time.unwrap_or(0.5 * duration);
    let one = |i: usize| -> Result<Record, SimulationError> {
        let mut s = Scenario::new(cores[i].model.clone());
        s.q0 = q0s[i].clone();
        s.v0 = v0s[i].clone();
        s.target = targets[i].clone();
        s.controller = kind;
        s.move_time = time;
        s.profile = scaling;
        s.options = opts;
        let mut sim = s.build()?;
        let mut rec = Record::default();
        run(&mut sim, steps, every, &mut rec)?;
        Ok(rec)
    };
    let recs: Vec<Record> = detach(py, pool.as_deref(), || {
        (0..cores.len())
            .into_par_iter()
            .map(|i| one(i).map_err(|e| (i, e)))
            .collect::<Result<Vec<_>, _>>()
    })
    .map_err(|(i, e)| value_error(F, format!("rollout {i}: {e}")))?;
    let (m, t) = (recs.len(), recs[0].t.len());
    let (nq, nv) = (cores[0].nq(), cores[0].nv());
    let (mut q, mut v, mut tau, mut energy) = (vec![], vec![], vec![], vec![]);
    for (core, rec) in cores.iter().zip(&recs) {
        let (nq_r, nv_r) = (core.model.nq().max(1), core.model.nv().max(1));
        q.extend(
            rec.q
                .chunks_exact(nq_r)
                .take(t)
                .flat_map(|x| core.q_to_layout(x)),
        );
        v.extend(
            rec.v
                .chunks_exact(nv_r)
                .take(t)
                .flat_map(|x| core.v_to_layout(x)),
        );
        tau.extend(
            rec.tau
                .chunks_exact(nv_r)
                .take(t)
                .flat_map(|x| core.v_to_layout(x)),
        );
        energy.extend_from_slice(&rec.energy);
    }
    let out = PyDict::new(py);
    out.set_item("t", PyArray1::from_slice(py, &recs[0].t))?;
    out.set_item("q", PyArray1::from_vec(py, q).reshape([m, t, nq])?)?;
    out.set_item("v", PyArray1::from_vec(py, v).reshape([m, t, nv])?)?;
    out.set_item("tau", PyArray1::from_vec(py, tau).reshape([m, t, nv])?)?;
    out.set_item("energy", PyArray1::from_vec(py, energy).reshape([m, t])?)?;
    Ok(out)
}

/// Test hook: inside the pool of `threads` (None: the global pool), rayon's thread count and the
/// number of distinct threads that ran 64 tasks of 2 ms each.
#[pyfunction]
#[pyo3(signature = (threads = None))]
pub fn _pool_threads(py: Python<'_>, threads: Option<i64>) -> PyResult<(usize, usize)> {
    let pool = pool("_pool_threads", threads)?;
    Ok(detach(py, pool.as_deref(), || {
        let ids: Vec<std::thread::ThreadId> = (0..64)
            .into_par_iter()
            .map(|_| {
                std::thread::sleep(std::time::Duration::from_millis(2));
                std::thread::current().id()
            })
            .collect();
        let mut distinct: Vec<_> = ids.into_iter().map(|i| format!("{i:?}")).collect();
        distinct.sort();
        distinct.dedup();
        (rayon::current_num_threads(), distinct.len())
    }))
}

/// Registers the functions of this file.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(regressor_batch, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_batch, m)?)?;
    m.add_function(wrap_pyfunction!(_pool_threads, m)?)?;
    Ok(())
}
