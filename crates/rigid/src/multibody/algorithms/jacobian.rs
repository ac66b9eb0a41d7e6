//! Joint and frame Jacobians and their time derivatives (Lynch & Park §5.1; Featherstone 2008,
//! §4.4 `J_i = Σ_{j ⪯ i} X_j S_j`), from the spatial (world-frame) Jacobian of all joints.

use super::kinematics::{forward_kinematics_qv, placements_unchecked};
use crate::multibody::{check_data, check_q, Data, FrameId, JointId, Model, MultibodyError};
use crate::spatial::{Transform, Twist};
use nalgebra::DMatrix;

/// The frame in which a Jacobian's twists are expressed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ReferenceFrame {
    /// Body Jacobian `J_b`: `V_b = J_b v`, the frame's body twist (Lynch & Park §5.1.2).
    Body,
    /// Space Jacobian `J_s`: `V_s = J_s v`, the spatial twist in the world frame (§5.1.1).
    Spatial,
    /// World-aligned: angular velocity and the velocity of the frame's origin, both in world
    /// axes (`ω_s`, `ṗ`), Pinocchio's `LOCAL_WORLD_ALIGNED`.
    WorldAligned,
}

impl ReferenceFrame {
    /// Pinocchio's name of the frame: `LOCAL` (body), `WORLD` (spatial), `LOCAL_WORLD_ALIGNED`.
    #[must_use]
    pub fn pinocchio_name(self) -> &'static str {
        match self {
            Self::Body => "LOCAL",
            Self::Spatial => "WORLD",
            Self::WorldAligned => "LOCAL_WORLD_ALIGNED",
        }
    }
}

impl std::str::FromStr for ReferenceFrame {
    type Err = String;
    /// A frame by Pinocchio's name or rigid's, in any case: `local` or `body`, `world` or
    /// `spatial`, `local_world_aligned` or `world_aligned`.
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "local" | "body" => Ok(Self::Body),
            "world" | "spatial" => Ok(Self::Spatial),
            "local_world_aligned" | "world_aligned" => Ok(Self::WorldAligned),
            _ => Err(format!(
                "the reference frame must be \"local\" (or \"body\"), \"world\" (or \"spatial\") \
                 or \"local_world_aligned\" (or \"world_aligned\"), got \"{s}\""
            )),
        }
    }
}

/// Column k of the spatial Jacobian: `J_k = [Ad_{oMi}] S_k`, i the joint of dof k.
/// Fills `data.jacobian` (6 x nv) and `data.placements`.
///
/// # Errors
/// Wrong length, non-finite entry or non-unit quaternion in `q`.
pub fn compute_joint_jacobians<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    placements_unchecked(model, data, q);
    super::update_subspaces(model, q, &mut data.S);
    fill_jacobian(model, data);
    Ok(&data.jacobian)
}

/// `J_k = [Ad_{oMi}] S_k` for every dof; when `S_k = s e_c` (a coordinate axis, `Plan::dof_axis`)
/// the column is `(s R_c, p × s R_c)` (angular axis) or `(0, s R_(c-3))` (linear): a column of
/// `R`, no product with `S`.
fn fill_jacobian(model: &Model, data: &mut Data) {
    let plan = model.plan();
    for k in 0..model.nv {
        let oMi = &data.placements[plan.dof_joint[k]];
        let t = match plan.dof_axis[k] {
            Some((c, s)) if c < 3 => {
                let w: crate::spatial::Vec3 = oMi.rotation.column(c) * s;
                Twist::new(w, oMi.translation.cross(&w))
            }
            Some((c, s)) => Twist::new(
                crate::spatial::Vec3::zeros(),
                oMi.rotation.column(c - 3) * s,
            ),
            None => oMi.act_twist(&data.S[k]),
        };
        set_col(&mut data.jacobian, k, &t);
    }
}

#[inline]
fn set_col(m: &mut DMatrix<f64>, k: usize, t: &Twist) {
    let mut c = m.column_mut(k);
    c[0] = t.w.x;
    c[1] = t.w.y;
    c[2] = t.w.z;
    c[3] = t.v.x;
    c[4] = t.v.y;
    c[5] = t.v.z;
}

#[inline]
fn col(m: &DMatrix<f64>, k: usize) -> Twist {
    let c = m.column(k);
    Twist::new(
        crate::spatial::Vec3::new(c[0], c[1], c[2]),
        crate::spatial::Vec3::new(c[3], c[4], c[5]),
    )
}

