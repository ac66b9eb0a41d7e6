//! Batch evaluation of many states at once across the cores (rayon): inverse dynamics, forward
//! dynamics, mass matrices and the derivatives of inverse and forward dynamics for `N` states,
//! each written to a caller-owned, row-major output.
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

/// `rnea` and `aba` share one shape: `(q, v, x) ↦ nv-vector` (also used by
/// [`crate::timing`]'s loops of single calls).
pub(crate) type QvxFn = for<'a> fn(
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
        for_each_state(&mut self.datas, out, model.nv, |data, k, out| {
            let (q, v, x) = state(model, k, qs, vs, xs);
            let r = f(model, data, q, v, x)?;
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
        self.crba_into(model, qs, mass, model.nv * model.nv, |m, _, out| {
            out.copy_from_slice(m);
            Ok(())
        })
    }

    /// The lower triangle of `M(q_k)` for every state k (see [`crba_lower_batch`]).
    ///
    /// # Errors
    /// As [`crba_lower_batch`], or [`MultibodyError::DataMismatch`].
    pub fn crba_lower(
        &mut self,
        model: &Model,
        qs: &[f64],
        packed: &mut [f64],
    ) -> Result<(), MultibodyError> {
        let nv = model.nv;
        self.crba_into(model, qs, packed, nv * (nv + 1) / 2, pack_lower)
    }

    /// `write(M(q_k) column-major, nv, out_k)` for every state k, `per` numbers per state.
    fn crba_into(
        &mut self,
        model: &Model,
        qs: &[f64],
        out: &mut [f64],
        per: usize,
        write: impl Fn(&[f64], usize, &mut [f64]) -> Result<(), DimensionError> + Sync,
    ) -> Result<(), MultibodyError> {
        count(model, qs, &[], out.len(), per)?;
        let (nq, nv) = (model.nq, model.nv);
        for_each_state(&mut self.datas, out, per, |data, k, out_k| {
            let m = crba(model, data, &qs[k * nq..(k + 1) * nq])?;
            Ok(write(m.as_slice(), nv, out_k)?)
        })
    }
}

/// The lower triangle of the column-major `nv x nv` matrix `m` into `out`, column by column
/// (LAPACK's packed storage `'L'`: column `j`'s rows `j..nv` at `j nv − j(j−1)/2`, which is also
/// the upper triangle row by row), as [`crba_lower_batch`] writes each state.
///
/// ```
/// let m = [1.0, 2.0, 3.0, 2.0, 4.0, 5.0, 3.0, 5.0, 6.0]; // 3x3, column-major
/// let mut packed = [0.0; 6];
/// rigid::multibody::batch::pack_lower(&m, 3, &mut packed)?;
/// assert_eq!(packed, [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
/// # Ok::<(), rigid::error::DimensionError>(())
/// ```
///
/// # Errors
/// `m` not `nv²` long, or `out` not `nv(nv+1)/2`.
pub fn pack_lower(m: &[f64], nv: usize, out: &mut [f64]) -> Result<(), DimensionError> {
    DimensionError::check("m", nv * nv, m.len())?;
    DimensionError::check("out", nv * (nv + 1) / 2, out.len())?;
    let mut at = 0;
    for j in 0..nv {
        out[at..at + nv - j].copy_from_slice(&m[j * nv + j..(j + 1) * nv]);
        at += nv - j;
    }
    Ok(())
}

