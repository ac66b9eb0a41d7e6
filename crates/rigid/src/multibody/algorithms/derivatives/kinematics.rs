//! The derivatives of a frame's placement, twist and acceleration with respect to `(q, v, a)`
//! (Carpentier & Mansard 2018, §III; Pinocchio's `computeForwardKinematicsDerivatives` and
//! `getFrameAccelerationDerivatives`).

use crate::multibody::algorithms::forward_kinematics;
use crate::multibody::{Data, FrameId, JointId, Model, MultibodyError, ReferenceFrame};
use crate::spatial::{Transform, Twist, Vec3};
use nalgebra::DMatrix;

/// The derivatives of a frame's twist `V` and acceleration `A = dV/dt`, borrowed from `data`
/// (each 6 x nv, angular rows first).
#[derive(Clone, Copy, Debug)]
pub struct KinematicsDerivatives<'a> {
    /// `∂V/∂q` (along `q ⊕ δ`).
    pub velocity_dq: &'a DMatrix<f64>,
    /// `∂V/∂v = J`, the frame Jacobian, also the derivative of the placement along `q ⊕ δ`.
    pub velocity_dv: &'a DMatrix<f64>,
    /// `∂A/∂q`.
    pub acceleration_dq: &'a DMatrix<f64>,
    /// `∂A/∂v`.
    pub acceleration_dv: &'a DMatrix<f64>,
    /// `∂A/∂a = J`.
    pub acceleration_da: &'a DMatrix<f64>,
}

/// The derivatives of the twist `V` and acceleration `A = dV/dt` of a named frame, expressed as
/// `rf` says (the representations of [`frame_jacobian`](crate::multibody::frame_jacobian)):
/// `Body` the body twist `V_b` and `A = V̇_b`; `Spatial` the spatial twist `V_s` and `V̇_s`;
/// `WorldAligned` `(ω, ṗ)` and `(ω̇, p̈)`, the classical acceleration of the frame's origin. So
/// `V = J v` and `A = J a + J̇ v` with `J`, `J̇` of
/// [`frame_jacobian_time_variation`](crate::multibody::frame_jacobian_time_variation). The
/// derivative of the placement along `q ⊕ δ` is `J` itself: `oMf(q ⊕ δ) = oMf exp(J_b δ)`
/// (`Body`), `exp(J_s δ) oMf` (`Spatial`).
///
/// In the world frame, with `J_k` the spatial column of dof k, λ its joint's parent and b the
/// frame's body (Carpentier & Mansard 2018, §III): for every dof k supporting b,
/// `∂V_s/∂q_k = J_k × V_s + V_λ × J_k`, `∂A_s/∂q_k = J_k × A_s + A_λ × J_k + V_λ × (V_λ × J_k)
/// + (V_λ × J_k) × V_s`, `∂A_s/∂v_k = (V_i + V_λ) × J_k + J_k × V_s` (`V`, `A` spatial twists and
/// accelerations); the body and world-aligned forms follow by differentiating
/// `V_b = [Ad_{oMf⁻¹}] V_s` (whose frame turns by `J_k`) and `(ω, v_s + ω × p)`. Columns of dofs
/// that do not support the frame are zero. Returns the five matrices (in
/// `data.derivatives`); runs [`forward_kinematics`].
///
/// # Errors
/// As [`forward_kinematics`], or `frame` out of range.
///
/// ```
/// use rigid::multibody::{frame_kinematics_derivatives, puma560, Data, Puma560Options, ReferenceFrame};
/// let model = puma560(Puma560Options::default());
/// let mut data = Data::new(&model);
/// let flange = model.frame_id("link6").unwrap();
/// let (q, v, a) = ([0.1; 6], [0.2; 6], [0.0; 6]);
/// let d = frame_kinematics_derivatives(&model, &mut data, &q, &v, &a, flange, ReferenceFrame::Body)?;
/// assert_eq!(d.velocity_dv, d.acceleration_da); // both are the body Jacobian
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn frame_kinematics_derivatives<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    frame: FrameId,
    rf: ReferenceFrame,
) -> Result<KinematicsDerivatives<'a>, MultibodyError> {
    crate::multibody::algorithms::require_constant_subspaces(model, "the analytical derivatives")?;
    let f = model
        .frames
        .get(frame.0)
        .ok_or(MultibodyError::OutOfRange {
            what: "frame",
            index: frame.0,
        })?;
    forward_kinematics(model, data, q, v, a)?;
    let (body, oMf) = match f.parent {
        Some(p) => (Some(p.0), data.placements[p.0] * f.placement),
        None => (None, f.placement),
    };
    fill(model, data, body, &oMf, rf);
    Ok(borrow(data))
}

