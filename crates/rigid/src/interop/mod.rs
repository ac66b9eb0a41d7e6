//! The layouts of other libraries: the same [`Model`](crate::multibody::Model) read and written in
//! their coordinates, so that vectors and matrices pass between rigid and code written for them
//! unchanged.
//!
//! | layout | where | what differs from rigid's |
//! | --- | --- | --- |
//! | Pinocchio | [`PinocchioLayout`] | sibling joints sorted by name (chosen at import), `(cos θ, sin θ)` for continuous and planar angles, free-flyer velocity linear first |

mod pinocchio;

pub use pinocchio::{LayoutError, PinocchioLayout, COS_SIN_TOLERANCE};
