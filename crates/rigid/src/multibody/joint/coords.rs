//! Names of each joint's coordinates, and how they differ in the layouts of other libraries.

use super::JointType;

/// How one joint's coordinates differ between rigid's layout and Pinocchio's
/// ([`PinocchioLayout`](crate::interop::PinocchioLayout)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PinocchioCoords {
    /// The same coordinates.
    Same,
    /// `θ` ↔ `(cos θ, sin θ)`: a revolute joint imported from a URDF `continuous` joint
    /// (Pinocchio's `JointModelRUBX`).
    CosSin,
    /// `(x, y, θ)` ↔ `(x, y, cos θ, sin θ)`.
    Planar,
    /// `(ω, v)` ↔ `(v, ω)` in velocity space; `q` the same.
    FreeFlyer,
    /// `q` a quaternion, the same; only the sign Pinocchio's integration keeps differs.
    Spherical,
}

impl PinocchioCoords {
    /// Pinocchio's `nq` for a joint with these coordinates and rigid's `nq`.
    #[must_use]
    pub fn nq(self, nq: usize) -> usize {
        match self {
            Self::CosSin | Self::Planar => nq + 1,
            Self::Same | Self::FreeFlyer | Self::Spherical => nq,
        }
    }
}

/// How one joint's coordinates differ between rigid's layout and MuJoCo's
/// ([`MujocoLayout`](crate::interop::MujocoLayout)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MujocoCoords {
    /// One coordinate counted from MuJoCo's `ref` (a hinge or slide): `qpos = q + ref`.
    Scalar,
    /// A ball joint: the quaternion written `w` first.
    Ball,
    /// A free joint: the quaternion `w` first, and the velocity (world linear, body angular)
    /// through a map that depends on `q`.
    Free,
    /// The same coordinates (joints MuJoCo does not have: planar, universal).
    Same,
}

impl JointType {
    /// How the joint's coordinates differ in MuJoCo's layout.
    #[must_use]
    pub fn mujoco_coords(&self) -> MujocoCoords {
        match self {
            Self::Revolute { .. } | Self::Prismatic { .. } | Self::Helical { .. } => {
                MujocoCoords::Scalar
            }
            Self::Spherical => MujocoCoords::Ball,
            Self::FreeFlyer => MujocoCoords::Free,
            Self::Planar | Self::Universal { .. } => MujocoCoords::Same,
        }
    }

    /// The suffixes of the joint's coordinates in `q` and in `v` (also `a`, `τ`) used to name
    /// columns: `q_<joint>_<suffix>`, or `q_<joint>` for a one-coordinate joint (empty suffix).
    #[must_use]
    pub fn coordinate_suffixes(&self) -> (&'static [&'static str], &'static [&'static str]) {
        match self {
            Self::Revolute { .. } | Self::Prismatic { .. } | Self::Helical { .. } => (&[""], &[""]),
            Self::Universal { .. } => (&["1", "2"], &["1", "2"]),
            Self::FreeFlyer => (
                &["x", "y", "z", "qx", "qy", "qz", "qw"],
                &["wx", "wy", "wz", "vx", "vy", "vz"],
            ),
            Self::Spherical => (&["qx", "qy", "qz", "qw"], &["wx", "wy", "wz"]),
            Self::Planar => (&["x", "y", "theta"], &["vx", "vy", "wz"]),
        }
    }

    /// How the joint's coordinates differ in Pinocchio's layout; `continuous` is
    /// [`Joint::continuous`](crate::multibody::Joint::continuous).
    #[must_use]
    pub fn pinocchio_coords(&self, continuous: bool) -> PinocchioCoords {
        match self {
            Self::Revolute { .. } if continuous => PinocchioCoords::CosSin,
            Self::Revolute { .. }
            | Self::Prismatic { .. }
            | Self::Helical { .. }
            | Self::Universal { .. } => PinocchioCoords::Same,
            Self::Spherical => PinocchioCoords::Spherical,
            Self::FreeFlyer => PinocchioCoords::FreeFlyer,
            Self::Planar => PinocchioCoords::Planar,
        }
    }
}

/// Column names of `model`'s coordinates for each prefix: `q_<joint>` for 1-dof joints,
/// `q_<joint>_x … _qw` for a free-flyer (`_wx … _vz` for its velocity), `_qx … _qw` /
/// `_wx … _wz` for a spherical joint, `_x, _y, _theta` / `_vx, _vy, _wz` for a planar one
/// ([`JointType::coordinate_suffixes`]). The prefix `q` takes the configuration's names, any
/// other prefix the velocity's.
///
/// ```
/// let model = rigid::multibody::builtin("double_pendulum").unwrap();
/// let names = rigid::multibody::column_names(&model, &["q", "tau"]);
/// assert_eq!(names, ["q_joint1", "q_joint2", "tau_joint1", "tau_joint2"]);
/// ```
#[must_use]
pub fn column_names(model: &crate::multibody::Model, prefixes: &[&str]) -> Vec<String> {
    let mut cols = Vec::new();
    for prefix in prefixes {
        for j in model.joints() {
            let (sq, sv) = j.kind.coordinate_suffixes();
            for s in if *prefix == "q" { sq } else { sv } {
                cols.push(if s.is_empty() {
                    format!("{prefix}_{}", j.name)
                } else {
                    format!("{prefix}_{}_{s}", j.name)
                });
            }
        }
    }
    cols
}
