//! The layouts of other libraries: the same [`Model`](crate::multibody::Model) read and written in
//! their coordinates, so that vectors and matrices pass between rigid and code written for them
//! unchanged.
//!
//! | layout | where | what differs from rigid's |
//! | --- | --- | --- |
//! | Pinocchio | [`PinocchioLayout`] | sibling joints sorted by name (chosen at import), `(cos θ, sin θ)` for continuous and planar angles, free-flyer velocity linear first |
//! | MuJoCo | [`MujocoLayout`] | joints in the MJCF file's order (as imported), hinge and slide counted from `ref`, quaternions `w` first, free-joint velocity `(ṗ world, ω_b)` (a `q`-dependent map: matrices by congruence, MuJoCo's bias `qfrc_bias`), armature in MuJoCo's coordinates |

mod mujoco;
mod pinocchio;

pub use mujoco::MujocoLayout;
pub use pinocchio::{LayoutError, PinocchioLayout, COS_SIN_TOLERANCE};
