//! Constrained forward dynamics (Pinocchio's `constraintDynamics`).

use super::kinematics::{
    error_velocity_drift, jacobian_rows, ConstraintPlacement, FrameMotion, JointCoords,
};
use super::solver::{delassus, primal, proximal, z_transpose_times};
use super::workspace::ConstraintData;
use super::{ConstraintError, ConstraintKind, ProximalSettings};
use crate::multibody::algorithms::{ltl_factor, ltl_solve_transposed};
use crate::multibody::{check_v, compute_joint_jacobians, crba, nonlinear_effects, Data, Model};
use crate::spatial::{Twist, Vec3};
use nalgebra::DVector;

/// Forward dynamics with bilateral constraints: `q̈` and the constraint forces `λ` with
///
/// `M(q) q̈ + c(q, q̇) + g(q) = τ + Jᵀ λ`,  `J q̈ + γ = 0`
///
/// (`γ` the drift with the Baumgarte terms, see [the module](super)). Steps: RNEA for `c + g`
/// and the bodies' drift accelerations, CRBA for `M`, the spatial Jacobian; per constraint its
/// frames, rows of `J` and `γ`; then the Schur complement of the KKT system: `M = LᵀL`
/// (tree-sparse), `Z = L⁻ᵀ Jᵀ`, the Delassus matrix `K = Zᵀ Z`, `w = L⁻ᵀ (τ − c − g)`, the
/// proximal iterations `(K + μ I) λ_{k+1} = −γ − Zᵀ w + μ λ_k`, and `q̈ = L⁻¹ (w + Z λ)`
/// (Carpentier, Budhiraja & Mansard, RSS 2021, §III–IV; Featherstone 2008, §6.5 and §8.3).
///
/// Results in `cdata`: [`ddq`](ConstraintData::ddq), [`lambda`](ConstraintData::lambda) (3, 6
/// or 1 numbers per constraint, in its reference frame, a wrench moment first), `jacobian`,
/// `gamma`, `error`, `velocity`, `placements`, `stats`. Returns `&cdata.ddq`. With `μ > 0` and
/// redundant but consistent constraints, `q̈` is the constrained acceleration and `λ` the one of
/// least norm; with inconsistent ones (an error no motion can correct), `q̈` tends to the
/// least-squares solution while `λ` grows with the iterations: `stats.absolute_residual` says how
/// far `J q̈ + γ` is from 0.
///
/// # Errors
/// Bad inputs ([`MultibodyError`](crate::multibody::MultibodyError)), a workspace of another
/// model, bad settings, or [`ConstraintError::Singular`] (redundant constraints with `μ = 0`).
pub fn constraint_dynamics<'a>(
    model: &Model,
    data: &mut Data,
    cdata: &'a mut ConstraintData,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    settings: &ProximalSettings,
) -> Result<&'a DVector<f64>, ConstraintError> {
    cdata.check_model(model)?;
    settings.check()?;
    check_v(model, "tau", tau)?;
    nonlinear_effects(model, data, q, v)?;
    crba(model, data, q)?;
    compute_joint_jacobians(model, data, q)?;
    constraint_rows(model, data, cdata, q, v, true);
    ltl_factor(model, data)?;
    delassus(data, cdata);
    // w = L⁻ᵀ (τ − c − g), b = −γ − J q̈_free = −γ − Zᵀ w
    for k in 0..model.nv() {
        cdata.w[k] = tau[k] - data.nle[k];
    }
    ltl_solve_transposed(
        data.chol.as_slice(),
        &data.dof_parent,
        cdata.w.as_mut_slice(),
    );
    let m = cdata.dim();
    let mut b = std::mem::take(&mut cdata.b);
    z_transpose_times(cdata, cdata.w.as_slice(), &mut b.as_mut_slice()[..m]);
    for r in 0..m {
        b[r] = -cdata.gamma[r] - b[r];
    }
    cdata.b = b;
    proximal(cdata, settings)?;
    cdata.ddq.copy_from(&cdata.w);
    let mut x = std::mem::take(&mut cdata.ddq);
    primal(data, cdata, &cdata.lambda, x.as_mut_slice());
    cdata.ddq = x;
    Ok(&cdata.ddq)
}

/// Every constraint's frames, rows of `J` and, when `drift`, its error, velocity and `γ`, from
/// `data.placements`, `data.jacobian`, and the body twists and accelerations of RNEA at
/// `q̈ = 0` (`data.velocities`, `data.accelerations_gravity`: the drift accelerations `A_i`
/// plus gravity's `[Ad_{oMi⁻¹}] (0, −g)`, taken out here).
pub(crate) fn constraint_rows(
    model: &Model,
    data: &Data,
    cd: &mut ConstraintData,
    q: &[f64],
    v: &[f64],
    drift: bool,
) {
    for i in 0..cd.placements.len() {
        let c = &cd.constraints[i];
        let pl = ConstraintPlacement::of(c, &data.placements);
        let joints = joint_coords(model, c, q, v);
        let row = cd.rows[i];
        jacobian_rows(
            c,
            &pl,
            &cd.support[i],
            &data.jacobian,
            joints,
            &mut cd.jacobian,
            row,
        );
        if drift {
            let a_world = Twist::new(Vec3::zeros(), -model.gravity());
            let motion = |j: Option<crate::multibody::JointId>, P| {
                let body = j.map(|i| {
                    let (V, Ag) = (&data.velocities[i.0], &data.accelerations_gravity[i.0]);
                    (*V, *Ag - data.placements[i.0].inv_act_twist(&a_world))
                });
                FrameMotion::of(body, P)
            };
            let (m1, m2) = (
                motion(c.joint1, &c.placement1),
                motion(c.joint2, &c.placement2),
            );
            error_velocity_drift(
                c,
                &pl,
                &m1,
                &m2,
                joints,
                row,
                cd.error.as_mut_slice(),
                cd.velocity.as_mut_slice(),
                cd.gamma.as_mut_slice(),
            );
        }
        cd.placements[i] = pl;
    }
}

/// The coordinates a joint-coordinate constraint reads (`None` for the others).
pub(crate) fn joint_coords(
    model: &Model,
    c: &super::ConstraintModel,
    q: &[f64],
    v: &[f64],
) -> Option<JointCoords> {
    let ConstraintKind::JointCoordinate { .. } = c.kind else {
        return None;
    };
    let at = |j: crate::multibody::JointId| {
        let joint = model.joint(j);
        (q[joint.idx_q], v[joint.idx_v], joint.idx_v)
    };
    Some((at(c.joint1?), c.joint2.map(at)))
}