/// Derivatives for many states: `nv x nv` matrices written row-major, one after the other.
impl Batch {
    /// `∂τ/∂q` and `∂τ/∂v` at `(q_k, v_k, a_k)` for every state k (see [`rnea_derivatives_batch`]).
    ///
    /// # Errors
    /// As [`rnea_derivatives_batch`], or [`MultibodyError::DataMismatch`].
    pub fn rnea_derivatives(
        &mut self,
        model: &Model,
        qs: &[f64],
        vs: &[f64],
        as_: &[f64],
        dtau_dq: &mut [f64],
        dtau_dv: &mut [f64],
    ) -> Result<(), MultibodyError> {
        let nn = model.nv * model.nv;
        let n = count(model, qs, &[vs, as_], dtau_dq.len(), nn)?;
        DimensionError::check("dtau_dv", n * nn, dtau_dv.len())?;
        if n * nn == 0 {
            return Ok(());
        }
        let per_task = per_task(n, self.datas.len());
        let blocks = dtau_dq
            .par_chunks_mut(per_task * nn)
            .zip(dtau_dv.par_chunks_mut(per_task * nn));
        blocks
            .zip(self.datas.par_iter_mut())
            .enumerate()
            .map(|(c, ((bq, bv), data))| {
                for (j, (oq, ov)) in bq.chunks_mut(nn).zip(bv.chunks_mut(nn)).enumerate() {
                    let (q, v, a) = state(model, c * per_task + j, qs, vs, as_);
                    let d = super::rnea_derivatives(model, data, q, v, a)?;
                    row_major(d.dtau_dq, oq);
                    row_major(d.dtau_dv, ov);
                }
                Ok(())
            })
            .collect()
    }

    /// `∂q̈/∂q`, `∂q̈/∂v` and `∂q̈/∂τ = M⁻¹` at `(q_k, v_k, τ_k)` for every state k (see
    /// [`aba_derivatives_batch`]).
    ///
    /// # Errors
    /// As [`aba_derivatives_batch`], or [`MultibodyError::DataMismatch`].
    #[allow(clippy::too_many_arguments)]
    pub fn aba_derivatives(
        &mut self,
        model: &Model,
        qs: &[f64],
        vs: &[f64],
        taus: &[f64],
        dqdd_dq: &mut [f64],
        dqdd_dv: &mut [f64],
        dqdd_dtau: &mut [f64],
    ) -> Result<(), MultibodyError> {
        let nn = model.nv * model.nv;
        let n = count(model, qs, &[vs, taus], dqdd_dq.len(), nn)?;
        DimensionError::check("dqdd_dv", n * nn, dqdd_dv.len())?;
        DimensionError::check("dqdd_dtau", n * nn, dqdd_dtau.len())?;
        if n * nn == 0 {
            return Ok(());
        }
        let per_task = per_task(n, self.datas.len());
        let blocks = dqdd_dq
            .par_chunks_mut(per_task * nn)
            .zip(dqdd_dv.par_chunks_mut(per_task * nn))
            .zip(dqdd_dtau.par_chunks_mut(per_task * nn));
        blocks
            .zip(self.datas.par_iter_mut())
            .enumerate()
            .map(|(c, (((bq, bv), bt), data))| {
                let outs = bq
                    .chunks_mut(nn)
                    .zip(bv.chunks_mut(nn))
                    .zip(bt.chunks_mut(nn));
                for (j, ((oq, ov), ot)) in outs.enumerate() {
                    let (q, v, t) = state(model, c * per_task + j, qs, vs, taus);
                    let d = super::aba_derivatives(model, data, q, v, t)?;
                    row_major(d.dqdd_dq, oq);
                    row_major(d.dqdd_dv, ov);
                    ot.copy_from_slice(d.dqdd_dtau.as_slice()); // symmetric
                }
                Ok(())
            })
            .collect()
    }
}

/// States per task when `n ≥ 1` states are cut into at most `tasks` contiguous blocks.
fn per_task(n: usize, tasks: usize) -> usize {
    n.div_ceil(tasks.clamp(1, n))
}

/// State `k`'s `(q, v, x)` from row-major inputs.
fn state<'a>(
    model: &Model,
    k: usize,
    qs: &'a [f64],
    vs: &'a [f64],
    xs: &'a [f64],
) -> (&'a [f64], &'a [f64], &'a [f64]) {
    let (nq, nv) = (model.nq, model.nv);
    (
        &qs[k * nq..][..nq],
        &vs[k * nv..][..nv],
        &xs[k * nv..][..nv],
    )
}