/// [`frame_kinematics_derivatives`] for the frame of joint `joint` (its placement `oMi`).
///
/// # Errors
/// As [`forward_kinematics`], or `joint` out of range.
///
/// ```
/// use rigid::multibody::{joint_kinematics_derivatives, double_pendulum, Data, JointId, ReferenceFrame};
/// let model = double_pendulum();
/// let mut data = Data::new(&model);
/// let d = joint_kinematics_derivatives(&model, &mut data, &[0.3, 0.2], &[1.0, 0.0], &[0.0; 2],
///                                      JointId(1), ReferenceFrame::Spatial)?;
/// // the spatial twist of body 2 at v = (1, 0) is the first column; it does not depend on q₁
/// assert!(d.velocity_dq.column(0).norm() < 1e-12);
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn joint_kinematics_derivatives<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    joint: JointId,
    rf: ReferenceFrame,
) -> Result<KinematicsDerivatives<'a>, MultibodyError> {
    crate::multibody::algorithms::require_constant_subspaces(model, "the analytical derivatives")?;
    if joint.0 >= model.njoints() {
        return Err(MultibodyError::OutOfRange {
            what: "joint",
            index: joint.0,
        });
    }
    forward_kinematics(model, data, q, v, a)?;
    let oMi = data.placements[joint.0];
    fill(model, data, Some(joint.0), &oMi, rf);
    Ok(borrow(data))
}

fn borrow(data: &Data) -> KinematicsDerivatives<'_> {
    let d = &data.derivatives;
    KinematicsDerivatives {
        velocity_dq: &d.velocity_dq,
        velocity_dv: &d.velocity_dv,
        acceleration_dq: &d.acceleration_dq,
        acceleration_dv: &d.acceleration_dv,
        acceleration_da: &d.acceleration_da,
    }
}

#[inline]
fn set_col(m: &mut DMatrix<f64>, k: usize, t: &Twist) {
    m.column_mut(k)
        .copy_from_slice(&[t.w.x, t.w.y, t.w.z, t.v.x, t.v.y, t.v.z]);
}

/// The spatial twist and acceleration of body i, `[Ad_{oMi}] V_i` and `[Ad_{oMi}] A_i` (zero for
/// the world), from the body-frame ones of forward kinematics.
fn spatial(oM: &[Transform], V: &[Twist], A: &[Twist], i: Option<usize>) -> (Twist, Twist) {
    i.map_or((Twist::zero(), Twist::zero()), |i| {
        (oM[i].act_twist(&V[i]), oM[i].act_twist(&A[i]))
    })
}

/// Fill the five matrices for a frame at `oMf` fixed in `body` (after forward kinematics).
fn fill(model: &Model, data: &mut Data, body: Option<usize>, oMf: &Transform, rf: ReferenceFrame) {
    let Data {
        derivatives: d,
        placements: oM,
        velocities: V,
        accelerations: A,
        ..
    } = data;
    let (Vs, As) = spatial(oM, V, A, body);
    let p = oMf.translation;
    // (ω, ṗ) of the frame origin: the world-aligned twist
    let pdot = Vs.v + Vs.w.cross(&p);
    let at_p = |x: &Twist| Twist::new(x.w, x.v + x.w.cross(&p));
    for m in [
        &mut d.velocity_dq,
        &mut d.velocity_dv,
        &mut d.acceleration_dq,
        &mut d.acceleration_dv,
        &mut d.acceleration_da,
    ] {
        m.fill(0.0);
    }
    let mut j = body;
    while let Some(i) = j {
        let ji = &model.joints()[i];
        let parent = ji.parent.map(|p| p.0);
        let (Vp, Ap) = spatial(oM, V, A, parent);
        let (Vi, _) = spatial(oM, V, A, Some(i));
        let oMi = &oM[i];
        for k in ji.idx_v..ji.idx_v + ji.nv {
            let Jk = oMi.act_twist(&model.plan().dof_S[k]);
            // world-frame derivatives of the body's spatial twist and acceleration
            let dVq_rel = Vp.cross(&Jk);
            let dVq = Jk.cross(&Vs) + dVq_rel;
            let dAq_rel = Ap.cross(&Jk) + Vp.cross(&dVq_rel) + dVq_rel.cross(&Vs);
            let dAq = Jk.cross(&As) + dAq_rel;
            let dAv = (Vi + Vp).cross(&Jk) + Jk.cross(&Vs);
            let (vq, vv, aq, av) = match rf {
                ReferenceFrame::Spatial => (dVq, Jk, dAq, dAv),
                ReferenceFrame::Body => {
                    // the frame turns by J_k too: [Ad_{oMf⁻¹}] (∂V_s - J_k × V_s)
                    let b = |x: &Twist| oMf.inv_act_twist(x);
                    (b(&dVq_rel), b(&Jk), b(&dAq_rel), b(&dAv))
                }
                ReferenceFrame::WorldAligned => {
                    // ∂p = (J_k at p).v; V = (ω, ṗ), A = (ω̇, v̇_s + ω̇ × p + ω × ṗ)
                    let Jp = at_p(&Jk);
                    let vq = at_p(&dVq) + Twist::new(Vec3::zeros(), Vs.w.cross(&Jp.v));
                    let aq = at_p(&dAq)
                        + Twist::new(
                            Vec3::zeros(),
                            As.w.cross(&Jp.v) + dVq.w.cross(&pdot) + Vs.w.cross(&vq.v),
                        );
                    let av = at_p(&dAv)
                        + Twist::new(Vec3::zeros(), Jk.w.cross(&pdot) + Vs.w.cross(&Jp.v));
                    (vq, Jp, aq, av)
                }
            };
            set_col(&mut d.velocity_dq, k, &vq);
            set_col(&mut d.velocity_dv, k, &vv);
            set_col(&mut d.acceleration_dq, k, &aq);
            set_col(&mut d.acceleration_dv, k, &av);
            set_col(&mut d.acceleration_da, k, &vv);
        }
        j = parent;
    }
}
