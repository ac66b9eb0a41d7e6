//! Batch evaluation of many states at once across the cores (rayon): inverse dynamics, forward
//! dynamics and mass matrices for `N` states, each written to a caller-owned, row-major output.
//!
//! Inputs are row-major: state `k`'s configuration is `qs[k nq..(k + 1) nq]`, its velocity
//! `vs[k nv..(k + 1) nv]`, and so on. The states are cut into a few contiguous blocks per
//! thread, each evaluated with its own [`Data`], and each state's result goes to its own slice of
//! the output, so the results are those of single calls, bit for bit, in the input order, for
//! any number of threads. Run inside a `rayon::ThreadPool::install` to choose the number of
//! threads. The free functions make their workspaces per call; a [`Batch`] keeps them across
//! calls (nothing allocated per call).
//!
//! ```
//! use rigid::multibody::{batch, puma560, Puma560Options};
//! let model = puma560(Puma560Options::default());
//! let (nq, nv, n) = (model.nq(), model.nv(), 4);
//! let qs = vec![0.1; n * nq];
//! let zeros = vec![0.0; n * nv];
//! let mut tau = vec![0.0; n * nv];
//! batch::rnea_batch(&model, &qs, &zeros, &zeros, &mut tau)?;
//! assert!(tau.chunks(nv).all(|t| t == &tau[..nv]));
//! # Ok::<(), rigid::multibody::MultibodyError>(())
//! ```

use super::{aba, crba, rnea, Data, Model, MultibodyError};
use crate::error::DimensionError;
use nalgebra::DVector;
use rayon::prelude::*;

/// `rnea` and `aba` share one shape: `(q, v, x) ↦ nv-vector`.
type QvxFn = for<'a> fn(
    &Model,
    &'a mut Data,
    &[f64],
    &[f64],
    &[f64],
) -> Result<&'a DVector<f64>, MultibodyError>;

/// Tasks per rayon thread: a few, so that a slow thread can be helped, each with its own
/// [`Data`].
const TASKS_PER_THREAD: usize = 2;

/// Number of states in row-major inputs, checking every length.
fn count(
    model: &Model,
    qs: &[f64],
    vs: &[&[f64]],
    out: usize,
    out_per: usize,
) -> Result<usize, MultibodyError> {
    let n = qs.len().checked_div(model.nq).unwrap_or(0);
    DimensionError::check("qs", n * model.nq, qs.len())?;
    for v in vs {
        DimensionError::check("vs", n * model.nv, v.len())?;
    }
    DimensionError::check("out", n * out_per, out)?;
    Ok(n)
}

/// The workspaces of the batch entry points: one [`Data`] per task (a few per thread of the
/// current rayon pool), made once and reused by every call, so that a batch call allocates
/// nothing per state and nothing per call (as Pinocchio's `ModelPool`).
///
/// ```
/// use rigid::multibody::{batch::Batch, puma560, Puma560Options};
/// let model = puma560(Puma560Options::default());
/// let mut batch = Batch::new(&model);
/// let (nq, nv, n) = (model.nq(), model.nv(), 100);
/// let (qs, zeros) = (vec![0.2; n * nq], vec![0.0; n * nv]);
/// let mut g = vec![0.0; n * nv];
/// for _ in 0..3 {
///     batch.rnea(&model, &qs, &zeros, &zeros, &mut g)?; // g(q) for 100 states, no allocation
/// }
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Batch {
    datas: Vec<Data>,
}

impl Batch {
    /// Workspaces for `model`, for the current rayon pool (`TASKS_PER_THREAD` per thread).
    #[must_use]
    pub fn new(model: &Model) -> Self {
        let tasks = (rayon::current_num_threads() * TASKS_PER_THREAD).max(1);
        Self {
            // made by the pool's threads, so that each lands in its thread's heap arena
            datas: (0..tasks)
                .into_par_iter()
                .map(|_| Data::new(model))
                .collect(),
        }
    }

    /// `τ_k = rnea(q_k, v_k, a_k)` for every state k (see [`rnea_batch`]).
    ///
    /// # Errors
    /// As [`rnea_batch`]; a model other than the one the workspaces were made for is
    /// [`MultibodyError::DataMismatch`].
    pub fn rnea(
        &mut self,
        model: &Model,
        qs: &[f64],
        vs: &[f64],
        as_: &[f64],
        tau: &mut [f64],
    ) -> Result<(), MultibodyError> {
        self.qvx(rnea, model, qs, vs, as_, tau)
    }

