//! The batch entry points as single calls: each makes its workspaces ([`Batch`]) for the call,
//! on the current rayon pool. Keep a [`Batch`] to call again without allocating.

use super::Batch;
use crate::multibody::{Model, MultibodyError};

/// `τ_k = rnea(q_k, v_k, a_k)` for every state k (see [`rnea`](crate::multibody::rnea); workspaces made for this call, see [`Batch`]), into `tau` (row-major,
/// `N × nv`).
///
/// # Errors
/// Lengths that are not `N nq` / `N nv`, or a failing state's error (the first
/// in its task's block; with several threads, not necessarily the first of all).
pub fn rnea_batch(
    model: &Model,
    qs: &[f64],
    vs: &[f64],
    as_: &[f64],
    tau: &mut [f64],
) -> Result<(), MultibodyError> {
    Batch::new(model).rnea(model, qs, vs, as_, tau)
}

/// `q̈_k = aba(q_k, v_k, τ_k)` for every state k (see [`aba`](crate::multibody::aba); workspaces made for this call, see [`Batch`]), into `ddq` (row-major,
/// `N × nv`).
///
/// # Errors
/// Lengths that are not `N nq` / `N nv`, or a failing state's error (the first
/// in its task's block; with several threads, not necessarily the first of all).
pub fn aba_batch(
    model: &Model,
    qs: &[f64],
    vs: &[f64],
    taus: &[f64],
    ddq: &mut [f64],
) -> Result<(), MultibodyError> {
    Batch::new(model).aba(model, qs, vs, taus, ddq)
}

/// `M(q_k)` for every state k (see [`crba`](crate::multibody::crba); workspaces made for this call, see [`Batch`]), into `mass` (`N` matrices of `nv × nv`, each
/// column-major, which for a symmetric matrix is also row-major).
///
/// # Errors
/// A length that is not `N nq` / `N nv²`, or a failing state's error (the first
/// in its task's block; with several threads, not necessarily the first of all).
pub fn crba_batch(model: &Model, qs: &[f64], mass: &mut [f64]) -> Result<(), MultibodyError> {
    Batch::new(model).crba(model, qs, mass)
}

/// The lower triangle of `M(q_k)` for every state k (see [`crba`](crate::multibody::crba); workspaces made for this call,
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
/// let single = [m[(0, 0)], m[(1, 0)], m[(1, 1)]];
/// // the same numbers, bit for bit (the lanes take the single call's steps in its order)
/// assert_eq!(packed[3..], single);
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
///
/// # Errors
/// A length that is not `N nq` / `N nv(nv+1)/2`, or a failing state's error (the first
/// in its task's block; with several threads, not necessarily the first of all).
pub fn crba_lower_batch(
    model: &Model,
    qs: &[f64],
    packed: &mut [f64],
) -> Result<(), MultibodyError> {
    Batch::new(model).crba_lower(model, qs, packed)
}

/// `∂τ/∂q` and `∂τ/∂v` at `(q_k, v_k, a_k)` for every state k (see
/// [`rnea_derivatives`](crate::multibody::rnea_derivatives); workspaces made for this call, see [`Batch`]),
/// into `dtau_dq` and `dtau_dv` (each `N` matrices of `nv x nv`, row-major, one after the other).
/// The states run side by side in SIMD lanes (`derivatives.rs`: Carpentier & Mansard, RSS 2018,
/// Alg. 1, in each tree's root frame, in the single call's order of operations).
///
/// # Errors
/// Lengths that are not `N nq` / `N nv` / `N nv²`, a joint whose motion subspace depends on `q`
/// ([`MultibodyError::Unsupported`], as the single call), or a failing state's error (the first
/// in its task's block; with several threads, not necessarily the first of all).
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
/// [`aba_derivatives`](crate::multibody::aba_derivatives); workspaces made for this call, see [`Batch`]),
/// each `N` matrices of `nv x nv`, row-major, one after the other.
///
/// # Errors
/// Lengths that are not `N nq` / `N nv` / `N nv²`, or a failing state's error (the first
/// in its task's block; with several threads, not necessarily the first of all).
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