/// `m` (column-major) into `out`, row-major.
fn row_major(m: &nalgebra::DMatrix<f64>, out: &mut [f64]) {
    let n = m.ncols();
    for (r, row) in out.chunks_exact_mut(n).enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = m[(r, c)];
        }
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
    let per_task = per_task(n, datas.len());
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

/// The lower triangle of `M(q_k)` for every state k (see [`crba`]; workspaces made for this call,
/// see [`Batch`]), packed: `N` blocks of `nv(nv+1)/2` numbers, each the columns' entries on and
/// below the diagonal, column after column (LAPACK's packed storage `'L'`, which is also the
/// upper triangle row by row). Half the memory written of [`crba_batch`]'s full matrices, for
/// callers that factor or store `M` (it is symmetric).
///
/// ```
/// use rigid::multibody::{batch, crba, double_pendulum, Data};
/// let model = double_pendulum();
/// let qs = [0.3, 0.0, -0.2, 0.5]; // two states
/// let mut packed = [0.0; 2 * 3];
/// batch::crba_lower_batch(&model, &qs, &mut packed)?;
/// let mut data = Data::new(&model);
/// let m = crba(&model, &mut data, &qs[2..])?;
/// assert_eq!(packed[3..], [m[(0, 0)], m[(1, 0)], m[(1, 1)]]);
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
///
/// # Errors
/// A length that is not `N nq` / `N nv(nv+1)/2`, or the first failing state's error.
pub fn crba_lower_batch(
    model: &Model,
    qs: &[f64],
    packed: &mut [f64],
) -> Result<(), MultibodyError> {
    Batch::new(model).crba_lower(model, qs, packed)
}

/// `∂τ/∂q` and `∂τ/∂v` at `(q_k, v_k, a_k)` for every state k (see
/// [`rnea_derivatives`](super::rnea_derivatives); workspaces made for this call, see [`Batch`]),
/// into `dtau_dq` and `dtau_dv` (each `N` matrices of `nv x nv`, row-major, one after the other).
///
/// # Errors
/// Lengths that are not `N nq` / `N nv` / `N nv²`, or the first failing state's error.
///
/// ```
/// use rigid::multibody::{batch, puma560, Puma560Options};
/// let model = puma560(Puma560Options::default());
/// let (nq, nv, n) = (model.nq(), model.nv(), 3);
/// let (qs, zeros) = (vec![0.1; n * nq], vec![0.0; n * nv]);
/// let (mut dq, mut dv) = (vec![0.0; n * nv * nv], vec![0.0; n * nv * nv]);
/// batch::rnea_derivatives_batch(&model, &qs, &zeros, &zeros, &mut dq, &mut dv)?;
/// assert!(dv.iter().all(|x| *x == 0.0)); // at rest, τ does not depend on v
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn rnea_derivatives_batch(
    model: &Model,
    qs: &[f64],
    vs: &[f64],
    as_: &[f64],
    dtau_dq: &mut [f64],
    dtau_dv: &mut [f64],
) -> Result<(), MultibodyError> {
    Batch::new(model).rnea_derivatives(model, qs, vs, as_, dtau_dq, dtau_dv)
}

/// `∂q̈/∂q`, `∂q̈/∂v`, `∂q̈/∂τ = M⁻¹` at `(q_k, v_k, τ_k)` for every state k (see
/// [`aba_derivatives`](super::aba_derivatives); workspaces made for this call, see [`Batch`]),
/// each `N` matrices of `nv x nv`, row-major, one after the other.
///
/// # Errors
/// Lengths that are not `N nq` / `N nv` / `N nv²`, or the first failing state's error.
pub fn aba_derivatives_batch(
    model: &Model,
    qs: &[f64],
    vs: &[f64],
    taus: &[f64],
    dqdd_dq: &mut [f64],
    dqdd_dv: &mut [f64],
    dqdd_dtau: &mut [f64],
) -> Result<(), MultibodyError> {
    Batch::new(model).aba_derivatives(model, qs, vs, taus, dqdd_dq, dqdd_dv, dqdd_dtau)
}