/// The spatial Jacobian and its time derivative `J̇_k = [ad_{V^s_i}] J_k` (`V^s_i` the spatial
/// twist of the body of dof k: `d/dt [Ad_{oMi}] = [ad_{V^s_i}][Ad_{oMi}]`). Fills
/// `data.jacobian`, `data.jacobian_dot`, `placements`, `velocities`.
///
/// # Errors
/// Wrong lengths, non-finite entries, a non-unit quaternion, or a joint whose motion subspace
/// depends on `q` ([`MultibodyError::Unsupported`]: `J̇` would need `Ṡ`).
pub fn compute_joint_jacobians_time_variation<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    super::require_constant_subspaces(model, "the Jacobian's time derivative")?;
    forward_kinematics_qv(model, data, q, v)?;
    fill_jacobian(model, data);
    for i in 0..model.njoints() {
        data.spatial_velocities[i] = data.placements[i].act_twist(&data.velocities[i]);
    }
    for k in 0..model.nv {
        let Vs = data.spatial_velocities[model.plan().dof_joint[k]];
        let Jk = col(&data.jacobian, k);
        set_col(&mut data.jacobian_dot, k, &Vs.cross(&Jk));
    }
    Ok(&data.jacobian_dot)
}

/// Fill `data.frame_jacobian` for a frame fixed in body `body` at world pose `oMf`, from
/// `data.jacobian`: columns of the joints supporting `body`, zero elsewhere.
fn express(
    model: &Model,
    data: &mut Data,
    body: Option<usize>,
    oMf: &Transform,
    rf: ReferenceFrame,
) {
    data.frame_jacobian.fill(0.0);
    let mut j = body;
    while let Some(i) = j {
        let ji = &model.joints()[i];
        for k in ji.idx_v..ji.idx_v + ji.nv {
            let Js = col(&data.jacobian, k);
            let t = match rf {
                ReferenceFrame::Spatial => Js,
                ReferenceFrame::Body => oMf.inv_act_twist(&Js),
                ReferenceFrame::WorldAligned => {
                    Twist::new(Js.w, Js.v + Js.w.cross(&oMf.translation))
                }
            };
            set_col(&mut data.frame_jacobian, k, &t);
        }
        j = ji.parent.map(|p| p.0);
    }
}

/// As [`express`], for the derivative: `J̇_b = [Ad_{oMf⁻¹}] (J̇_s - [ad_{V^s_f}] J_s)`;
/// world-aligned `(ω̇_k, v̇_k + ω̇_k × p + ω_k × ṗ)` with `ṗ = v^s_f + ω^s_f × p`.
fn express_dot(
    model: &Model,
    data: &mut Data,
    body: Option<usize>,
    oMf: &Transform,
    rf: ReferenceFrame,
) {
    data.frame_jacobian_dot.fill(0.0);
    let Vs = body.map_or(Twist::zero(), |b| data.spatial_velocities[b]);
    let p = oMf.translation;
    let pdot = Vs.v + Vs.w.cross(&p);
    let mut j = body;
    while let Some(i) = j {
        let ji = &model.joints()[i];
        for k in ji.idx_v..ji.idx_v + ji.nv {
            let Js = col(&data.jacobian, k);
            let dJs = col(&data.jacobian_dot, k);
            let t = match rf {
                ReferenceFrame::Spatial => dJs,
                ReferenceFrame::Body => oMf.inv_act_twist(&(dJs - Vs.cross(&Js))),
                ReferenceFrame::WorldAligned => {
                    Twist::new(dJs.w, dJs.v + dJs.w.cross(&p) + Js.w.cross(&pdot))
                }
            };
            set_col(&mut data.frame_jacobian_dot, k, &t);
        }
        j = ji.parent.map(|p| p.0);
    }
}

fn check_joint(model: &Model, joint: JointId) -> Result<(), MultibodyError> {
    if joint.0 < model.njoints() {
        Ok(())
    } else {
        Err(MultibodyError::OutOfRange {
            what: "joint",
            index: joint.0,
        })
    }
}

fn frame_pose(model: &Model, data: &Data, frame: FrameId) -> (Option<usize>, Transform) {
    let f = &model.frames[frame.0];
    match f.parent {
        Some(p) => (Some(p.0), data.placements[p.0] * f.placement),
        None => (None, f.placement),
    }
}

fn check_frame(model: &Model, frame: FrameId) -> Result<(), MultibodyError> {
    if frame.0 < model.frames.len() {
        Ok(())
    } else {
        Err(MultibodyError::OutOfRange {
            what: "frame",
            index: frame.0,
        })
    }
}

