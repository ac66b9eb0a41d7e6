//! How fast the multibody algorithms run on a model: the timing harness behind `rigid bench`
//! (and so behind `bench/compare.py`, which divides its numbers by Pinocchio's).
//!
//! - [`time_algorithms`]: median nanoseconds per call of each algorithm of [`ALGORITHMS`] over
//!   pre-drawn random [`States`] (so that branch prediction is not flattered). One pass calls the
//!   algorithm once per state; the time of a pass divided by the number of states is one sample;
//!   the result is the median of the samples, after one warm-up pass; the algorithms take turns
//!   pass by pass, as in Pinocchio's timing program, so that a slow spell of a shared machine
//!   hits all of them alike.
//! - [`batch_throughput`]: states per second of the batch entry points
//!   ([`multibody::batch`](crate::multibody::batch)) on 1, 2, … threads (each in its own rayon
//!   pool) against a loop of single calls, median over the passes; the configurations take turns
//!   pass by pass.
//!
//! ```
//! use rigid::multibody::{builtin, Data};
//! use rigid::timing::{time_algorithms, States};
//! let model = builtin("double_pendulum").unwrap();
//! let states = States::new(&model, 10, 7);
//! let ns = time_algorithms(&model, &mut Data::new(&model), &states, &["rnea", "aba"], 3)?;
//! assert!(ns.iter().all(|t| *t > 0.0));
//! # Ok::<(), rigid::timing::TimingError>(())
//! ```

use crate::error::DimensionError;
use crate::multibody::{
    aba, aba_derivatives, batch, compute_joint_jacobians, compute_minverse, crba,
    forward_dynamics_cholesky, forward_kinematics, forward_kinematics_q, gravity_torques,
    nonlinear_effects, random_configuration, rnea, rnea_derivatives, Data, Model, MultibodyError,
    Rng,
};
use std::hint::black_box;
use std::time::Instant;
use thiserror::Error;

/// What can go wrong when timing.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum TimingError {
    /// A name that is not one of [`ALGORITHMS`].
    #[error("unknown algorithm {0}")]
    UnknownAlgorithm(String),
    /// An algorithm failed on a state (e.g. a singular mass matrix).
    #[error("{name}: {source}")]
    Algorithm {
        /// The algorithm's key.
        name: &'static str,
        /// Its error.
        source: MultibodyError,
    },
    /// A batch entry point failed.
    #[error(transparent)]
    Batch(#[from] MultibodyError),
    /// A thread pool could not be built.
    #[error("thread pool: {0}")]
    ThreadPool(String),
}

/// The algorithms [`time_algorithms`] times, in output order. The keys are those of
/// Pinocchio's timing program in `bench/pinocchio/`:
///
/// | key | rigid call | Pinocchio call |
/// | --- | --- | --- |
/// | `forward_kinematics` | `forward_kinematics_q` (placements) | `forwardKinematics(q)` |
/// | `forward_kinematics_qva` | `forward_kinematics` (placements, V, A) | `forwardKinematics(q, v, a)` |
/// | `jacobians` | `compute_joint_jacobians` | `computeJointJacobians(q)` |
/// | `rnea`, `gravity`, `nonlinear_effects` | `rnea`, `gravity_torques`, `nonlinear_effects` | same |
/// | `crba` | `crba` (full symmetric `M`) | `crba` (upper triangle only) |
/// | `aba` | `aba` | `aba` |
/// | `minverse` | `compute_minverse` (full symmetric `M⁻¹`) | `computeMinverse` (upper triangle only; `bench/pinocchio/timings-aba.cpp` does not symmetrise) |
/// | `cholesky_fd` | `forward_dynamics_cholesky` (nle + CRBA + Cholesky solve) | nle + crba + `cholesky::solve` |
/// | `rnea_derivatives` | `rnea_derivatives` (`∂τ/∂q`, `∂τ/∂v`, full symmetric `M`) | `computeRNEADerivatives` (`M` upper triangle) |
/// | `aba_derivatives` | `aba_derivatives` (`∂q̈/∂q`, `∂q̈/∂v`, full symmetric `M⁻¹`) | `computeABADerivatives` |
pub const ALGORITHMS: [&str; 12] = [
    "forward_kinematics",
    "forward_kinematics_qva",
    "jacobians",
    "rnea",
    "gravity",
    "nonlinear_effects",
    "crba",
    "aba",
    "minverse",
    "cholesky_fd",
    "rnea_derivatives",
    "aba_derivatives",
];

