//! Impulse dynamics (Pinocchio's `impulseDynamics`).

use super::dynamics::constraint_rows;
use super::solver::{delassus, primal, proximal};
use super::workspace::ConstraintData;
use super::{ConstraintError, ProximalSettings};
use crate::multibody::algorithms::ltl_factor;
use crate::multibody::{check_v, compute_joint_jacobians, crba, Data, Model};
use nalgebra::DVector;

/// The velocity `q̇⁺` just after an impact that starts the constraints, and the impulse `Λ`:
///
/// `M(q) (q̇⁺ − q̇⁻) = Jᵀ Λ`,  `J q̇⁺ = −e J q̇⁻`
///
/// (Newton's impact law with restitution `e ∈ [0, 1]` for every constraint; `e = 0`: the
/// constraint velocity becomes zero, a perfectly inelastic impact; `e = 1`: it is reversed and
/// kinetic energy kept). Solved as the forward dynamics: `Z = L⁻ᵀ Jᵀ`, `K = Zᵀ Z`, the proximal
/// iterations on `K Λ = −(1 + e) J q̇⁻`, `q̇⁺ = q̇⁻ + L⁻¹ Z Λ`. Results in `cdata.dq_plus`,
/// `cdata.impulse` (3, 6 or 1 numbers per constraint, in its reference frame, a wrench moment
/// first; N·s and N·m·s), `cdata.velocity` (= `J q̇⁻`), `cdata.stats`. Returns `&cdata.dq_plus`.
///
/// Pinocchio 4.1's `impulseDynamics` sets the right-hand side from body 1's velocity only,
/// `J q̇⁺ = J q̇⁻ − (1 + e) J_1 q̇⁻` with `J_1 q̇⁻` the velocity of c1 on joint1's body: the same
/// law when joint2 is the world, and a different one for a constraint between two moving bodies
/// (there the relative velocity after the impact is `e J q̇⁻ + (1 + e) J_2 q̇⁻`, not `−e J q̇⁻`).
/// With `μ > 0` Pinocchio does a single regularised solve (rigid's `max_iter = 1`).
///
/// # Errors
/// As [`constraint_dynamics`](super::constraint_dynamics), or
/// [`ConstraintError::BadRestitution`].
pub fn impulse_dynamics<'a>(
    model: &Model,
    data: &mut Data,
    cdata: &'a mut ConstraintData,
    q: &[f64],
    v_before: &[f64],
    restitution: f64,
    settings: &ProximalSettings,
) -> Result<&'a DVector<f64>, ConstraintError> {
    cdata.check_model(model)?;
    settings.check()?;
    if !(0.0..=1.0).contains(&restitution) {
        return Err(ConstraintError::BadRestitution(restitution));
    }
    check_v(model, "v", v_before)?;
    crba(model, data, q)?;
    compute_joint_jacobians(model, data, q)?;
    constraint_rows(model, data, cdata, q, v_before, false);
    ltl_factor(model, data)?;
    delassus(data, cdata);
    let m = cdata.dim();
    for c in 0..cdata.placements.len() {
        for r in cdata.rows_of(c) {
            let jv: f64 = cdata.support[c]
                .cols
                .iter()
                .map(|&(k, _, _)| cdata.jacobian[(r, k)] * v_before[k])
                .sum();
            cdata.velocity[r] = jv;
            cdata.b[r] = -(1.0 + restitution) * jv;
        }
    }
    proximal(cdata, settings)?;
    cdata.impulse.copy_from(&cdata.lambda.rows(0, m));
    cdata.dq_plus.fill(0.0);
    let mut x = std::mem::take(&mut cdata.dq_plus);
    primal(data, cdata, &cdata.impulse, x.as_mut_slice());
    for (x, v) in x.iter_mut().zip(v_before) {
        *x += v;
    }
    cdata.dq_plus = x;
    Ok(&cdata.dq_plus)
}
