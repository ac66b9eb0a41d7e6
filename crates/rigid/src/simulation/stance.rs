//! The stance controller of a legged robot on the ground ([`ControlLaw::Stance`]): its gains and
//! the feedforward torques that hold the stance on its contacts.

use super::{ControlLaw, SimulationError};
use crate::collision::ContactPoint;
use crate::multibody::constraints::{
    constraint_rows, contact_inverse_dynamics, ConstraintData, ConstraintModel,
};
use crate::multibody::{
    compute_joint_jacobians, crba, forward_kinematics_q, Data, JointId, JointType, Model,
    ReferenceFrame,
};
use crate::spatial::{Transform, Vec3};
use nalgebra::DMatrix;

impl ControlLaw {
    /// Standing on `contacts` (points of the bodies touching the world at `target`): joint PD to
    /// `target`, nothing on a free-flyer's dofs, plus the feedforward `τ_ff` that holds the
    /// stance at rest: the least-norm `(τ, λ)` of `g(q*) = τ + Jᵀ λ` with `λ` a force at each
    /// contact point ([`contact_inverse_dynamics`]; without contacts, the least-norm part of
    /// `g(q*)` the joints can hold).
    ///
    /// Every actuated joint alone has the natural frequency `omega` (rad/s) and damping ratio
    /// `zeta` on the inertia it moves *while the feet hold*: `K_p,k = ω² m_k`, `K_d,k = 2ζω m_k`
    /// with `m_k = max(M_kk, 1 / (M_c⁻¹)_kk)` and `M_c⁻¹ = M⁻¹ − M⁻¹Aᵀ (A M⁻¹ Aᵀ)⁺ A M⁻¹` the
    /// constrained mobility (Featherstone 2008 §8.1), `A` the rows of one anchor per touching
    /// body at the centroid of its contacts: a frame (the sole held whole) on a body with three
    /// or more contacts, else a point; where the frames lock joint k, the points alone. A knee
    /// then moves the body it carries, not only its shank: with the leg's own `M_kk`, as
    /// [`ControlLaw::pd`] on a fixed base, the joints are far softer than the load's geometric
    /// stiffness `≈ m g ℓ` and the stance buckles (Solo-12 twisted in yaw and fell after ~1 s).
    /// Anchors rather than every contact: the many points of a sole would give the same frame
    /// with redundant rows.
    ///
    /// # Errors
    /// A bad target, a contact on a body of another model.
    pub fn stance(
        model: &Model,
        target: &[f64],
        contacts: &[ContactPoint],
        omega: f64,
        zeta: f64,
    ) -> Result<Self, SimulationError> {
        let mut data = Data::new(model);
        forward_kinematics_q(model, &mut data, target)?;
        // a point (or, `whole`, a frame) of `body` at `at` held where it is
        let anchor = |body: JointId, at: Vec3, whole: bool| {
            let at = Transform::from_translation(at);
            let local = data.placements[body.0].inverse() * at;
            if whole {
                ConstraintModel::frame(Some(body), local, None, at)
            } else {
                ConstraintModel::point(Some(body), local, None, at)
                    .with_reference(ReferenceFrame::WorldAligned)
            }
        };
        let points: Vec<ConstraintModel> = contacts
            .iter()
            .filter_map(|c| Some(anchor(c.body1?, c.point, false)))
            .collect();
        // per touching body: the sum of its contact points and their number
        let mut bodies: Vec<(JointId, Vec3, f64)> = Vec::new();
        for c in contacts {
            let Some(body) = c.body1 else { continue };
            match bodies.iter_mut().find(|b| b.0 == body) {
                Some(b) => {
                    b.1 += c.point;
                    b.2 += 1.0;
                }
                None => bodies.push((body, c.point, 1.0)),
            }
        }
        let pinned: Vec<ConstraintModel> = bodies
            .iter()
            .map(|&(body, sum, n)| anchor(body, sum / n, false))
            .collect();
        let held: Vec<ConstraintModel> = bodies
            .iter()
            .map(|&(body, sum, n)| anchor(body, sum / n, n >= 3.0))
            .collect();
        let invalid = |e: crate::multibody::constraints::ConstraintError| {
            SimulationError::Invalid(format!("stance: {e}"))
        };
        let nv = model.nv();
        let zeros = vec![0.0; nv];
        let mut cdata = ConstraintData::new(model, &points).map_err(invalid)?;
        let feedforward =
            contact_inverse_dynamics(model, &mut data, &mut cdata, target, &zeros, &zeros)
                .map_err(invalid)?
                .as_slice()
                .to_vec();
        let m = crba(model, &mut data, target)?.clone();
        let actuated: Vec<bool> = (0..nv)
            .map(|k| model.joint(model.dof_joint(k)).kind != JointType::FreeFlyer)
            .collect();
        let mut inertia: Vec<f64> = (0..nv).map(|k| m[(k, k)]).collect();
        if !bodies.is_empty() {
            let minv = m.clone().try_inverse().ok_or_else(|| {
                SimulationError::Invalid("stance: the mass matrix is singular at the target".into())
            })?;
            compute_joint_jacobians(model, &mut data, target)?;
            let by_frame = mobility(model, &data, target, &held, &minv)?;
            let by_point = mobility(model, &data, target, &pinned, &minv)?;
            for k in (0..nv).filter(|&k| actuated[k]) {
                // the soles held whole, or where that locks the joint the feet pinned at a point;
                // a joint locked both ways keeps its own inertia
                let unlocked = |x: f64| x > 1e-9 * minv[(k, k)];
                if let Some(x) = [by_frame[k], by_point[k]]
                    .into_iter()
                    .find(|&x| unlocked(x))
                {
                    inertia[k] = inertia[k].max(1.0 / x);
                }
            }
        }
        let gain = |w: f64| -> Vec<f64> {
            (0..nv)
                .map(|k| if actuated[k] { w * inertia[k] } else { 0.0 })
                .collect()
        };
        Ok(Self::Stance {
            target: target.to_vec(),
            kp: gain(omega * omega),
            kd: gain(2.0 * zeta * omega),
            feedforward,
        })
    }