/// Pre-drawn random states `(q, v, a, τ)`: `q` uniform within the joint limits (unit
/// quaternions uniform on SO(3)), `v`, `a`, `τ` uniform in `[-1, 1]`.
#[derive(Clone, Debug)]
pub struct States {
    q: Vec<Vec<f64>>,
    v: Vec<Vec<f64>>,
    a: Vec<Vec<f64>>,
    tau: Vec<Vec<f64>>,
}

impl States {
    /// `n` random states of `model` from the seed `seed`.
    #[must_use]
    pub fn new(model: &Model, n: usize, seed: u64) -> Self {
        let mut rng = Rng::new(seed);
        let vec = |rng: &mut Rng| -> Vec<f64> {
            (0..model.nv()).map(|_| rng.uniform(-1.0, 1.0)).collect()
        };
        let (mut q, mut v, mut a, mut tau) = (vec![], vec![], vec![], vec![]);
        for _ in 0..n {
            q.push(random_configuration(model, &mut rng));
            v.push(vec(&mut rng));
            a.push(vec(&mut rng));
            tau.push(vec(&mut rng));
        }
        Self { q, v, a, tau }
    }

    /// The number of states.
    #[must_use]
    pub fn len(&self) -> usize {
        self.q.len()
    }

    /// No state at all.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.q.is_empty()
    }
}

/// One call of an algorithm on state `i`, returning one entry of its result (kept alive with
/// `black_box` so that nothing is optimised away).
type Call = fn(&Model, &mut Data, &States, usize) -> Result<f64, MultibodyError>;

/// The call timed under each key of [`ALGORITHMS`].
fn call_of(name: &str) -> Option<Call> {
    let f: Call = match name {
        "forward_kinematics" => |m, d, s, i| forward_kinematics_q(m, d, &s.q[i]).map(|()| 0.0),
        "forward_kinematics_qva" => {
            |m, d, s, i| forward_kinematics(m, d, &s.q[i], &s.v[i], &s.a[i]).map(|()| 0.0)
        }
        "jacobians" => |m, d, s, i| compute_joint_jacobians(m, d, &s.q[i]).map(|j| j[0]),
        "rnea" => |m, d, s, i| rnea(m, d, &s.q[i], &s.v[i], &s.a[i]).map(|t| t[0]),
        "gravity" => |m, d, s, i| gravity_torques(m, d, &s.q[i]).map(|t| t[0]),
        "nonlinear_effects" => |m, d, s, i| nonlinear_effects(m, d, &s.q[i], &s.v[i]).map(|t| t[0]),
        "crba" => |m, d, s, i| crba(m, d, &s.q[i]).map(|x| x[0]),
        "aba" => |m, d, s, i| aba(m, d, &s.q[i], &s.v[i], &s.tau[i]).map(|t| t[0]),
        "minverse" => |m, d, s, i| compute_minverse(m, d, &s.q[i]).map(|x| x[0]),
        "cholesky_fd" => {
            |m, d, s, i| forward_dynamics_cholesky(m, d, &s.q[i], &s.v[i], &s.tau[i]).map(|t| t[0])
        }
        "rnea_derivatives" => {
            |m, d, s, i| rnea_derivatives(m, d, &s.q[i], &s.v[i], &s.a[i]).map(|x| x.dtau_dq[0])
        }
        "aba_derivatives" => {
            |m, d, s, i| aba_derivatives(m, d, &s.q[i], &s.v[i], &s.tau[i]).map(|x| x.dqdd_dq[0])
        }
        _ => return None,
    };
    Some(f)
}

