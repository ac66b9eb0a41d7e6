//! Spatial algebra: the Lie groups SO(3) and SE(3), twists, wrenches, `Ad` and `ad`.
//!
//! Notation follows Lynch & Park, *Modern Robotics* (ch. 3 and 8) and the lecture notes:
//! twists `V = (ω, v)` and wrenches `F = (m, f)` are **angular first**; `T_ab` is frame {b}
//! seen from {a}, and `T_ab * T_bc = T_ac`.
//!
//! | notes | code |
//! | --- | --- |
//! | `[ω]` | [`skew`] |
//! | `exp([ω]θ)`, `log R` | [`so3::exp`], [`so3::log`] |
//! | `T = (R, p)` | [`Transform`] |
//! | `exp([S]θ)`, `log T` | [`Transform::exp`], [`Transform::log`] |
//! | `[Ad_T]` | [`Transform::adjoint`] |
//! | `[ad_V]` | [`Twist::ad`] |
//! | `[ad_V]ᵀ F` | [`Twist::ad_transpose`] |

mod kernels;
pub mod so3;
mod transform;
pub(crate) mod trig;
mod twist;
#[cfg(feature = "serde")]
pub(crate) mod wire;
mod wrench;

pub use transform::Transform;
pub use twist::Twist;
pub use wrench::Wrench;

pub(crate) use kernels::*;
pub(crate) use so3::{quat_exp, quat_mul, quat_norm, quat_normalize, quat_to_rot};

use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};

/// A 3-vector of `f64`.
pub type Vec3 = Vector3<f64>;
/// A 3x3 matrix of `f64`.
pub type Mat3 = Matrix3<f64>;
/// A 6-vector of `f64` (spatial vectors are laid out angular first).
pub type Vec6 = Vector6<f64>;
/// A 6x6 matrix of `f64`.
pub type Mat6 = Matrix6<f64>;

/// The skew-symmetric matrix `[ω]` of a 3-vector, so that `[ω] x = ω × x`.
///
/// ```
/// use rigid::spatial::{skew, Vec3};
/// let w = Vec3::new(1.0, 2.0, 3.0);
/// let x = Vec3::new(-4.0, 0.5, 2.0);
/// assert!((skew(&w) * x - w.cross(&x)).norm() < 1e-15);
/// ```
#[must_use]
#[inline]
pub fn skew(w: &Vec3) -> Mat3 {
    Mat3::new(0.0, -w.z, w.y, w.z, 0.0, -w.x, -w.y, w.x, 0.0)
}

/// The 3-vector `ω` of a skew-symmetric matrix `[ω]` (the inverse of [`skew`]); the symmetric part
/// of `m` is ignored: it returns `vee((m - mᵀ)/2)`.
#[must_use]
#[inline]
pub fn unskew(m: &Mat3) -> Vec3 {
    Vec3::new(
        0.5 * (m[(2, 1)] - m[(1, 2)]),
        0.5 * (m[(0, 2)] - m[(2, 0)]),
        0.5 * (m[(1, 0)] - m[(0, 1)]),
    )
}
