//! The articulated-body algorithm for forward dynamics (Featherstone 2008, Table 7.1), in body
//! coordinates, and forward dynamics by Cholesky factorisation of `M` as a cross-check.
//!
//! Read [`reference::aba`](crate::multibody::reference::aba) first (spatial_v2's `FDab.m`): the
//! single call runs the same three loops as the batch's kernel at one lane (`batch/aba.rs`:
//! `IA{λ(i)} += Xup' * Ia * Xup` on the articulated inertia's 3x3 blocks, a one-dof joint's `U`,
//! `d`, `u` as a column and scalars), so that [`aba`] and
//! [`aba_batch`](crate::multibody::batch::aba_batch) give the same bits.

use crate::error::DimensionError;
use crate::multibody::batch::aba_one;
use crate::multibody::{check_data, check_q, check_v, Data, Model, MultibodyError};
use crate::spatial::Wrench;
use nalgebra::DVector;

/// Forward dynamics `q̈ = M(q)⁻¹ (τ - c(q, v) - g(q))` by the articulated-body algorithm
/// (Featherstone 2008, Table 7.1), body coordinates, gravity as base acceleration `A_0 = -g`:
///
/// - pass 1 (i = 1..n): `V_i = [Ad_{liMi⁻¹}] V_{λ(i)} + S_i q̇_i`, `c_i = [ad_{V_i}] S_i q̇_i`,
///   `I^A_i = G_i`, `p^A_i = -[ad_{V_i}]ᵀ G_i V_i - F_i^ext`
/// - pass 2 (i = n..1): `U_i = I^A_i S_i`, `D_i = S_iᵀ U_i + armature_i`,
///   `u_i = τ_i - S_iᵀ p^A_i`; `I^a = I^A_i - U_i D_i⁻¹ U_iᵀ`, `p^a = p^A_i + I^a c_i + U_i D_i⁻¹ u_i`;
///   `I^A_{λ(i)} += Xᵀ I^a X`, `p^A_{λ(i)} += Xᵀ p^a` with `X = [Ad_{liMi⁻¹}]`
/// - pass 3 (i = 1..n): `A' = X A_{λ(i)} + c_i`, `q̈_i = D_i⁻¹ (u_i - U_iᵀ A')`, `A_i = A' + S_i q̈_i`
///
/// Returns `data.ddq`. O(n). Should the recursion meet a joint inertia `D_i ≤ 0` while `M` is
/// positive definite (digits lost to a light body carrying a heavy subtree), the answer comes from
/// the sparse Cholesky factorisation of `M` instead ([`forward_dynamics_cholesky`](crate::multibody::forward_dynamics_cholesky)).
///
/// # Errors
/// Wrong lengths, non-finite entries, a non-unit quaternion, or a singular `M` (a massless
/// subtree moved by a joint).
///
/// ```
/// use rigid::multibody::{aba, puma560, rnea, Data, Puma560Options};
/// let model = puma560(Puma560Options::default());
/// let mut data = Data::new(&model);
/// let (q, v, a) = ([0.1; 6], [0.2; 6], [0.3; 6]);
/// let tau = rnea(&model, &mut data, &q, &v, &a)?.clone();
/// let ddq = aba(&model, &mut data, &q, &v, tau.as_slice())?;
/// assert!(ddq.iter().zip(&a).all(|(x, y)| (x - y).abs() < 1e-9));
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn aba<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
) -> Result<&'a DVector<f64>, MultibodyError> {
    check_inputs(model, data, q, v, tau)?;
    match aba_one(model, data, q, v, tau, None) {
        Err(MultibodyError::NotPositiveDefinite) => cholesky_fallback(model, data, q, v, tau, None),
        r => r.map(|()| &data.ddq),
    }
}

/// [`aba`] with an external wrench `fext[i]` on each body, in body i's frame.
///
/// # Errors
/// As [`aba`], and `fext.len() != njoints`.
pub fn aba_with_external<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    fext: &[Wrench],
) -> Result<&'a DVector<f64>, MultibodyError> {
    check_inputs(model, data, q, v, tau)?;
    DimensionError::check("fext", model.njoints(), fext.len())?;
    match aba_one(model, data, q, v, tau, Some(fext)) {
        Err(MultibodyError::NotPositiveDefinite) => {
            cholesky_fallback(model, data, q, v, tau, Some(fext))
        }
        r => r.map(|()| &data.ddq),
    }
}

/// When ABA meets a joint inertia `D ≤ 0`, `M` may still be positive definite: the recursion's
/// subtraction `I^A - U D⁻¹ Uᵀ` loses every digit when a light body carries a heavy subtree (mass
/// ratios of 1e10 and more). Solve `M q̈ = τ - b` by the sparse Cholesky factorisation of `M`
/// instead ([`forward_dynamics_cholesky`](crate::multibody::forward_dynamics_cholesky)); a massless subtree makes `M` singular and stays an
/// error. No allocation (`data.nle` lends its storage for the zero acceleration).
fn cholesky_fallback<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    fext: Option<&[Wrench]>,
) -> Result<&'a DVector<f64>, MultibodyError> {
    // b = rnea(q, v, 0) with the external wrenches: c + g - Jᵀ f
    let mut zero = std::mem::take(&mut data.nle);
    zero.fill(0.0);
    let bias = match fext {
        Some(f) => super::rnea_with_external(model, data, q, v, zero.as_slice(), f).map(|_| ()),
        None => super::rnea(model, data, q, v, zero.as_slice()).map(|_| ()),
    };
    data.nle = zero;
    bias?;
    data.nle.copy_from(&data.tau);
    super::crba(model, data, q)?;
    super::cholesky::ltl_solve(model, data, tau)
}

/// The argument checks shared by [`aba`], [`aba_with_external`] and the ABA derivatives.
pub(crate) fn check_inputs(
    model: &Model,
    data: &Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
) -> Result<(), MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    check_v(model, "v", v)?;
    check_v(model, "tau", tau)
}
