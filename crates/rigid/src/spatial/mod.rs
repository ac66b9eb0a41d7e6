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

pub mod so3;
mod transform;
mod twist;
mod wrench;

pub use transform::Transform;
pub use twist::Twist;
pub use wrench::Wrench;

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

/// `R x` written out on the column-major storage (nalgebra's generic product is not always
/// unrolled on the hot paths of the multibody algorithms).
#[inline(always)]
pub(crate) fn mat3_vec(r: &Mat3, x: &Vec3) -> Vec3 {
    let a = r.as_slice();
    Vec3::new(
        a[0] * x.x + a[3] * x.y + a[6] * x.z,
        a[1] * x.x + a[4] * x.y + a[7] * x.z,
        a[2] * x.x + a[5] * x.y + a[8] * x.z,
    )
}

/// A constant 3-vector of a model (a joint offset, a centre of mass, a principal axis) kept as
/// `s e_k` when it lies on a coordinate axis, as URDF vectors often do, so that `R x` is one
/// column of `R` scaled (3 products) instead of a full product (9 products, 6 additions).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum ModelVec3 {
    /// `s e_k` (the zero vector is `0 e_0`).
    Axis(usize, f64),
    /// Any other vector.
    General(Vec3),
}

impl ModelVec3 {
    /// `s e_k` when at most one component is nonzero, else the vector as it is.
    pub(crate) fn new(x: &Vec3) -> Self {
        match (x.x != 0.0, x.y != 0.0, x.z != 0.0) {
            (false, false, false) => Self::Axis(0, 0.0),
            (true, false, false) => Self::Axis(0, x.x),
            (false, true, false) => Self::Axis(1, x.y),
            (false, false, true) => Self::Axis(2, x.z),
            _ => Self::General(*x),
        }
    }

    /// `R x`.
    #[inline(always)]
    pub(crate) fn rotated(&self, r: &Mat3) -> Vec3 {
        match *self {
            Self::Axis(k, s) => {
                let a = r.as_slice();
                Vec3::new(a[3 * k] * s, a[3 * k + 1] * s, a[3 * k + 2] * s)
            }
            Self::General(x) => mat3_vec(r, &x),
        }
    }
}

/// `Rᵀ x` written out on the column-major storage.
#[inline(always)]
pub(crate) fn mat3_tr_vec(r: &Mat3, x: &Vec3) -> Vec3 {
    let a = r.as_slice();
    Vec3::new(
        a[0] * x.x + a[1] * x.y + a[2] * x.z,
        a[3] * x.x + a[4] * x.y + a[5] * x.z,
        a[6] * x.x + a[7] * x.y + a[8] * x.z,
    )
}

#[cfg(test)]
mod tests {
    use super::{ModelVec3, Vec3};

    /// `R x` by the axis path equals the full product, for each axis, the zero vector and a
    /// general vector (which keeps the full product).
    #[test]
    fn model_vectors_rotate_like_the_full_product() {
        let r = nalgebra::Rotation3::from_euler_angles(0.3, -1.2, 2.0).into_inner();
        for x in [
            Vec3::zeros(),
            Vec3::new(-0.4, 0.0, 0.0),
            Vec3::new(0.0, 2.5, 0.0),
            Vec3::new(0.0, 0.0, 1e-3),
            Vec3::new(0.1, 0.0, -0.2),
        ] {
            let m = ModelVec3::new(&x);
            assert_eq!(matches!(m, ModelVec3::General(_)), x.x != 0.0 && x.z != 0.0);
            assert!((m.rotated(&r) - r * x).amax() < 1e-16, "{x}");
        }
    }
}
