//! Forward kinematics: placements, body velocities and accelerations (Featherstone 2008, §3.5 and
//! the first pass of Table 5.1; Lynch & Park §8.3.2).

use super::{compose, joint_bias, joint_motion, parent_placement, update_subspaces};
use crate::multibody::{check_data, check_q, check_v, Data, Model, MultibodyError};
use crate::spatial::Twist;

/// Placements only: `liMi = X_T X_J(q_i)`, `oMi = oM_{λ(i)} liMi` (`λ(i)` the parent).
/// Fills `data.parent_placements` and `data.placements`.
///
/// # Errors
/// Wrong length, non-finite entry or non-unit quaternion in `q`.
pub fn forward_kinematics_q(
    model: &Model,
    data: &mut Data,
    q: &[f64],
) -> Result<(), MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    placements_unchecked(model, data, q);
    Ok(())
}

pub(crate) fn placements_unchecked(model: &Model, data: &mut Data, q: &[f64]) {
    for i in 0..model.njoints() {
        let liMi = parent_placement(model, i, q);
        data.parent_placements[i] = liMi;
        data.placements[i] = match model.joints()[i].parent {
            Some(p) => compose(&data.placements[p.0], &liMi),
            None => liMi,
        };
    }
}

/// Placements and body twists: `V_i = [Ad_{liMi⁻¹}] V_{λ(i)} + S_i q̇_i` (body frame).
///
/// # Errors
/// As [`forward_kinematics`].
pub fn forward_kinematics_qv(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: &[f64],
) -> Result<(), MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    check_v(model, "v", v)?;
    update_subspaces(model, q, &mut data.S);
    for i in 0..model.njoints() {
        let liMi = parent_placement(model, i, q);
        data.parent_placements[i] = liMi;
        let vJ = joint_motion(model, &data.S, i, v);
        let (oMp, Vp) = match model.joints()[i].parent {
            Some(p) => (data.placements[p.0], data.velocities[p.0]),
            None => (crate::spatial::Transform::identity(), Twist::zero()),
        };
        data.placements[i] = compose(&oMp, &liMi);
        data.velocities[i] = liMi.inv_act_twist(&Vp) + vJ;
    }
    Ok(())
}

/// Forward kinematics to second order, in body (local) coordinates:
///
/// - `liMi = X_T X_J(q_i)`, `oMi = oM_{λ(i)} liMi`
/// - `V_i = [Ad_{liMi⁻¹}] V_{λ(i)} + S_i q̇_i`
/// - `A_i = [Ad_{liMi⁻¹}] A_{λ(i)} + S_i q̈_i + c_J + [ad_{V_i}] S_i q̇_i`
///
/// with `V_0 = A_0 = 0` for the world (Featherstone 2008, Table 5.1, first loop, without gravity).
/// Fills `data.parent_placements`, `placements`, `velocities`, `accelerations`.
///
/// # Errors
/// Wrong lengths, non-finite entries, or a non-unit quaternion (naming the joint).
pub fn forward_kinematics(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: &[f64],
    a: &[f64],
) -> Result<(), MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    check_v(model, "v", v)?;
    check_v(model, "a", a)?;
    update_subspaces(model, q, &mut data.S);
    for i in 0..model.njoints() {
        let liMi = parent_placement(model, i, q);
        data.parent_placements[i] = liMi;
        let vJ = joint_motion(model, &data.S, i, v);
        let mut aJ = joint_motion(model, &data.S, i, a);
        if let Some(cJ) = joint_bias(model, i, q, v) {
            aJ += cJ;
        }
        let (oMp, Vp, Ap) = match model.joints()[i].parent {
            Some(p) => (
                data.placements[p.0],
                data.velocities[p.0],
                data.accelerations[p.0],
            ),
            None => (
                crate::spatial::Transform::identity(),
                Twist::zero(),
                Twist::zero(),
            ),
        };
        data.placements[i] = compose(&oMp, &liMi);
        let V = liMi.inv_act_twist(&Vp) + vJ;
        data.velocities[i] = V;
        data.accelerations[i] = liMi.inv_act_twist(&Ap) + aJ + V.cross(&vJ);
    }
    Ok(())
}

/// World poses of the named frames, `oMf = oMi iMf`, from `data.placements` (run a forward
/// kinematics first). Frames fixed in the world get their placement as is. A `data` made for
/// another model is left untouched.
pub fn update_frame_placements(model: &Model, data: &mut Data) {
    if check_data(model, data).is_err() {
        return;
    }
    for (f, frame) in model.frames.iter().enumerate() {
        data.frame_placements[f] = match frame.parent {
            Some(p) => compose(&data.placements[p.0], &frame.placement),
            None => frame.placement,
        };
    }
}
