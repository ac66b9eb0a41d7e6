//! Multibody dynamics of kinematic trees: a constant [`Model`], a reusable [`Data`] workspace and
//! the classic recursive algorithms (forward kinematics, Jacobians, RNEA, CRBA, ABA, `M⁻¹`,
//! energies, Coriolis matrix).
//!
//! Conventions (see docs/conventions.md): joints are numbered depth-first from the root; twists and
//! wrenches are angular first; every body's quantities are expressed in its own joint frame
//! (the joint frame moved by the joint, "local" coordinates, Featherstone's body coordinates);
//! [`Data::placements`] holds the world pose `oMi` of each moved joint frame. Free-flyer
//! `q = (x, y, z, qx, qy, qz, qw)` with velocity the body twist `(ω_b, v_b)`; spherical `q` a
//! quaternion `(qx, qy, qz, qw)` with velocity `ω_b`; planar `q = (x, y, θ)` with velocity the
//! body-frame `(v_x, v_y, ω_z)`. Quaternions must have `|‖q‖ - 1| ≤ 1e-6`
//! ([`QUATERNION_TOLERANCE`]), otherwise the error names the joint.
//!
//! | notes | code | source |
//! | --- | --- | --- |
//! | `T_i(q)`, `V_i`, `V̇_i` | [`forward_kinematics`] | Featherstone 2008 Table 5.1 (first loop) |
//! | `J_s`, `J_b`, `(ω, ṗ)` and `J̇` | [`joint_jacobian`], [`frame_jacobian`], `*_time_variation`, [`stored_joint_jacobian`] | Lynch & Park §5.1 |
//! | `τ = M q̈ + c + g` | [`rnea`], [`rnea_with_external`] | Featherstone 2008 Table 5.1; Lynch & Park §8.3.2 |
//! | `c + g`, `g` | [`nonlinear_effects`], [`gravity_torques`] | RNEA with `q̈ = 0` (and `q̇ = 0`) |
//! | `M(q)` | [`crba`] | Featherstone 2008 Table 6.2 |
//! | `q̈ = M⁻¹(τ - c - g)` | [`aba`], [`forward_dynamics_cholesky`] | Featherstone 2008 Table 7.1 |
//! | `M(q)⁻¹` | [`compute_minverse`] | ABA for all unit torques: Featherstone 2008 §7.3; Carpentier & Mansard 2018 |
//! | `C(q, q̇)` (Christoffel), `Ṁ - 2C` skew | [`coriolis_matrix`] | Lynch & Park §8.1.2; Pinocchio `computeCoriolisMatrix` |
//! | `K = ½ q̇ᵀ M q̇`, `U = -Σ mᵢ gᵀ cᵢ` | [`kinetic_energy`], [`potential_energy`] | Lynch & Park §8.1 |
//! | subtree `c`, `ċ`, `c̈`; `ċ = J_c v`; `h_G = A_G v` | [`subtree_centers_of_mass`], [`jacobian_center_of_mass`], [`centroidal_momentum_matrix`], [`centroidal_momentum`] | Orin, Goswami & Lee 2013; Pinocchio `centerOfMass`, `jacobianCenterOfMass`, `ccrba` |
//! | `q ⊕ v dt`, `q₁ ⊖ q₀` | [`integrate`], [`difference`] | joint Lie groups |
//! | `(Mᵢ, Gᵢ, Sᵢ)`, DH tables | [`from_modern_robotics`], [`from_dh`] | Lynch & Park §8.3.2; Craig, Spong |
//! | Pinocchio's `q` (`cos θ, sin θ`) and `v` (linear first) | [`PinocchioLayout`](crate::interop::PinocchioLayout) | URDF models loaded with sibling joints sorted by name |
//! | `∂τ/∂(q, v)`, `∂q̈/∂(q, v, τ)`, `∂g/∂q`, frame kinematics, `∂(q ⊕ v)`, `∂(q₁ ⊖ q₀)` | [`derivatives`] ([`rnea_derivatives`], [`aba_derivatives`], …; `q` along `q ⊕ δ`) | Carpentier & Mansard, RSS 2018 |
//! | simulate: `(q, v)` on the manifold, RK4, variational, controllers, batch | [`simulation`](crate::simulation), the layer above this one | ABA; Lynch & Park ch. 9, 11 |
//! | mimic joints `q_m = k q_s + o`: `τ = Gᵀ τ_full`, `M = Gᵀ M_full G` | [`MimicModel`] | Pinocchio's `mimic=True` |
//! | many states at once, on every core | [`batch`] (`rnea_batch`, `aba_batch`, `crba_batch`, `crba_lower_batch`; `Batch` keeps the workspaces) | rayon; bit-for-bit single calls |
//!
//! No algorithm allocates after [`Data::new`] (tested with a counting allocator), and each
//! dispatches once on the joint type per joint ([`JointType::placed_transform`]); the motion
//! subspace columns are constant in body coordinates and stored in the model.
//!
//! ```
//! use rigid::multibody::{builtin, rnea, crba, Data};
//! let model = builtin("double_pendulum").unwrap();
//! let mut data = Data::new(&model);
//! let tau = rnea(&model, &mut data, &[0.1, 0.2], &[0.0, 0.0], &[0.0, 0.0]).unwrap().clone();
//! let m = crba(&model, &mut data, &[0.1, 0.2]).unwrap();
//! assert!(m[(0, 0)] > 0.0 && tau.norm() > 0.0);
//! ```