/// Mean ns per call of one pass of `f` through every state. Never inlined: bench/flops.py
/// counts the operations executed inside it (callgrind's `--toggle-collect`).
#[inline(never)]
fn pass(
    model: &Model,
    data: &mut Data,
    s: &States,
    name: &'static str,
    f: Call,
) -> Result<f64, TimingError> {
    let n = s.len();
    let t = Instant::now();
    for i in 0..n {
        black_box(f(model, data, s, i).map_err(|source| TimingError::Algorithm { name, source })?);
    }
    Ok(t.elapsed().as_nanos() as f64 / n.max(1) as f64)
}

/// Median ns per call of each algorithm in `names` (keys of [`ALGORITHMS`]) over `reps` passes
/// through `states` (see the [module](self) documentation).
///
/// # Errors
/// [`TimingError::UnknownAlgorithm`] for a name not in [`ALGORITHMS`];
/// [`TimingError::Algorithm`] if an algorithm fails (e.g. a singular mass matrix).
pub fn time_algorithms(
    model: &Model,
    data: &mut Data,
    states: &States,
    names: &[&str],
    reps: usize,
) -> Result<Vec<f64>, TimingError> {
    let calls = names
        .iter()
        .map(|n| {
            let key = ALGORITHMS.iter().find(|k| *k == n);
            key.and_then(|k| Some((*k, call_of(k)?)))
                .ok_or_else(|| TimingError::UnknownAlgorithm((*n).to_string()))
        })
        .collect::<Result<Vec<_>, _>>()?;
    for &(name, f) in &calls {
        pass(model, data, states, name, f)?;
    }
    let mut samples = vec![Vec::with_capacity(reps.max(1)); names.len()];
    for _ in 0..reps.max(1) {
        for (&(name, f), x) in calls.iter().zip(&mut samples) {
            x.push(pass(model, data, states, name, f)?);
        }
    }
    Ok(samples.into_iter().map(median).collect())
}

/// `rnea` and `aba` share one shape: `(q, v, x) ↦ nv-vector` (the loops of single calls).
pub(crate) type QvxFn = for<'a> fn(
    &Model,
    &'a mut Data,
    &[f64],
    &[f64],
    &[f64],
) -> Result<&'a nalgebra::DVector<f64>, MultibodyError>;

/// Row-major states for the batch entry points.
struct Rows {
    n: usize,
    qs: Vec<f64>,
    vs: Vec<f64>,
    as_: Vec<f64>,
}

impl Rows {
    fn new(s: &States) -> Self {
        Self {
            n: s.len(),
            qs: s.q.concat(),
            vs: s.v.concat(),
            as_: s.a.concat(),
        }
    }

    /// State `k`: its `q`, `v` and `a` rows.
    fn state(&self, m: &Model, k: usize) -> (&[f64], &[f64], &[f64]) {
        let (nq, nv) = (m.nq(), m.nv());
        (
            &self.qs[k * nq..][..nq],
            &self.vs[k * nv..][..nv],
            &self.as_[k * nv..][..nv],
        )
    }
}

/// A batch entry point on row-major states, with workspaces made once per thread pool.
type Kernel = fn(&mut batch::Batch, &Model, &Rows, &mut [f64]) -> Result<(), MultibodyError>;
/// A loop of single calls with one workspace.
type Single = fn(&Model, &Rows, &mut [f64], &mut Data) -> Result<(), MultibodyError>;

/// A loop of single calls of `f` over the states, the third input taken from `r.as_`.
fn loop_qvx(
    f: QvxFn,
    m: &Model,
    r: &Rows,
    out: &mut [f64],
    d: &mut Data,
) -> Result<(), MultibodyError> {
    let nv = m.nv();
    for k in 0..r.n {
        let (q, v, x) = r.state(m, k);
        let t = f(m, d, q, v, x)?;
        out[k * nv..][..nv].copy_from_slice(t.as_slice());
    }
    Ok(())
}

fn loop_rnea(m: &Model, r: &Rows, out: &mut [f64], d: &mut Data) -> Result<(), MultibodyError> {
    loop_qvx(rnea, m, r, out, d)
}

fn loop_aba(m: &Model, r: &Rows, out: &mut [f64], d: &mut Data) -> Result<(), MultibodyError> {
    loop_qvx(aba, m, r, out, d)
}