    /// `q̈_k = aba(q_k, v_k, τ_k)` for every state k (see [`aba_batch`]).
    ///
    /// # Errors
    /// As [`aba_batch`], or [`MultibodyError::DataMismatch`].
    pub fn aba(
        &mut self,
        model: &Model,
        qs: &[f64],
        vs: &[f64],
        taus: &[f64],
        ddq: &mut [f64],
    ) -> Result<(), MultibodyError> {
        self.qvx(aba, model, qs, vs, taus, ddq)
    }

    /// `out_k = f(q_k, v_k, x_k)` (an `nv`-vector) for every state k.
    fn qvx(
        &mut self,
        f: QvxFn,
        model: &Model,
        qs: &[f64],
        vs: &[f64],
        xs: &[f64],
        out: &mut [f64],
    ) -> Result<(), MultibodyError> {
        count(model, qs, &[vs, xs], out.len(), model.nv)?;
        let (nq, nv) = (model.nq, model.nv);
        for_each_state(&mut self.datas, out, nv, |data, k, out| {
            let r = f(
                model,
                data,
                &qs[k * nq..(k + 1) * nq],
                &vs[k * nv..(k + 1) * nv],
                &xs[k * nv..(k + 1) * nv],
            )?;
            out.copy_from_slice(r.as_slice());
            Ok(())
        })
    }

    /// `M(q_k)` for every state k (see [`crba_batch`]).
    ///
    /// # Errors
    /// As [`crba_batch`], or [`MultibodyError::DataMismatch`].
    pub fn crba(
        &mut self,
        model: &Model,
        qs: &[f64],
        mass: &mut [f64],
    ) -> Result<(), MultibodyError> {
        let nn = model.nv * model.nv;
        count(model, qs, &[], mass.len(), nn)?;
        let nq = model.nq;
        for_each_state(&mut self.datas, mass, nn, |data, k, out| {
            let m = crba(model, data, &qs[k * nq..(k + 1) * nq])?;
            out.copy_from_slice(m.as_slice());
            Ok(())
        })
    }
}

/// Evaluate `f(data, k, out_k)` for every state `k`: the states are cut into one contiguous
/// block per workspace (fewer if there are fewer states), run in parallel, each with its own
/// `Data`.
fn for_each_state<F>(
    datas: &mut [Data],
    out: &mut [f64],
    out_per: usize,
    f: F,
) -> Result<(), MultibodyError>
where
    F: Fn(&mut Data, usize, &mut [f64]) -> Result<(), MultibodyError> + Sync,
{
    let n = out.len().checked_div(out_per).unwrap_or(0);
    if n == 0 {
        return Ok(());
    }
    let per_task = n.div_ceil(datas.len().clamp(1, n));
    out.par_chunks_mut(per_task * out_per)
        .zip(datas.par_iter_mut())
        .enumerate()
        .map(|(c, (block, data))| {
            for (j, out_k) in block.chunks_mut(out_per).enumerate() {
                f(data, c * per_task + j, out_k)?;
            }
            Ok(())
        })
        .collect::<Result<(), MultibodyError>>()
}

/// `τ_k = rnea(q_k, v_k, a_k)` for every state k (see [`rnea`]; workspaces made for this call, see [`Batch`]), into `tau` (row-major,
/// `N × nv`).
///
/// # Errors
/// Lengths that are not `N nq` / `N nv`, or the first failing state's error.
pub fn rnea_batch(
    model: &Model,
    qs: &[f64],
    vs: &[f64],
    as_: &[f64],
    tau: &mut [f64],
) -> Result<(), MultibodyError> {
    Batch::new(model).rnea(model, qs, vs, as_, tau)
}

/// `q̈_k = aba(q_k, v_k, τ_k)` for every state k (see [`aba`]; workspaces made for this call, see [`Batch`]), into `ddq` (row-major,
/// `N × nv`).
///
/// # Errors
/// Lengths that are not `N nq` / `N nv`, or the first failing state's error.
pub fn aba_batch(
    model: &Model,
    qs: &[f64],
    vs: &[f64],
    taus: &[f64],
    ddq: &mut [f64],
) -> Result<(), MultibodyError> {
    Batch::new(model).aba(model, qs, vs, taus, ddq)
}

/// `M(q_k)` for every state k (see [`crba`]; workspaces made for this call, see [`Batch`]), into `mass` (`N` matrices of `nv × nv`, each
/// column-major, which for a symmetric matrix is also row-major).
///
/// # Errors
/// A length that is not `N nq` / `N nv²`, or the first failing state's error.
pub fn crba_batch(model: &Model, qs: &[f64], mass: &mut [f64]) -> Result<(), MultibodyError> {
    Batch::new(model).crba(model, qs, mass)
}