pub mod algorithms;
pub mod batch;
mod builder;
mod builtins;
pub(crate) mod configuration;
pub mod constraints;
mod data;
pub(crate) mod joint;
mod mimic;
mod textbook;

mod model;
pub(crate) mod plan;
pub mod reference;
#[cfg(feature = "serde")]
mod serialize;

pub use algorithms::*;
pub use builder::{InertiaCheck, ModelBuilder};
pub use builtins::{builtin, builtin_names, double_pendulum, pendulum, puma560, Puma560Options};
pub use configuration::{
    difference, difference_jacobians, integrate, integrate_jacobians, neutral, normalize,
    random_configuration, random_configuration_within, Rng,
};
pub use data::Data;
pub use joint::lie::{
    se3_jr as se3_right_jacobian, se3_jr_inv as se3_right_jacobian_inverse,
    so3_jr as so3_right_jacobian, so3_jr_inv as so3_right_jacobian_inverse,
};
pub use joint::{column_names, JointType, MujocoCoords, PinocchioCoords};
pub use mimic::{Mimic, MimicData, MimicError, MimicModel};
pub use model::{Frame, FrameId, FrameKind, FrameLookupError, Joint, JointId, Model};
pub use textbook::{from_dh, from_modern_robotics, DhConvention, DhJoint, DhLink};

use crate::error::{DimensionError, InertiaError};
use thiserror::Error;

/// Tolerance on a quaternion's norm: `|‖q‖ - 1| > 1e-6` is an error naming the joint.
pub const QUATERNION_TOLERANCE: f64 = 1e-6;

/// An invalid model description.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ModelError {
    /// Two joints, or two frames of one kind, with the same name.
    #[error("duplicate name '{name}' (joint names are unique among joints, frame names within their kind)")]
    DuplicateName {
        /// The name.
        name: String,
    },
    /// A parent index that does not exist (yet).
    #[error("'{name}': parent joint index {parent} does not exist")]
    UnknownParent {
        /// The joint or frame being added.
        name: String,
        /// The parent index given.
        parent: usize,
    },
    /// Joints must be added in depth-first order.
    #[error("joint '{name}': parent '{parent}' is not on the current depth-first branch (add joints depth-first)")]
    NotDepthFirst {
        /// The joint being added.
        name: String,
        /// Its parent.
        parent: String,
    },
    /// A joint index that does not exist.
    #[error("joint index {index} does not exist")]
    UnknownJoint {
        /// The index.
        index: usize,
    },
    /// A zero or non-finite joint axis (or two parallel axes of a joint that needs two).
    #[error("joint '{name}': axis is zero or not finite, or its two axes are parallel")]
    BadAxis {
        /// The joint.
        name: String,
    },
    /// A placement that is not a rigid transform.
    #[error("'{name}': placement is not a finite rigid transform")]
    BadPlacement {
        /// The joint or frame.
        name: String,
    },
    /// A non-physical body inertia.
    #[error("body '{name}': {source}")]
    BadInertia {
        /// The joint (body) or welded body.
        name: String,
        /// What is wrong.
        source: InertiaError,
    },
    /// A per-joint vector of the wrong length.
    #[error("joint '{joint}': {source}")]
    Dimension {
        /// The joint.
        joint: String,
        /// The lengths.
        source: DimensionError,
    },
    /// Limits with NaN, `lower > upper`, or a negative velocity/effort limit.
    #[error("joint '{joint}': invalid limits")]
    BadLimits {
        /// The joint.
        joint: String,
    },
    /// Negative or non-finite armature.
    #[error("joint '{joint}': armature must be finite and non-negative")]
    BadArmature {
        /// The joint.
        joint: String,
    },
    /// Negative or non-finite joint damping or friction.
    #[error("joint '{joint}': damping and friction must be finite and non-negative")]
    BadDynamics {
        /// The joint.
        joint: String,
    },
    /// Non-finite gravity.
    #[error("gravity must be finite")]
    BadGravity,
    /// A model file (the serialised form) that does not describe a valid model.
    #[error("model file: {what}")]
    InvalidFile {
        /// What is wrong.
        what: String,
    },
    /// A builder input that does not describe a supported joint (e.g. a helical screw axis).
    #[error("joint {index}: {reason}")]
    Unsupported {
        /// Index of the joint in the builder's input.
        index: usize,
        /// What is not supported.
        reason: &'static str,
    },
}