/// Single `crba` calls, `write(M column-major, nv, out_k)` with `per` numbers per state: the
/// loop counterpart of `Batch::crba_into`.
fn loop_crba_into(
    m: &Model,
    r: &Rows,
    out: &mut [f64],
    d: &mut Data,
    per: usize,
    write: impl Fn(&[f64], usize, &mut [f64]) -> Result<(), DimensionError>,
) -> Result<(), MultibodyError> {
    let nq = m.nq();
    for k in 0..r.n {
        let t = crba(m, d, &r.qs[k * nq..][..nq])?;
        write(t.as_slice(), m.nv(), &mut out[k * per..][..per])?;
    }
    Ok(())
}

/// The loop counterpart of `crba_lower`: single calls, each matrix's lower triangle packed.
fn loop_crba_lower(
    m: &Model,
    r: &Rows,
    out: &mut [f64],
    d: &mut Data,
) -> Result<(), MultibodyError> {
    let nv = m.nv();
    loop_crba_into(m, r, out, d, nv * (nv + 1) / 2, batch::pack_lower)
}

/// Single `rnea_derivatives` calls, each state's `∂τ/∂q` then `∂τ/∂v` (column-major, as the
/// single call leaves them; the batch writes row-major blocks of the same size).
fn loop_rnea_derivatives(
    m: &Model,
    r: &Rows,
    out: &mut [f64],
    d: &mut Data,
) -> Result<(), MultibodyError> {
    let nn = m.nv() * m.nv();
    let (dq, dv) = out.split_at_mut(r.n * nn);
    for k in 0..r.n {
        let (q, v, a) = r.state(m, k);
        let t = rnea_derivatives(m, d, q, v, a)?;
        dq[k * nn..][..nn].copy_from_slice(t.dtau_dq.as_slice());
        dv[k * nn..][..nn].copy_from_slice(t.dtau_dv.as_slice());
    }
    Ok(())
}

fn loop_crba(m: &Model, r: &Rows, out: &mut [f64], d: &mut Data) -> Result<(), MultibodyError> {
    loop_crba_into(m, r, out, d, m.nv() * m.nv(), |t, _, out| {
        out.copy_from_slice(t);
        Ok(())
    })
}

/// Wall time (s) of one run of `f`.
fn secs(f: impl FnOnce() -> Result<(), MultibodyError>) -> Result<f64, MultibodyError> {
    let s = Instant::now();
    f()?;
    Ok(s.elapsed().as_secs_f64())
}

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

/// The throughput of one batch entry point ([`batch_throughput`]).
#[derive(Clone, Debug, PartialEq)]
pub struct BatchThroughput {
    /// `rnea`, `aba`, `crba`, `crba_lower` (the packed lower triangles of `Batch::crba_lower`)
    /// or `rnea_derivatives` (`∂τ/∂q` and `∂τ/∂v`).
    pub name: &'static str,
    /// States per second of a loop of single calls.
    pub single: f64,
    /// One entry per thread count, in the order asked for.
    pub threads: Vec<ThreadThroughput>,
}

/// The throughput of a batch entry point on one thread count.
#[derive(Clone, Debug, PartialEq)]
pub struct ThreadThroughput {
    /// The number of threads.
    pub threads: usize,
    /// States per second.
    pub rate: f64,
    /// The speed-up over the loop of single calls.
    pub vs_loop: f64,
    /// The speed-up over the first thread count asked for.
    pub vs_first: f64,
}

/// The batch entry points [`batch_throughput`] times.
pub const BATCH_ALGORITHMS: [&str; 5] = ["rnea", "aba", "crba", "crba_lower", "rnea_derivatives"];

