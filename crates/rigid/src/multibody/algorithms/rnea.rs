//! The recursive Newton-Euler algorithm for inverse dynamics (Featherstone 2008, Table 5.1;
//! Lynch & Park §8.3.2), in body coordinates, with gravity as a fictitious base acceleration.
//!
//! Read [`reference::rnea`](crate::multibody::reference::rnea) first (spatial_v2's `ID.m`): this
//! is the same two loops with `Xup{i} * v` as [`Transform::inv_act_twist`](crate::spatial::Transform::inv_act_twist)
//! (no 6x6 matrix), `I{i} * a` as [`SpatialInertia::momentum`](crate::mass::SpatialInertia::momentum),
//! `crm(v) * vJ` written out for a joint whose `S` is a coordinate axis (`cross_axis`), and
//! `Xup{i}' * f{i}` as [`Transform::act_wrench`](crate::spatial::Transform::act_wrench).

use super::{
    add_axis, axis_motion, cross_axis, joint_bias, joint_motion, parent_placement, update_subspaces,
};
use crate::error::DimensionError;
use crate::multibody::{check_data, check_q, check_v, Data, Model, MultibodyError};
use crate::spatial::{Twist, Wrench};
use nalgebra::DVector;

/// `τ = ID(q, v, a, f_ext)`, the generalised forces that produce `a` at `(q, v)`:
///
/// forward, for i = 1..n (λ(i) the parent, world = 0 with `V_0 = 0`, `A_0 = -g`):
/// - `liMi = X_T X_J(q_i)`, `V_i = [Ad_{liMi⁻¹}] V_{λ(i)} + S_i q̇_i`
/// - `A_i = [Ad_{liMi⁻¹}] A_{λ(i)} + S_i q̈_i + [ad_{V_i}] S_i q̇_i + c_J`
/// - `F_i = G_i A_i - [ad_{V_i}]ᵀ G_i V_i - F_i^ext`
///
/// backward, for i = n..1: `τ_i = S_iᵀ F_i + armature_i q̈_i`, `F_{λ(i)} += [Ad_{liMi⁻¹}]ᵀ F_i`
/// (the armature term keeps `rnea = M a + nle` with the armature on the diagonal of `M`).
fn rnea_impl(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: Option<&[f64]>,
    a: Option<&[f64]>,
    fext: Option<&[Wrench]>,
    out: Out,
) {
    let a_world = Twist::new(crate::spatial::Vec3::zeros(), -model.gravity);
    let n = model.njoints();
    update_subspaces(model, q, &mut data.S);
    for i in 0..n {
        let liMi = parent_placement(model, i, q);
        data.parent_placements[i] = liMi;
        let (Vp, Ap) = match model.joints()[i].parent {
            Some(p) => (data.velocities[p.0], data.accelerations_gravity[p.0]),
            None => (Twist::zero(), a_world),
        };
        let G = &model.inertias()[i];
        let mut A = liMi.inv_act_twist(&Ap);
        if let Some(a) = a {
            match axis_motion(model, i, a) {
                Some((c, x)) => add_axis(&mut A, c, x),
                None => A += joint_motion(model, &data.S, i, a),
            }
        }
        let mut F;
        if let Some(v) = v {
            let mut V = liMi.inv_act_twist(&Vp);
            match axis_motion(model, i, v) {
                Some((c, x)) => {
                    add_axis(&mut V, c, x);
                    A += cross_axis(&V, c, x);
                }
                None => {
                    let vJ = joint_motion(model, &data.S, i, v);
                    V += vJ;
                    A += V.cross(&vJ);
                }
            }
            if let Some(cJ) = joint_bias(model, i, q, v) {
                A += cJ;
            }
            data.velocities[i] = V;
            F = G.momentum(&A) - V.ad_transpose(&G.momentum(&V));
        } else {
            data.velocities[i] = Twist::zero();
            F = G.momentum(&A);
        }
        if let Some(fext) = fext {
            F -= fext[i];
        }
        data.accelerations_gravity[i] = A;
        data.forces[i] = F;
    }
    let tau: &mut DVector<f64> = match out {
        Out::Tau => &mut data.tau,
        Out::Nle => &mut data.nle,
        Out::G => &mut data.g,
    };
    for i in (0..n).rev() {
        let j = &model.joints()[i];
        let F = data.forces[i];
        for k in j.idx_v..j.idx_v + j.nv {
            tau[k] = data.S[k].dot(&F);
            if let Some(a) = a {
                tau[k] += model.armature[k] * a[k];
            }
        }
        if let Some(p) = j.parent {
            let Fp = data.parent_placements[i].act_wrench(&F);
            data.forces[p.0] += Fp;
        }
    }
}

