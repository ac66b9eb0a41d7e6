//! The recursive algorithms, one file each. All take `(model, data, inputs...)`, check the inputs
//! (lengths, finiteness, unit quaternions) and write into `data`.

mod aba;
mod coriolis;
mod crba;
mod energy;
mod jacobian;
mod kinematics;
mod rnea;

pub use aba::{aba, aba_with_external, forward_dynamics_cholesky};
pub use coriolis::coriolis_matrix;
pub use crba::crba;
pub use energy::{center_of_mass, kinetic_energy, potential_energy};
pub use jacobian::{
    compute_joint_jacobians, compute_joint_jacobians_time_variation, frame_jacobian,
    frame_jacobian_time_variation, joint_jacobian, joint_jacobian_time_variation, ReferenceFrame,
};
pub use kinematics::{
    forward_kinematics, forward_kinematics_q, forward_kinematics_qv, update_frame_placements,
};
pub use rnea::{gravity_torques, nonlinear_effects, rnea, rnea_with_external};

use super::Model;
use crate::spatial::{Transform, Twist};

/// `S_i q̇_i = Σ_k S_k x_k` over the degrees of freedom of joint `i` (child frame).
#[inline]
pub(crate) fn joint_motion(model: &Model, i: usize, x: &[f64]) -> Twist {
    let j = &model.joints[i];
    let mut t = Twist::zero();
    let r = j.idx_v..j.idx_v + j.nv;
    for (S, xk) in model.dof_S[r.clone()].iter().zip(&x[r]) {
        t += *S * *xk;
    }
    t
}

/// `liMi = X_T X_J(q_i)`: the pose of body i in its parent (one match on the joint type).
#[inline]
pub(crate) fn parent_placement(model: &Model, i: usize, q: &[f64]) -> Transform {
    let j = &model.joints[i];
    j.placement * j.kind.transform(&q[j.idx_q..j.idx_q + j.nq])
}