/// States per second of a loop of single calls and of the batch entry points `names` (keys of
/// [`BATCH_ALGORITHMS`]; empty: all of them) on each of `threads`, median of `reps` passes
/// through `states`; a speed-up is the median over passes of the ratio of the two
/// configurations' times within the pass. The batch computes `lanes` states side by side
/// ([`batch::Batch::with_lanes`]: 2, 4 or 8; anything else is 2), or with `None` those of
/// [`batch::Batch::new`] (`RIGID_LANES` when set, else as many as the CPU's vector unit holds).
///
/// # Errors
/// [`TimingError::UnknownAlgorithm`] for a name not in [`BATCH_ALGORITHMS`], an algorithm
/// error, or a thread pool that cannot be built.
pub fn batch_throughput(
    model: &Model,
    states: &States,
    names: &[&str],
    threads: &[usize],
    lanes: Option<usize>,
    reps: usize,
) -> Result<Vec<BatchThroughput>, TimingError> {
    if let Some(n) = names.iter().find(|n| !BATCH_ALGORITHMS.contains(n)) {
        return Err(TimingError::UnknownAlgorithm((*n).to_string()));
    }
    let rows = Rows::new(states);
    let nv = model.nv();
    let kernels: [(&str, usize, Kernel, Single); 5] = [
        (
            "rnea",
            nv,
            |b, m, r, o| b.rnea(m, &r.qs, &r.vs, &r.as_, o),
            loop_rnea,
        ),
        (
            "aba",
            nv,
            |b, m, r, o| b.aba(m, &r.qs, &r.vs, &r.as_, o),
            loop_aba,
        ),
        ("crba", nv * nv, |b, m, r, o| b.crba(m, &r.qs, o), loop_crba),
        (
            "crba_lower",
            nv * (nv + 1) / 2,
            |b, m, r, o| b.crba_lower(m, &r.qs, o),
            loop_crba_lower,
        ),
        (
            "rnea_derivatives",
            2 * nv * nv,
            |b, m, r, o| {
                let (dq, dv) = o.split_at_mut(o.len() / 2);
                b.rnea_derivatives(m, &r.qs, &r.vs, &r.as_, dq, dv)
            },
            loop_rnea_derivatives,
        ),
    ];
    let pools = threads
        .iter()
        .map(|&k| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(k)
                .build()
                .map_err(|e| TimingError::ThreadPool(e.to_string()))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut out = Vec::with_capacity(kernels.len());
    for (name, per, par, single) in kernels {
        if !names.is_empty() && !names.contains(&name) {
            continue;
        }
        let mut buf = vec![0.0; rows.n * per];
        let mut data = Data::new(model);
        let mut batches: Vec<batch::Batch> = pools
            .iter()
            .map(|p| {
                p.install(|| match lanes {
                    Some(w) => batch::Batch::with_lanes(model, w),
                    None => batch::Batch::new(model),
                })
            })
            .collect();
        // the loop and every thread count take turns pass by pass, so that a slow spell of a
        // shared machine hits them alike; each turn is an untimed pass then a timed one, so that
        // what is timed is a pool already awake (the steady state of a long batch), not the wake-up
        // of threads that slept through the other configurations' turns
        let mut t = vec![Vec::with_capacity(reps.max(1)); 1 + pools.len()];
        for _ in 0..reps.max(1) {
            single(model, &rows, &mut buf, &mut data)?;
            t[0].push(secs(|| single(model, &rows, &mut buf, &mut data))?);
            for ((pool, b), t) in pools.iter().zip(&mut batches).zip(&mut t[1..]) {
                pool.install(|| par(b, model, &rows, &mut buf))?;
                t.push(pool.install(|| secs(|| par(b, model, &rows, &mut buf)))?);
            }
        }
        // speed-ups as the median over passes of the ratio within each pass (the configurations
        // ran back to back), which cancels the slow spells that a ratio of medians keeps
        let ratio = |a: &[f64], b: &[f64]| median(a.iter().zip(b).map(|(a, b)| a / b).collect());
        let n = rows.n as f64;
        out.push(BatchThroughput {
            name,
            single: n / median(t[0].clone()),
            threads: threads
                .iter()
                .zip(&t[1..])
                .map(|(&k, tk)| ThreadThroughput {
                    threads: k,
                    rate: n / median(tk.clone()),
                    vs_loop: ratio(&t[0], tk),
                    vs_first: ratio(&t[1], tk),
                })
                .collect(),
        });
    }
    Ok(out)
}
