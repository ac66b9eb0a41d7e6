//! Wheeled mobile robots (Lynch & Park, *Modern Robotics*, ch. 13): the kinematics of
//! omnidirectional and nonholonomic bases, odometry, and mobile manipulation up to the course's
//! capstone. Planar chassis configurations are `q = (φ, x, y)`; planar body twists
//! `V_b = (ω_bz, v_bx, v_by)`, angular first as everywhere in rigid.
//!
//! | notes | code | source |
//! | --- | --- | --- |
//! | `u_i = h_i(φ) q̇`, `h_i(0) = 1/(r_i cos γ_i) [x_i sin(β_i+γ_i) - y_i cos(β_i+γ_i), cos(β_i+γ_i), sin(β_i+γ_i)]` | [`Wheel::h0`], [`Base::H`] | Lynch & Park eq. 13.5 |
//! | three omniwheels, four mecanum wheels | [`Base::omni3`], [`Base::mecanum`] | eq. 13.9, 13.10 |
//! | differential drive, car: `A(q) q̇ = 0`, `ω = v tan ψ / ℓ` | [`Base::diff_drive`], [`Base::car`], [`Base::constraint`], [`Base::steering`] | §13.3 |
//! | `V_b = F Δθ`, `F = H(0)†`; the planar exponential, `Δq = R(φ) Δq_b` | [`Base::F`], [`Base::odometry`] | §13.4, eq. 13.33–13.36 |
//! | `T_se = T_sb(q) T_b0 T_0e(θ)`, `J_e = [[Ad_{T_0e⁻¹ T_b0⁻¹}] F6, J_arm]` | [`MobileManipulator::forward`], [`MobileManipulator::jacobian`] | §13.5 |
//! | `V = [Ad_{X⁻¹X_d}] V_d + K_p X_err + K_i ∫X_err`, `(u, θ̇) = J_e† V` | [`Feedback::command`] | eq. 11.16, 13.37 |
//! | `τ = K (u_d − u)` on the wheel joints of a robot model, implicit in the time stepper | [`WheelDrive`] | velocity control |
//! | Euler step of chassis, arm and wheels; the pick-and-place reference; a whole run | [`MobileManipulator::next_state`], [`PickAndPlace::reference`], [`Capstone::run`] | the capstone project |
//!
//! ```
//! use rigid::mobile::Capstone;
//! let run = Capstone::youbot().run()?;
//! // the feedback brings the end effector onto the reference and keeps it there
//! let last = run.errors.last().unwrap();
//! assert!(last.norm() < 1e-3, "{}", last.norm());
//! # Ok::<(), rigid::mobile::MobileError>(())
//! ```
//!
//! Wheels that roll in the simulator are bodies with revolute joints and cylinder collision
//! shapes touching the ground ([`crate::simulation`]); [`WheelDrive`] commands their speeds
//! (`rigid mobile drive`); docs/mobile.md shows a differential drive and TIAGo.

mod base;
mod capstone;
mod drive;
mod manipulator;

pub use base::{chassis_velocity, planar_rotation, Base, Kind, Wheel};
pub use capstone::{Capstone, CapstoneRun, MobileState, PickAndPlace, ReferencePoint};
pub use drive::{chassis_motion, WheelDrive};
#[cfg(feature = "collision")]
pub use drive::{drive, wheel_simulator, DriveOptions, DriveRecord};
pub use manipulator::{Command, Feedback, MobileManipulator};

use crate::error::DimensionError;
use thiserror::Error;

/// What a wheeled base or a mobile manipulator refuses.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum MobileError {
    /// A length, radius or time that must be positive.
    #[error("{what} must be positive and finite, got {value}")]
    NotPositive {
        /// Which quantity.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A NaN or infinite input.
    #[error("{what} has a non-finite entry")]
    NotFinite {
        /// Which input.
        what: &'static str,
    },
    /// An error about one wheel.
    #[error("wheel {wheel}: {error}")]
    Wheel {
        /// The wheel's index (from 0, the row of `H`).
        wheel: usize,
        /// What is wrong with it.
        error: Box<MobileError>,
    },
    /// Rollers at ±90° to the driving direction (`cos γ = 0`): the wheel cannot push.
    #[error(
        "wheel {wheel}: its rollers slide along its driving direction (cos γ = 0), it cannot drive"
    )]
    RollersAlongDrive {
        /// The wheel's index.
        wheel: usize,
    },
    /// `H(0)` of lower rank than the base's motion needs.
    #[error("{base} base: H(0) has rank {rank}, the base needs {needed} (wheels placed so that some chassis motion drives no wheel)")]
    RankDeficient {
        /// The base's name.
        base: &'static str,
        /// The rank found.
        rank: usize,
        /// The rank needed (3 omnidirectional, 2 nonholonomic).
        needed: usize,
    },
    /// A joint's limits with `low > high` or NaN.
    #[error("arm joint {joint}: limits ({low}, {high}) are not a range")]
    Limits {
        /// The arm joint's index (from 0).
        joint: usize,
        /// The lower limit given.
        low: f64,
        /// The upper limit given.
        high: f64,
    },
    /// A wheel joint of a robot model that cannot be driven.
    #[error("wheel joint {name:?}: {reason}")]
    WheelJoint {
        /// The joint's name.
        name: String,
        /// Why (absent, not revolute).
        reason: String,
    },
    /// The simulator refused the run (its message).
    #[error("{0}")]
    Simulation(String),
    /// A vector of the wrong length.
    #[error(transparent)]
    Dimension(#[from] DimensionError),
}

impl MobileError {
    fn on_wheel(self, wheel: usize) -> Self {
        MobileError::Wheel {
            wheel,
            error: Box::new(self),
        }
    }
}
