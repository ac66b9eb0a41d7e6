//! Constrained inverse dynamics: the torques and constraint forces that produce a given `q̈`.

use super::dynamics::constraint_rows;
use super::solver::proximal_solve;
use super::workspace::ConstraintData;
use super::{ConstraintError, ProximalSettings};
use crate::multibody::{check_v, compute_joint_jacobians, nonlinear_effects, rnea, Data, Model};
use nalgebra::DVector;

/// Inverse dynamics with constraints: given `(q, q̇, q̈)` with `q̈` consistent with the
/// constraints (`J q̈ + γ = 0`), the torques `τ` (zero on the unactuated degrees of freedom,
/// [`ConstraintData::set_unactuated`]; by default a free-flyer's six) and the constraint forces
/// `λ` such that
///
/// `M(q) q̈ + c(q, q̇) + g(q) = τ + Jᵀ λ`,
///
/// of least norm `‖τ‖² + ‖λ‖²` (the minimum-norm solution of the underdetermined system
/// `[S_aᵀ Jᵀ] (τ_a, λ) = τ_ID`, `τ_ID` = RNEA(q, q̇, q̈)): with `G = S_aᵀ S_a + Jᵀ J` (nv x nv),
/// `G y = τ_ID`, `τ = S_aᵀ S_a y`, `λ = J y`. The norm mixes units (N·m, N): scale the rows of a
/// constraint to weigh its forces differently. When no `(τ, λ)` produces `q̈` (too few actuators
/// and constraints), `G` is singular: with `μ > 0` the proximal iterations give the least-squares
/// answer of least norm, and `stats.dynamics_residual` says how far it is from exact; with
/// `μ = 0` it is an error.
///
/// `stats.absolute_residual` is `‖J q̈ + γ‖∞`, the inconsistency of the given `q̈` with the
/// constraints (it is not corrected). Results in `cdata.tau`, `cdata.lambda`; returns
/// `&cdata.tau`.
///
/// Pinocchio 4.1's `contactInverseDynamics` solves another problem: for (frictional) point
/// contacts with a compliance `R`, `λ` comes from the contacts' velocity after a step `dt`,
/// `λ = proj_cone(−(c_ref − μ λ_prev) / (R + μ))` with `c_ref = (J (q̇ + dt q̈) + correction) / dt`,
/// iterated per contact (no mass matrix), then `τ = RNEA(q, q̇, q̈) − Jᵀ λ`; with `R = 0` and a
/// consistent `q̈` its `λ` stays at the initial guess. Both return a `(τ, λ)` that satisfies the
/// equation above; they pick different ones.
///
/// # Errors
/// Bad inputs, a workspace of another model, bad settings, or [`ConstraintError::Singular`]
/// (with `μ = 0`).
pub fn contact_inverse_dynamics<'a>(
    model: &Model,
    data: &mut Data,
    cdata: &'a mut ConstraintData,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    settings: &ProximalSettings,
) -> Result<&'a DVector<f64>, ConstraintError> {
    cdata.check_model(model)?;
    settings.check()?;
    check_v(model, "a", a)?;
    nonlinear_effects(model, data, q, v)?;
    compute_joint_jacobians(model, data, q)?;
    constraint_rows(model, data, cdata, q, v, true);
    let m = cdata.dim();
    let nv = model.nv();
    // the consistency of q̈: ‖J q̈ + γ‖∞
    let mut consistency: f64 = 0.0;
    for c in 0..cdata.placements.len() {
        for r in cdata.rows_of(c) {
            let jq: f64 = cdata.support[c]
                .cols
                .iter()
                .map(|&(k, _, _)| cdata.jacobian[(r, k)] * a[k])
                .sum();
            consistency = consistency.max((jq + cdata.gamma[r]).abs());
        }
    }
    rnea(model, data, q, v, a)?;
    // G = S_aᵀ S_a + Jᵀ J
    cdata.gram.fill(0.0);
    for k in 0..nv {
        if !cdata.unactuated[k] {
            cdata.gram[(k, k)] = 1.0;
        }
    }
    for c in 0..cdata.placements.len() {
        let cols = &cdata.support[c].cols;
        for r in cdata.rows_of(c) {
            for &(k, _, _) in cols {
                let jk = cdata.jacobian[(r, k)];
                for &(l, _, _) in cols {
                    cdata.gram[(k, l)] += jk * cdata.jacobian[(r, l)];
                }
            }
        }
    }
    cdata.b.rows_mut(0, nv).copy_from(&data.tau);
    let mut stats = proximal_solve(
        &cdata.gram,
        &mut cdata.chol,
        &cdata.b.as_slice()[..nv],
        cdata.y.as_mut_slice(),
        &mut cdata.prev.as_mut_slice()[..nv],
        settings,
    )?;
    stats.dynamics_residual = stats.absolute_residual;
    stats.absolute_residual = consistency;
    cdata.stats = stats;
    for k in 0..nv {
        cdata.tau[k] = if cdata.unactuated[k] { 0.0 } else { cdata.y[k] };
    }
    for r in 0..m {
        cdata.lambda[r] = (0..nv).map(|k| cdata.jacobian[(r, k)] * cdata.y[k]).sum();
    }
    Ok(&cdata.tau)
}
