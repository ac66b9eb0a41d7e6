//! Forward dynamics through the mass matrix: `M(q) q̈ = τ - nle(q, v)` by CRBA and the sparse
//! `LᵀL` factorisation that follows the tree (Featherstone 2008, §6.5).

use super::super::{check_v, Data, Model, MultibodyError};
use nalgebra::DVector;

/// The parent degree of freedom `λ(k)`: the previous dof of the same joint, else the last dof of
/// the parent joint (`None` at the root). `M_ki ≠ 0` (i < k) only for `i` on the chain
/// `λ(k), λ(λ(k)), …`.
#[inline]
fn dof_parent(model: &Model, k: usize) -> Option<usize> {
    let j = &model.joints()[model.plan().dof_joint[k]];
    if k > j.idx_v {
        return Some(k - 1);
    }
    j.parent.map(|p| {
        let pj = &model.joints()[p.0];
        pj.idx_v + pj.nv - 1
    })
}

/// Forward dynamics by `M(q) q̈ = τ - nle(q, v)`: CRBA, RNEA for `nle`, then the sparse
/// factorisation `M = Lᵀ L` that follows the tree (Featherstone 2008, §6.5, Table 6.3, "LTL":
/// fill-in stays on each dof's chain of ancestors `λ(k)`, so it costs O(Σ_k depth(k)²) rather than
/// O(nv³)), and the two sparse triangular solves `y = L⁻ᵀ (τ - nle)`, `q̈ = L⁻¹ y`. No
/// allocation. A cross-check of [`aba`](crate::multibody::aba). Returns `data.ddq`.
///
/// # Errors
/// As [`aba`](crate::multibody::aba), or [`MultibodyError::NotPositiveDefinite`].
pub fn forward_dynamics_cholesky<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
) -> Result<&'a DVector<f64>, MultibodyError> {
    check_v(model, "tau", tau)?;
    super::nonlinear_effects(model, data, q, v)?;
    super::crba(model, data, q)?;
    ltl_solve(model, data, tau)
}

/// `q̈ = M⁻¹ (τ - data.nle)` with `M = data.mass_matrix` factorised as `LᵀL` in `data.chol`;
/// returns `data.ddq`.
pub(crate) fn ltl_solve<'a>(
    model: &Model,
    data: &'a mut Data,
    tau: &[f64],
) -> Result<&'a DVector<f64>, MultibodyError> {
    ltl_factor(model, data)?;
    let x = data.ddq.as_mut_slice();
    for k in 0..model.nv {
        x[k] = tau[k] - data.nle[k];
    }
    let (L, lambda) = (data.chol.as_slice(), &data.dof_parent);
    ltl_solve_transposed(L, lambda, x);
    ltl_solve_lower(L, lambda, x);
    Ok(&data.ddq)
}

/// Factorises `M = data.mass_matrix` as `LᵀL` into `data.chol` (lower triangle, `L[(k, i)]` for
/// `i` on the chain of `k`) and fills `data.dof_parent` with `λ(k)` (`usize::MAX` at a root).
///
/// # Errors
/// [`MultibodyError::NotPositiveDefinite`] when a pivot is not positive.
pub(crate) fn ltl_factor(model: &Model, data: &mut Data) -> Result<(), MultibodyError> {
    let n = model.nv;
    let lambda = &mut data.dof_parent;
    for (k, l) in lambda.iter_mut().enumerate() {
        *l = dof_parent(model, k).unwrap_or(NONE);
    }
    let lambda = &data.dof_parent;
    data.chol.copy_from(&data.mass_matrix);
    // column-major: L[(k, i)] = L[i * n + k]; LTL in the lower triangle, L[(k, i)] for i on k's chain
    let L = data.chol.as_mut_slice();
    for k in (0..n).rev() {
        let d = L[k * n + k];
        if d <= 0.0 || !d.is_finite() {
            return Err(MultibodyError::NotPositiveDefinite);
        }
        let a = d.sqrt();
        L[k * n + k] = a;
        let mut i = lambda[k];
        while i != NONE {
            L[i * n + k] /= a;
            i = lambda[i];
        }
        let mut i = lambda[k];
        while i != NONE {
            let lki = L[i * n + k];
            let mut j = i;
            while j != NONE {
                L[j * n + i] -= lki * L[j * n + k];
                j = lambda[j];
            }
            i = lambda[i];
        }
    }
    Ok(())
}

/// No parent dof (a root joint's first dof).
pub(crate) const NONE: usize = usize::MAX;

/// `x ← L⁻ᵀ x` for the factor of [`ltl_factor`] (`L` column-major `nv x nv`, `lambda` the
/// parent dofs): back substitution from the last dof; fill-in stays on the chains of the
/// nonzero entries of `x`.
pub(crate) fn ltl_solve_transposed(L: &[f64], lambda: &[usize], x: &mut [f64]) {
    let n = x.len();
    for k in (0..n).rev() {
        x[k] /= L[k * n + k];
        let xk = x[k];
        let mut j = lambda[k];
        while j != NONE {
            x[j] -= L[j * n + k] * xk;
            j = lambda[j];
        }
    }
}

/// `x ← L⁻¹ x` for the factor of [`ltl_factor`].
pub(crate) fn ltl_solve_lower(L: &[f64], lambda: &[usize], x: &mut [f64]) {
    let n = x.len();
    for k in 0..n {
        let mut s = x[k];
        let mut j = lambda[k];
        while j != NONE {
            s -= L[j * n + k] * x[j];
            j = lambda[j];
        }
        x[k] = s / L[k * n + k];
    }
}
