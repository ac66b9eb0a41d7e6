//! The batches' threads: a [`Batch`]'s workspaces per rayon task, the states cut into contiguous
//! blocks per task, the checks of each chunk of states, and the ABA derivatives as single calls
//! spread across the cores.

use super::rows;
use super::simd::{self, Algo, Lanes};
use super::CHUNK;
use crate::error::DimensionError;
use crate::multibody::{check_q, check_v, Data, Model, MultibodyError};
use rayon::prelude::*;

/// Tasks per rayon thread: a few, so that a slow thread can be helped, each with its own
/// workspaces.
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

/// The workspaces of the batch entry points: one lane workspace (RNEA, ABA, CRBA, the RNEA
/// derivatives) and one [`Data`] (the ABA derivatives) per task, a few tasks per thread of the
/// current rayon pool, made once and reused by every call, so that a batch call allocates
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
/// assert!(batch.lanes() >= 2); // states side by side in the vector registers
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Batch {
    datas: Vec<Data>,
    lanes: Vec<Lanes>,
    /// The joints of the model the workspaces were made for (`Plan::joints_key`, as a `Data`
    /// keeps it), compared by [`Batch::follow`].
    joints_key: u64,
    /// The caller's velocity order (empty: rigid's) and a buffer per task to reorder through.
    order: rows::Order,
    scratch: Vec<Vec<f64>>,
}

impl Batch {
    /// Workspaces for `model`, for the current rayon pool (`TASKS_PER_THREAD` per thread), with
    /// the widest lanes the CPU has (8 with AVX-512, 4 with AVX2, else 2), or the width the
    /// environment variable `RIGID_LANES` gives (2, 4 or 8: the same lanes, and so the same
    /// bits, on two machines; docs/simd.md).
    #[must_use]
    pub fn new(model: &Model) -> Self {
        Self::with_lanes(model, simd::default_width())
    }

    /// [`Batch::new`] with `width` lanes (2, 4 or 8; anything else is 2), to compare widths: a
    /// width wider than the CPU's vector unit runs the same kernels on narrower instructions.
    #[must_use]
    pub fn with_lanes(model: &Model, width: usize) -> Self {
        let tasks = (rayon::current_num_threads() * TASKS_PER_THREAD).max(1);
        Self {
            // made by the pool's threads, so that each lands in its thread's heap arena
            datas: (0..tasks)
                .into_par_iter()
                .map(|_| Data::new(model))
                .collect(),
            lanes: (0..tasks)
                .into_par_iter()
                .map(|_| Lanes::new(model, width))
                .collect(),
            joints_key: model.plan().joints_key,
            order: rows::Order::default(),
            scratch: vec![Vec::new(); tasks],
        }
    }

    /// The workspaces made anew for `model` when it has their shape (`nq`, `nv`, joints) but
    /// not the joints (parents, types, axes) of the model they were made for: they keep what
    /// they took from it when made (the constant motion subspaces, the tree of the derivatives,
    /// the entries of `M` outside the subtrees, which CRBA never writes), and a batch may be
    /// handed any model of its shape (any two 6-joint arms). Another shape is left to the
    /// checks that refuse it.
    fn follow(&mut self, model: &Model) {
        let key = model.plan().joints_key;
        if key == self.joints_key || !self.lanes.iter().all(|l| l.fits(model)) {
            return;
        }
        let width = self.lanes();
        for data in &mut self.datas {
            *data = Data::new(model);
        }
        for lanes in &mut self.lanes {
            *lanes = Lanes::new(model, width);
        }
        self.joints_key = key;
    }