/// An invalid input to an algorithm.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum MultibodyError {
    /// An input vector of the wrong length.
    #[error(transparent)]
    Dimension(#[from] DimensionError),
    /// A NaN or infinite entry.
    #[error("{what}[{index}] is not finite")]
    NonFinite {
        /// Which input (`q`, `v`, `a`, `tau`).
        what: &'static str,
        /// The index of the bad entry.
        index: usize,
    },
    /// A spherical or free-flyer joint whose quaternion is not of unit norm
    /// (tolerance [`QUATERNION_TOLERANCE`]).
    #[error("joint '{joint}': quaternion norm {norm} is not 1 (tolerance 1e-6)")]
    NotUnitQuaternion {
        /// The joint.
        joint: String,
        /// The norm found.
        norm: f64,
    },
    /// The mass matrix is not positive definite (Cholesky failed).
    #[error("mass matrix is not positive definite")]
    NotPositiveDefinite,
    /// A [`Data`] made for another model: different numbers of joints, configuration
    /// coordinates or degrees of freedom, or other joints (parents, types, axes), whose
    /// constant motion subspaces and tree it holds.
    #[error("data was made for another model ({njoints} joints, nq = {nq}, nv = {nv})")]
    DataMismatch {
        /// Joints the data was made for.
        njoints: usize,
        /// Configuration coordinates the data was made for.
        nq: usize,
        /// Degrees of freedom the data was made for.
        nv: usize,
    },
    /// An algorithm that does not (yet) handle a joint whose motion subspace depends on `q`
    /// (a universal joint): the analytical derivatives, `J̇` and the Coriolis matrix assume `S`
    /// constant in body coordinates.
    #[error("joint '{joint}' ({kind}): {algorithm} assumes every joint's motion subspace is constant in body coordinates, and this one's depends on q; use finite differences of the other algorithms")]
    Unsupported {
        /// The joint.
        joint: String,
        /// Its type.
        kind: &'static str,
        /// The algorithm.
        algorithm: &'static str,
    },
    /// A frame or joint index out of range.
    #[error("{what} index {index} out of range")]
    OutOfRange {
        /// "joint" or "frame".
        what: &'static str,
        /// The index.
        index: usize,
    },
}

/// Check `q`: length `nq`, finite, unit quaternions.
pub(crate) fn check_q(model: &Model, q: &[f64]) -> Result<(), MultibodyError> {
    DimensionError::check("q", model.nq, q.len())?;
    check_finite("q", q)?;
    for &(j, o) in &model.plan().quaternions {
        let n = crate::spatial::quat_norm(&q[o..o + 4]);
        if (n - 1.0).abs() > QUATERNION_TOLERANCE {
            return Err(MultibodyError::NotUnitQuaternion {
                joint: model.joints()[j].name.clone(),
                norm: n,
            });
        }
    }
    Ok(())
}

/// Check that `data` was made by `Data::new(model)` (or a model of the same shape).
pub(crate) fn check_data(model: &Model, data: &Data) -> Result<(), MultibodyError> {
    if data.placements.len() != model.njoints()
        || data.tau.len() != model.nv
        || data.sin_cos.len() != model.nq
        || data.frame_placements.len() != model.frames.len()
        || data.joints_key != model.plan().joints_key
    {
        return Err(MultibodyError::DataMismatch {
            njoints: data.placements.len(),
            nq: data.sin_cos.len(),
            nv: data.tau.len(),
        });
    }
    Ok(())
}

/// Check a velocity-like vector: length `nv`, finite.
pub(crate) fn check_v(model: &Model, what: &'static str, v: &[f64]) -> Result<(), MultibodyError> {
    DimensionError::check(what, model.nv, v.len())?;
    check_finite(what, v)
}

fn check_finite(what: &'static str, x: &[f64]) -> Result<(), MultibodyError> {
    match first_non_finite(x) {
        Some(index) => Err(MultibodyError::NonFinite { what, index }),
        None => Ok(()),
    }
}

/// The index of the first entry of `x` that is NaN or infinite, if any, as every input check
/// finds it.
///
/// Blocks of 512 entries are summed as `Σ 0·x_i`, which is 0 when every entry is finite and NaN
/// otherwise (no branch per entry), in 8 independent partial sums (one chain of additions would
/// wait 3-4 cycles per entry); only a block whose sum is not 0 is searched.
///
/// ```
/// use rigid::multibody::first_non_finite;
/// let mut x = vec![1.0; 2000];
/// assert_eq!(first_non_finite(&x), None);
/// x[1500] = f64::NEG_INFINITY;
/// x[1700] = f64::NAN;
/// assert_eq!(first_non_finite(&x), Some(1500));
/// ```
#[must_use]
pub fn first_non_finite(x: &[f64]) -> Option<usize> {
    const BLOCK: usize = 512;
    x.chunks(BLOCK).enumerate().find_map(|(b, block)| {
        let mut sums = [0.0; 8];
        let mut eights = block.chunks_exact(8);
        for e in &mut eights {
            for (s, v) in sums.iter_mut().zip(e) {
                *s += 0.0 * v;
            }
        }
        for (s, v) in sums.iter_mut().zip(eights.remainder()) {
            *s += 0.0 * v;
        }
        if sums.iter().sum::<f64>() == 0.0 {
            return None;
        }
        block
            .iter()
            .position(|x| !x.is_finite())
            .map(|i| b * BLOCK + i)
    })
}