/// The Jacobian (6 x nv) of joint `joint`'s moved frame (placement `oMi`) in `rf`:
/// `V = J v` (body twist, spatial twist, or world-aligned `(ω, ṗ)`). Returns
/// `data.frame_jacobian`.
///
/// # Errors
/// As [`compute_joint_jacobians`], or `joint` out of range.
pub fn joint_jacobian<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    joint: JointId,
    rf: ReferenceFrame,
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    check_joint(model, joint)?;
    compute_joint_jacobians(model, data, q)?;
    let oMi = data.placements[joint.0];
    express(model, data, Some(joint.0), &oMi, rf);
    Ok(&data.frame_jacobian)
}

/// The Jacobian (6 x nv) of a named frame in `rf`. Returns `data.frame_jacobian` (zero for a
/// frame fixed in the world).
///
/// # Errors
/// As [`compute_joint_jacobians`], or `frame` out of range.
///
/// ```
/// use rigid::multibody::{frame_jacobian, puma560, Data, Puma560Options, ReferenceFrame};
/// let model = puma560(Puma560Options::default());
/// let mut data = Data::new(&model);
/// let flange = model.frame_id("link6").unwrap();
/// let j = frame_jacobian(&model, &mut data, &[0.0; 6], flange, ReferenceFrame::WorldAligned)?;
/// // joint 1 turns about the world z axis
/// assert!((j[(2, 0)] - 1.0).abs() < 1e-12);
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn frame_jacobian<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    frame: FrameId,
    rf: ReferenceFrame,
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    check_frame(model, frame)?;
    compute_joint_jacobians(model, data, q)?;
    let (body, oMf) = frame_pose(model, data, frame);
    express(model, data, body, &oMf, rf);
    Ok(&data.frame_jacobian)
}

/// The Jacobian (6 x nv) of joint `joint`'s moved frame in `rf`, from the spatial Jacobian and
/// the placements already in `data` (those of the last [`compute_joint_jacobians`]): no
/// kinematics is run. Pinocchio's `getJointJacobian`. Returns `data.frame_jacobian`.
///
/// # Errors
/// `joint` out of range, or a `data` made for another model.
pub fn stored_joint_jacobian<'a>(
    model: &Model,
    data: &'a mut Data,
    joint: JointId,
    rf: ReferenceFrame,
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    check_joint(model, joint)?;
    check_data(model, data)?;
    let oMi = data.placements[joint.0];
    express(model, data, Some(joint.0), &oMi, rf);
    Ok(&data.frame_jacobian)
}

/// The Jacobian (6 x nv) of a named frame in `rf`, from the spatial Jacobian and the placements
/// already in `data` (those of the last [`compute_joint_jacobians`]), with the frame's pose
/// `oMf = oMi iMf`. Pinocchio's `getFrameJacobian`. Returns `data.frame_jacobian`.
///
/// # Errors
/// `frame` out of range, or a `data` made for another model.
pub fn stored_frame_jacobian<'a>(
    model: &Model,
    data: &'a mut Data,
    frame: FrameId,
    rf: ReferenceFrame,
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    check_frame(model, frame)?;
    check_data(model, data)?;
    let (body, oMf) = frame_pose(model, data, frame);
    express(model, data, body, &oMf, rf);
    Ok(&data.frame_jacobian)
}

/// The time derivative `J̇(q, v)` of [`joint_jacobian`] (so that the frame's acceleration is
/// `J a + J̇ v`). Returns `data.frame_jacobian_dot`; `data.frame_jacobian` holds `J`.
///
/// # Errors
/// As [`compute_joint_jacobians_time_variation`], or `joint` out of range.
pub fn joint_jacobian_time_variation<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    joint: JointId,
    rf: ReferenceFrame,
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    check_joint(model, joint)?;
    compute_joint_jacobians_time_variation(model, data, q, v)?;
    let oMi = data.placements[joint.0];
    express(model, data, Some(joint.0), &oMi, rf);
    express_dot(model, data, Some(joint.0), &oMi, rf);
    Ok(&data.frame_jacobian_dot)
}

/// The time derivative of [`frame_jacobian`]. Returns `data.frame_jacobian_dot`;
/// `data.frame_jacobian` holds `J`.
///
/// # Errors
/// As [`compute_joint_jacobians_time_variation`], or `frame` out of range.
pub fn frame_jacobian_time_variation<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    frame: FrameId,
    rf: ReferenceFrame,
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    check_frame(model, frame)?;
    compute_joint_jacobians_time_variation(model, data, q, v)?;
    let (body, oMf) = frame_pose(model, data, frame);
    express(model, data, body, &oMf, rf);
    express_dot(model, data, body, &oMf, rf);
    Ok(&data.frame_jacobian_dot)
}