#[derive(Clone, Copy)]
enum Out {
    Tau,
    Nle,
    G,
}

/// Inverse dynamics `τ = M(q) a + c(q, v) + g(q)` by the recursive Newton-Euler algorithm
/// (Featherstone 2008, Table 5.1; Lynch & Park §8.3.2), body coordinates, gravity as the base
/// acceleration `A_0 = -g`. Returns `data.tau`; also fills `data.forces` (joint wrenches `F_i`
/// in body frames), `velocities`, `accelerations_gravity`, `parent_placements`. O(n).
///
/// # Errors
/// Wrong lengths, non-finite entries, or a non-unit quaternion.
///
/// ```
/// use rigid::multibody::{pendulum, rnea, Data};
/// let model = pendulum(); // M = 1/3, g(q) = 4.905 sin q
/// let mut data = Data::new(&model);
/// let tau = rnea(&model, &mut data, &[0.5], &[0.0], &[3.0])?;
/// assert!((tau[0] - (1.0 + 4.905 * 0.5f64.sin())).abs() < 1e-12);
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn rnea<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    a: &[f64],
) -> Result<&'a DVector<f64>, MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    check_v(model, "v", v)?;
    check_v(model, "a", a)?;
    rnea_impl(model, data, q, Some(v), Some(a), None, Out::Tau);
    Ok(&data.tau)
}

/// [`rnea`] with an external wrench `fext[i]` applied to each body i, expressed in body i's
/// frame (moment about its origin): `F_i = G_i A_i - [ad_{V_i}]ᵀ G_i V_i - F_i^ext`.
///
/// # Errors
/// As [`rnea`], and `fext.len() != njoints`.
pub fn rnea_with_external<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    fext: &[Wrench],
) -> Result<&'a DVector<f64>, MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    check_v(model, "v", v)?;
    check_v(model, "a", a)?;
    check_fext(model, fext)?;
    rnea_impl(model, data, q, Some(v), Some(a), Some(fext), Out::Tau);
    Ok(&data.tau)
}

/// Check external wrenches: one per joint, finite.
pub(crate) fn check_fext(model: &Model, fext: &[Wrench]) -> Result<(), MultibodyError> {
    DimensionError::check("fext", model.njoints(), fext.len())?;
    if let Some(index) = fext
        .iter()
        .position(|f| !(f.m.iter().chain(f.f.iter()).all(|x| x.is_finite())))
    {
        return Err(MultibodyError::NonFinite {
            what: "fext",
            index,
        });
    }
    Ok(())
}

/// Nonlinear effects `nle = c(q, v) + g(q) = rnea(q, v, 0)` (Coriolis, centrifugal and gravity
/// forces). Returns `data.nle`.
///
/// # Errors
/// As [`rnea`].
pub fn nonlinear_effects<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
) -> Result<&'a DVector<f64>, MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    check_v(model, "v", v)?;
    rnea_impl(model, data, q, Some(v), None, None, Out::Nle);
    Ok(&data.nle)
}

/// Generalised gravity `g(q) = rnea(q, 0, 0)`. Returns `data.g`.
///
/// # Errors
/// As [`rnea`].
pub fn gravity_torques<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
) -> Result<&'a DVector<f64>, MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    rnea_impl(model, data, q, None, None, None, Out::G);
    Ok(&data.g)
}