    /// [`stance`](Self::stance) on the contacts `collision` finds at `target` with a gap under
    /// 2 mm (the feet on the ground: the points of a sole within twice its resting face's
    /// unevenness), with the gains of `rigid simulate --controller pd`
    /// (`ω = 8π`, `ζ = 1`). `rigid simulate ROBOT --floating --ground --controller pd --target
    /// STANCE` stands on it.
    ///
    /// # Errors
    /// As [`stance`](Self::stance), or a bad collision model.
    #[cfg(feature = "collision")]
    pub fn standing(
        model: &Model,
        target: &[f64],
        collision: &crate::collision::CollisionModel,
    ) -> Result<Self, SimulationError> {
        let mut data = Data::new(model);
        forward_kinematics_q(model, &mut data, target)?;
        let mut cd = crate::collision::CollisionData::new(model, collision)?;
        let mut contacts = Vec::new();
        cd.contacts(collision, &data.placements, &mut contacts);
        contacts.retain(|c| c.gap < 2.0 * crate::collision::RESTING_FACE && c.body2.is_none());
        Self::stance(model, target, &contacts, STANCE_OMEGA, 1.0)
    }
}

/// The natural frequency (rad/s) of each joint of the stance controller of
/// [`ControlLaw::standing`]: 4 Hz (`--controller pd` on the ground). At 2 Hz, as `--controller
/// pd` without contact, TALOS's forward lean (knees, ankles and base pitch together) grew at
/// 1.7 s⁻¹ and felled it at 6.1 s: the joints' stiffness fell short of gravity's in that mode.
#[cfg(feature = "collision")]
pub const STANCE_OMEGA: f64 = 8.0 * std::f64::consts::PI;

/// The diagonal of the constrained mobility `M_c⁻¹ = M⁻¹ − M⁻¹Aᵀ (A M⁻¹ Aᵀ)⁺ A M⁻¹` at `q`
/// (`A` the rows of `anchors`; `data` holds the placements and the spatial Jacobian at `q`).
fn mobility(
    model: &Model,
    data: &Data,
    q: &[f64],
    anchors: &[ConstraintModel],
    minv: &DMatrix<f64>,
) -> Result<Vec<f64>, SimulationError> {
    let invalid = |e: String| SimulationError::Invalid(format!("stance: {e}"));
    let mut adata = ConstraintData::new(model, anchors).map_err(|e| invalid(e.to_string()))?;
    let zeros = vec![0.0; model.nv()];
    constraint_rows(model, data, &mut adata, q, &zeros, false);
    let A = adata.jacobian.rows(0, adata.dim());
    let AMinv = A * minv;
    let delassus = &AMinv * A.transpose();
    let tol = 1e-12 * delassus.amax();
    let pinv = delassus
        .pseudo_inverse(tol)
        .map_err(|e| invalid(e.to_string()))?;
    let held = AMinv.transpose() * pinv * &AMinv;
    Ok((0..model.nv())
        .map(|k| minv[(k, k)] - held[(k, k)])
        .collect())
}
