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

/// The layout a model's vectors and matrices are read and written in (the table above):
/// rigid's own, Pinocchio's or MuJoCo's; `rigid eval --layout`, Python's `layout=`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Layout {
    /// rigid's: the file's joint order, one angle per continuous joint, twists angular first.
    #[default]
    Rigid,
    /// Pinocchio's ([`PinocchioLayout`]).
    Pinocchio,
    /// MuJoCo's ([`MujocoLayout`]).
    Mujoco,
}

impl Layout {
    /// Every layout, in the order of their names in messages.
    pub const ALL: [Self; 3] = [Self::Rigid, Self::Pinocchio, Self::Mujoco];

    /// Its name: `rigid`, `pinocchio` or `mujoco`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Rigid => "rigid",
            Self::Pinocchio => "pinocchio",
            Self::Mujoco => "mujoco",
        }
    }
}

impl std::fmt::Display for Layout {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Layout {
    type Err = String;
    /// A layout by its [name](Layout::name); the message of an unknown one lists them.
    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|l| l.name() == s)
            .ok_or_else(|| {
                format!("layout must be \"rigid\", \"pinocchio\" or \"mujoco\", got \"{s}\"")
            })
    }
}
pub use pinocchio::{LayoutError, PinocchioLayout, COS_SIN_TOLERANCE};