    /// This batch for states whose velocity-space numbers are in another order than rigid's:
    /// entry `k` of the caller's `v`, `a`, `τ` and `q̈` is rigid's entry `order[k]`, and entry
    /// `(r, c)` of its `M` and derivatives is rigid's `(order[r], order[c])`, as in Pinocchio's
    /// layout ([`PinocchioLayout::v_index`](crate::interop::PinocchioLayout::v_index),
    /// a free-flyer's linear velocity before its angular one). The configurations stay in
    /// rigid's layout. A chunk of 64 states at a time, the inputs are reordered into a buffer
    /// and the results in place while they are in the cache: no pass over whole arrays, no
    /// allocation per call, and the kernels are those of rigid's order. Only the entries the
    /// order moves are reordered (6 per free-flyer in Pinocchio's layout), and the identity is
    /// no order at all. (The rows are read in order as they are reordered, not prefetched a
    /// chunk ahead as without an order.)
    ///
    /// ```
    /// use rigid::multibody::{batch::Batch, Model, Puma560Options, puma560};
    /// let model = puma560(Puma560Options::default());
    /// let (nq, nv, n) = (model.nq(), model.nv(), 3);
    /// let order = [5, 4, 3, 2, 1, 0]; // the caller lists the joints from the wrist down
    /// let mut reversed = Batch::new(&model).with_velocity_order(&model, &order)?;
    /// let (qs, vs, a) = (vec![0.3; n * nq], vec![0.1; n * nv], vec![0.0; n * nv]);
    /// let (mut tau, mut tau_r) = (vec![0.0; n * nv], vec![0.0; n * nv]);
    /// Batch::new(&model).rnea(&model, &qs, &vs, &a, &mut tau)?;
    /// reversed.rnea(&model, &qs, &vs, &a, &mut tau_r)?; // vs is the same in either order
    /// assert!(tau_r.chunks(nv).zip(tau.chunks(nv)).all(|(r, t)| (0..nv).all(|k| r[k] == t[order[k]])));
    /// # Ok::<(), rigid::multibody::MultibodyError>(())
    /// ```
    ///
    /// # Errors
    /// `order` is not `nv` long ([`MultibodyError::Dimension`]), or an entry is not below `nv`
    /// or repeats an earlier one ([`MultibodyError::OutOfRange`], naming its position).
    pub fn with_velocity_order(
        mut self,
        model: &Model,
        order: &[usize],
    ) -> Result<Self, MultibodyError> {
        let nv = model.nv;
        DimensionError::check("order", nv, order.len())?;
        let mut seen = vec![false; nv];
        for (k, &o) in order.iter().enumerate() {
            if o >= nv || std::mem::replace(&mut seen[o], true) {
                return Err(MultibodyError::OutOfRange {
                    what: "velocity order (a permutation of 0..nv) entry",
                    index: k,
                });
            }
        }
        self.order = rows::Order::new(order);
        if !self.order.is_empty() {
            // a chunk's v and x rows (CHUNK states, at least a pack) and one result
            let len = 2 * CHUNK.max(8) * nv + nv * nv;
            for s in &mut self.scratch {
                *s = vec![0.0; len];
            }
        }
        Ok(self)
    }

    /// The number of states computed side by side (the lanes of the vector registers).
    #[must_use]
    pub fn lanes(&self) -> usize {
        self.lanes.first().map_or(2, Lanes::width)
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
        self.packs(Algo::Rnea, model, qs, (vs, "v"), (as_, "a"), tau, &mut [])
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
        self.packs(Algo::Aba, model, qs, (vs, "v"), (taus, "tau"), ddq, &mut [])
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
        self.packs(Algo::Crba, model, qs, (&[], "v"), (&[], "a"), mass, &mut [])
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
        self.packs(
            Algo::CrbaLower,
            model,
            qs,
            (&[], "v"),
            (&[], "a"),
            packed,
            &mut [],
        )
    }

