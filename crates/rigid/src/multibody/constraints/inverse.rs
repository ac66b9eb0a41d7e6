//! Constrained inverse dynamics: the torques and constraint forces that produce a given `q̈`.

use super::dynamics::constraint_rows;
use super::solver::pinv_solve;
use super::workspace::ConstraintData;
use super::{ConstraintError, SolverStats};
use crate::multibody::{check_v, compute_joint_jacobians, nonlinear_effects, rnea, Data, Model};
use nalgebra::DVector;

/// Inverse dynamics with constraints: given `(q, q̇, q̈)`, the torques `τ` (zero on the
/// unactuated degrees of freedom, [`ConstraintData::set_unactuated`]; by default a free-flyer's
/// six) and the constraint forces `λ` such that
///
/// `M(q) q̈ + c(q, q̇) + g(q) = τ + Jᵀ λ`,
///
/// of least norm `‖τ‖² + ‖λ‖²`: the minimum-norm solution `x = A⁺ τ_ID` of
/// `A x = [S_aᵀ Jᵀ] (τ_a, λ) = τ_ID`, `τ_ID` = RNEA(q, q̇, q̈). With `G = A Aᵀ = S_aᵀ S_a + Jᵀ J`
/// (nv x nv) and `A⁺ = Aᵀ G⁺`: `y = G⁺ τ_ID` by a Cholesky factorisation with complete pivoting
/// that stops at `G`'s numerical rank, then `τ = S_aᵀ S_a y`, `λ = J y`. The norm mixes units
/// (N·m, N): scale a constraint's rows to weigh its forces differently.
///
/// When no `(τ, λ)` produces `q̈` (a free-flyer's acceleration that the contacts cannot
/// produce: the base is not actuated), the answer is the least-squares one of least norm, and
/// `stats.dynamics_residual = ‖A x − τ_ID‖∞` says how far it is from exact (the force the base
/// would need). `stats.absolute_residual` is `‖J q̈ + γ‖∞`: how far the given `q̈` is from
/// satisfying the constraints (it is not corrected). Results in `cdata.tau`, `cdata.lambda`;
/// returns `&cdata.tau`.
///
/// Pinocchio 4.1's `contactInverseDynamics` solves another problem: for (frictional) point
/// contacts with a compliance `R`, `λ` comes from the contacts' velocity after a step `dt`,
/// `λ = proj_cone(−(c_ref − μ λ_prev) / (R + μ))` with `c_ref = (J (q̇ + dt q̈) + correction) / dt`,
/// iterated per contact (no mass matrix), then `τ = RNEA(q, q̇, q̈) − Jᵀ λ` (every dof actuated);
/// with `R = 0` and a `q̈` that keeps the contacts (`c_ref = 0`), its `λ` stays at the initial
/// guess. Both return a `(τ, λ)` with `M q̈ + c + g = τ + Jᵀ λ`; they pick different ones.
///
/// # Errors
/// Bad inputs or a workspace of another model.
pub fn contact_inverse_dynamics<'a>(
    model: &Model,
    data: &mut Data,
    cdata: &'a mut ConstraintData,
    q: &[f64],
    v: &[f64],
    a: &[f64],
) -> Result<&'a DVector<f64>, ConstraintError> {
    cdata.check_model(model)?;
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
    pinv_solve(
        &cdata.gram,
        &mut cdata.chol,
        &mut cdata.normal,
        &mut cdata.perm,
        data.tau.as_slice(),
        cdata.y.as_mut_slice(),
    );
    let mut residual: f64 = 0.0;
    for k in 0..nv {
        let gy: f64 = (0..nv).map(|l| cdata.gram[(k, l)] * cdata.y[l]).sum();
        residual = residual.max((gy - data.tau[k]).abs());
        cdata.tau[k] = if cdata.unactuated[k] { 0.0 } else { cdata.y[k] };
    }
    for r in 0..m {
        cdata.lambda[r] = (0..nv).map(|k| cdata.jacobian[(r, k)] * cdata.y[k]).sum();
    }
    cdata.stats = SolverStats {
        iterations: 1,
        absolute_residual: consistency,
        relative_residual: 0.0,
        converged: true,
        dynamics_residual: residual,
    };
    Ok(&cdata.tau)
}
