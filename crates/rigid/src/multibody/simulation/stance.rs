//! The stance controller of a legged robot on the ground ([`ControlLaw::Stance`]): its gains and
//! the feedforward torques that hold the stance on its contacts.

use super::{ControlLaw, SimulationError};
use crate::multibody::constraints::{contact_inverse_dynamics, ConstraintData, ConstraintModel};
use crate::multibody::contact::ContactPoint;
use crate::multibody::{crba, forward_kinematics_q, Data, JointType, Model, ReferenceFrame};
use crate::spatial::Transform;

impl ControlLaw {
    /// Standing on `contacts` (points of the bodies touching the world at `target`): joint PD to
    /// `target`, every actuated joint alone at the natural frequency `omega` (rad/s) and damping
    /// ratio `zeta` (`K_p,k = ω² M_kk`, `K_d,k = 2ζω M_kk` at the target, as [`ControlLaw::pd`]),
    /// nothing on a free-flyer's dofs, and the feedforward `τ_ff` that holds the stance at rest:
    /// the least-norm `(τ, λ)` of `g(q*) = τ + Jᵀ λ` with `λ` a force at each contact point
    /// ([`contact_inverse_dynamics`]). Without contacts `τ_ff` is the least-norm part of `g(q*)`
    /// the joints can hold.
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
        let points: Vec<ConstraintModel> = contacts
            .iter()
            .filter_map(|c| {
                let body = c.body1?;
                let at = Transform::from_translation(c.point);
                let local = data.placements[body.0].inverse() * at;
                Some(
                    ConstraintModel::point(Some(body), local, None, at)
                        .with_reference(ReferenceFrame::WorldAligned),
                )
            })
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
        let m = crba(model, &mut data, target)?;
        let actuated: Vec<bool> = (0..nv)
            .map(|k| model.joint(model.dof_joint(k)).kind != JointType::FreeFlyer)
            .collect();
        let gain = |w: f64| -> Vec<f64> {
            (0..nv)
                .map(|k| if actuated[k] { w * m[(k, k)] } else { 0.0 })
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
    /// 1 mm (the feet on the ground), with the gains of `rigid simulate --controller pd`
    /// (`ω = 4π`, `ζ = 1`). `rigid simulate ROBOT --floating --ground --controller pd --target
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
        contacts.retain(|c| c.gap < 1e-3 && c.body2.is_none());
        Self::stance(model, target, &contacts, STANCE_OMEGA, 1.0)
    }
}

/// The natural frequency (rad/s) of each joint of the stance controller of
/// [`ControlLaw::standing`]: 2 Hz, as `--controller pd`.
#[cfg(feature = "collision")]
pub const STANCE_OMEGA: f64 = 4.0 * std::f64::consts::PI;
