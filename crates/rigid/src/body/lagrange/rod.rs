//! The rod on a spherical pivot of the notes 002, in the angles `(φ, θ)`.

use super::{Lagrangian, Scalar};
use crate::body::{BodyError, RigidBody, State};
use crate::mass::{RotationalInertia, SpatialInertia};
use crate::spatial::{Mat3, Transform, Twist, Vec3};
use nalgebra::Vector2;

/// A thin uniform rod of mass `m` and length `L` hanging from a spherical pivot at one end, under
/// gravity `g` along `-z` (notes 002, "Lagrange's equations with rigid bodies").
///
/// Coordinates `q = (φ, θ)`: the rod frame is `R = Rz(φ) Rx(θ)` and the rod lies along `-z` of
/// its frame, so `θ = 0` hangs straight down. Its body angular velocity is
/// `ω_b = (θ̇, φ̇ sin θ, φ̇ cos θ)`, its inertia about the pivot `I_B = diag(⅓mL², ⅓mL², 0)`, and
///
/// `K = ½ ω_bᵀ I_B ω_b = ⅙ m L² (θ̇² + sin²θ φ̇²)`, `U = -m g (L/2) cos θ`.
///
/// Lagrange's equations are then `⅓mL² sin²θ φ̈ + ⅔mL² sinθ cosθ θ̇ φ̇ = 0` and
/// `⅓mL² θ̈ - ⅓mL² sinθ cosθ φ̇² + m g (L/2) sinθ = 0`. `M(q)` is singular at `sin θ = 0`
/// (the angles' pole), where `φ` is undefined.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RodOnPivot {
    /// Mass `m` (kg).
    pub mass: f64,
    /// Length `L` (m).
    pub length: f64,
    /// Gravity `g` (m/s², positive, along `-z`).
    pub gravity: f64,
}

impl RodOnPivot {
    /// The body angular velocity `ω_b = (θ̇, φ̇ sin θ, φ̇ cos θ)` for `q = (φ, θ)`.
    pub fn body_angular_velocity<D: Scalar>(q: &[D; 2], qd: &[D; 2]) -> [D; 3] {
        let (s, c) = q[1].sin_cos();
        [qd[1], qd[0] * s, qd[0] * c]
    }

    /// The rod frame `R = Rz(φ) Rx(θ)`.
    #[must_use]
    pub fn rotation(q: &Vector2<f64>) -> Mat3 {
        let rz = crate::spatial::so3::exp(&(Vec3::z() * q[0]));
        let rx = crate::spatial::so3::exp(&(Vec3::x() * q[1]));
        rz * rx
    }

    /// The world position of the free end, `R (0, 0, -L)`, with the pivot at the origin.
    #[must_use]
    pub fn tip(&self, q: &Vector2<f64>) -> Vec3 {
        Self::rotation(q) * Vec3::new(0.0, 0.0, -self.length)
    }

    /// The same rod as a [`RigidBody`] on a pivot, for the simulator: CoM at `(0, 0, -L/2)`,
    /// inertia about the CoM `diag(mL²/12, mL²/12, J)` with a spin inertia `J > 0` (a real rod's
    /// `½ m r²`), gravity `(0, 0, -g)`. Started with no spin about its axis ([`Self::state`]),
    /// the spin stays zero and `J` plays no part.
    ///
    /// # Errors
    /// If the parameters are not physical.
    pub fn pivot_body(&self, spin_inertia: f64) -> Result<RigidBody, BodyError> {
        let (m, l) = (self.mass, self.length);
        let i = m * l * l / 12.0;
        let g = SpatialInertia::from_com(
            m,
            Vec3::new(0.0, 0.0, -0.5 * l),
            RotationalInertia::diagonal(i, i, spin_inertia),
        );
        RigidBody::pivot(g)?.with_gravity(Vec3::new(0.0, 0.0, -self.gravity))
    }

    /// The simulator state of the rod at `(q, q̇)`: pose `Rz(φ) Rx(θ)` at the pivot, body
    /// angular velocity `(θ̇, φ̇ sin θ, 0)`: the part of `ω_b` that moves the rod's axis (the
    /// spin about the axis, `φ̇ cos θ` in the `(φ, θ)` frame, does not move a thin rod).
    #[must_use]
    pub fn state(q: &Vector2<f64>, qd: &Vector2<f64>) -> State {
        let w = Vec3::new(qd[1], qd[0] * q[1].sin(), 0.0);
        State::new(
            Transform::from_rotation(Self::rotation(q)),
            Twist::new(w, Vec3::zeros()),
        )
    }
}

impl Lagrangian<2> for RodOnPivot {
    fn kinetic_energy<D: Scalar>(&self, q: &[D; 2], qd: &[D; 2]) -> D {
        let i = self.mass * self.length * self.length / 3.0; // about the pivot
        let w = Self::body_angular_velocity(q, qd);
        // ½ ω_bᵀ diag(i, i, 0) ω_b
        (w[0] * w[0] + w[1] * w[1]) * (0.5 * i)
    }

    fn potential_energy<D: Scalar>(&self, q: &[D; 2]) -> D {
        q[1].cos() * (-self.mass * self.gravity * 0.5 * self.length)
    }
}
