//! One rigid body in motion: Newton-Euler equations in both directions, Euler's equations,
//! a simulator on SE(3) (free body or body on a pivot), and Lagrange's equations from energies by
//! automatic differentiation.
//!
//! | notes | code |
//! | --- | --- |
//! | `F = G V̇ - [ad_V]ᵀ G V` (000) | [`inverse_dynamics`] |
//! | `V̇ = G⁻¹(F + [ad_V]ᵀ G V)` | [`forward_dynamics`], [`InverseInertia`] |
//! | `m = I ω̇ + ω × I ω` about the CoM or a fixed point (002) | [`euler_moment`], [`euler_acceleration`] |
//! | gravity at the CoM, force at a point | [`gravity_wrench`], [`world_force_at_point`] |
//! | `Ṫ = T [V_b]`, `V̇_b = f(t, T, V_b)` | [`RigidBody`], [`Simulator`], [`Integrator`] |
//! | a `rigid mass` body set up for simulation | [`Setup`] |
//! | `M(q) q̈ + c(q, q̇) + g(q) = τ` from `K`, `U` | [`lagrange`] |
//!
//! The simulator speaks the multibody simulator's vocabulary ([`Integrator`] is
//! [`simulation::Integrator`](crate::simulation::Integrator), with the same
//! default, `rk4`): a free body is the one-joint case of a multibody model (a free-flyer), a body
//! on a pivot too (a spherical joint), and `semi-implicit`, `rk4` and `variational` step that
//! model with the multibody code. The Lie-group variational integrator of Lee, Leok &
//! McClamroch ([`Integrator::Lgvi`]) is the one stepper of its own here.
//!
//! Sources: Lynch & Park, *Modern Robotics*, §8.2 (twist-wrench form); Munthe-Kaas, "High order
//! Runge-Kutta methods on manifolds" (1999) for RKMK; Lee, Leok & McClamroch, "Lie group
//! variational integrators for the full body problem" (CMAME 2007) for the LGVI.

#[cfg(feature = "autodiff")]
pub mod lagrange;
mod lgvi;
mod newton_euler;
mod rigid_body;
mod setup;
mod simulate;

pub use crate::simulation::Integrator;
pub use newton_euler::{
    euler_acceleration, euler_moment, forward_dynamics, gravity_wrench, inverse_dynamics,
    world_force_at_point, InverseInertia, InverseRotationalInertia,
};
pub use rigid_body::{no_wrench, RigidBody, State, Support, WrenchFn};
pub use setup::Setup;
pub use simulate::{Simulator, Summary};

use crate::error::InertiaError;
use crate::multibody::ModelError;
use crate::simulation::SimulationError;
use thiserror::Error;

/// What can go wrong when setting up or stepping a body.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum BodyError {
    /// The mass properties are not physical.
    #[error("non-physical body: {0}")]
    Inertia(#[from] InertiaError),
    /// An inertia that is positive semi-definite but (numerically) singular, so some
    /// acceleration is undetermined (a thin rod spinning about its own axis, a point mass).
    #[error(
        "{what} is singular (smallest principal moment {smallest:.3e}, largest {largest:.3e}): \
         the angular acceleration is undetermined"
    )]
    SingularInertia {
        /// Which inertia.
        what: &'static str,
        /// The smallest principal moment.
        smallest: f64,
        /// The largest principal moment.
        largest: f64,
    },
    /// A body on a pivot with zero mass.
    #[error("a body on a pivot needs a positive mass, got {mass}")]
    MasslessPivot {
        /// The mass found.
        mass: f64,
    },
    /// A time step that is not positive and finite.
    #[error("time step must be positive and finite, got {dt}")]
    TimeStep {
        /// The step given.
        dt: f64,
    },
    /// A NaN or infinite input, or a state that became non-finite.
    #[error("{what} is not finite")]
    NonFinite {
        /// Which quantity.
        what: &'static str,
    },
    /// A body on a pivot given a linear velocity of the pivot point.
    #[error(
        "the pivot point is fixed: the linear part of the body twist must be zero, got {speed} m/s"
    )]
    PivotMoves {
        /// `|v_b|`.
        speed: f64,
    },
    /// The Newton iteration of the variational integrator did not converge.
    #[error("implicit step did not converge in {iterations} iterations (residual {residual:.3e}); reduce dt")]
    NoConvergence {
        /// Iterations done.
        iterations: usize,
        /// The last residual norm.
        residual: f64,
    },
    /// A mass matrix `M(q)` that is not positive definite (a coordinate singularity).
    #[error("mass matrix M(q) is not positive definite (coordinate singularity?)")]
    SingularMassMatrix,
    /// The body's one-joint model could not be built (a body that is not physical).
    #[error(transparent)]
    Model(#[from] ModelError),
    /// Another error of the multibody simulator that steps the body's one-joint model.
    #[error(transparent)]
    Simulation(SimulationError),
}