    /// `algo` for every state, in packs of [`Batch::lanes`] states, the packs cut into one
    /// contiguous block per task, run in parallel; each block in chunks of [`CHUNK`] states,
    /// checked as a single call checks them and then computed. `vs` and `xs` (named for the errors) are empty
    /// for CRBA; `out2` is the derivatives' `∂τ/∂v` (its length checked by the caller), empty
    /// for the others.
    #[allow(clippy::too_many_arguments)]
    fn packs(
        &mut self,
        algo: Algo,
        model: &Model,
        qs: &[f64],
        (vs, v_name): (&[f64], &'static str),
        (xs, x_name): (&[f64], &'static str),
        out: &mut [f64],
        out2: &mut [f64],
    ) -> Result<(), MultibodyError> {
        let per = algo.per_state(model.nv);
        let inputs: &[&[f64]] = if algo == Algo::Crba || algo == Algo::CrbaLower {
            &[]
        } else {
            &[vs, xs]
        };
        let n = count(model, qs, inputs, out.len(), per)?;
        if algo == Algo::RneaDerivatives && n * per > 0 {
            // as the single call, before any state is looked at
            crate::multibody::algorithms::require_constant_subspaces(
                model,
                "the analytical derivatives",
            )?;
        }
        if !self.lanes.iter().all(|l| l.fits(model)) {
            let d = &self.datas[0];
            return Err(MultibodyError::DataMismatch {
                njoints: d.placements.len(),
                nq: d.sin_cos.len(),
                nv: d.tau.len(),
            });
        }
        self.follow(model);
        if n == 0 || per == 0 {
            return Ok(());
        }
        let w = self.lanes();
        let per_task = per_task(n, self.lanes.len()).div_ceil(w) * w;
        self.order.fits(model.nv)?;
        let (nq, nv, order) = (model.nq, model.nv, &self.order);
        let task = |c: usize, block: &mut [f64], block2: &mut [f64], work: Work| {
            let (lanes, scratch) = work;
            let chunk = (CHUNK / w).max(1) * w * per;
            let mut first = c * per_task;
            let mut block2 = block2.chunks_mut(chunk);
            for sub in block.chunks_mut(chunk) {
                for k in first..first + sub.len() / per {
                    check_q(model, &qs[k * nq..][..nq])?;
                    if !inputs.is_empty() {
                        check_v(model, v_name, &vs[k * nv..][..nv])?;
                        check_v(model, x_name, &xs[k * nv..][..nv])?;
                    }
                }
                let (sub2, states) = (block2.next().unwrap_or_default(), sub.len() / per);
                if order.is_empty() {
                    lanes.run(algo, model, qs, vs, xs, first, sub, sub2)?;
                } else {
                    // the chunk's v and x rows into rigid's order in the task's buffer, then
                    // its results into the caller's in place (the kernels see rigid's order)
                    let (v, rest) = scratch.split_at_mut(CHUNK.max(8) * nv);
                    let (x, tmp) = rest.split_at_mut(CHUNK.max(8) * nv);
                    let (v, x) = if inputs.is_empty() {
                        (&[][..], &[][..])
                    } else {
                        let (v, x) = (&mut v[..states * nv], &mut x[..states * nv]);
                        let span = first * nv..(first + states) * nv;
                        rows::rows_in_order(&vs[span.clone()], order, v);
                        rows::rows_in_order(&xs[span], order, x);
                        (&*v, &*x)
                    };
                    let q = &qs[first * nq..(first + states) * nq];
                    lanes.run(algo, model, q, v, x, 0, sub, &mut *sub2)?;
                    for y in sub.chunks_exact_mut(per).chain(sub2.chunks_exact_mut(per)) {
                        rows::order_out(algo, y, order, tmp);
                    }
                }
                first += states;
            }
            Ok(())
        };
        let tasks = out
            .par_chunks_mut(per_task * per)
            .zip(self.lanes.par_iter_mut().zip(self.scratch.par_iter_mut()))
            .enumerate();
        if algo == Algo::RneaDerivatives {
            tasks
                .zip(out2.par_chunks_mut(per_task * per))
                .map(|((c, (block, work)), block2)| task(c, block, block2, work))
                .collect()
        } else {
            tasks
                .map(|(c, (block, work))| task(c, block, &mut [], work))
                .collect()
        }
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
        let (v, a) = ((vs, "v"), (as_, "a"));
        self.packs(Algo::RneaDerivatives, model, qs, v, a, dtau_dq, dtau_dv)
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
        self.order.fits(model.nv)?;
        self.follow(model);
        let per_task = per_task(n, self.datas.len());
        let (nv, order) = (model.nv, &self.order);
        let blocks = dqdd_dq
            .par_chunks_mut(per_task * nn)
            .zip(dqdd_dv.par_chunks_mut(per_task * nn))
            .zip(dqdd_dtau.par_chunks_mut(per_task * nn));
        blocks
            .zip(self.datas.par_iter_mut().zip(self.scratch.par_iter_mut()))
            .enumerate()
            .map(|(c, (((bq, bv), bt), (data, scratch)))| {
                let outs = bq
                    .chunks_mut(nn)
                    .zip(bv.chunks_mut(nn))
                    .zip(bt.chunks_mut(nn));
                for (j, ((oq, ov), ot)) in outs.enumerate() {
                    let (q, v, t) = state(model, c * per_task + j, qs, vs, taus);
                    let d = if order.is_empty() {
                        crate::multibody::aba_derivatives(model, data, q, v, t)?
                    } else {
                        // checked in the caller's order (errors name its indices), then v and
                        // τ into rigid's (the first 2 nv numbers of the buffer)
                        check_v(model, "v", v)?;
                        check_v(model, "tau", t)?;
                        let (vr, tr) = scratch[..2 * nv].split_at_mut(nv);
                        rows::rows_in_order(v, order, vr);
                        rows::rows_in_order(t, order, tr);
                        crate::multibody::aba_derivatives(model, data, q, vr, tr)?
                    };
                    row_major(d.dqdd_dq, oq);
                    row_major(d.dqdd_dv, ov);
                    ot.copy_from_slice(d.dqdd_dtau.as_slice()); // symmetric
                    if !order.is_empty() {
                        for y in [oq, ov, ot] {
                            rows::order_out(Algo::Crba, y, order, scratch);
                        }
                    }
                }
                Ok(())
            })
            .collect()
    }
}

/// A task's lane workspace and its buffer to reorder results through.
type Work<'a> = (&'a mut Lanes, &'a mut Vec<f64>);

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
