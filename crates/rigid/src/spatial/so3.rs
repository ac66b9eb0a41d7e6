//! The rotation group SO(3): exponential and logarithm, and conversions between rotation matrices,
//! unit quaternions, axis-angle and URDF roll-pitch-yaw.
//!
//! Rodrigues' formula (Lynch & Park, Prop. 3.11): `exp([ω̂]θ) = I + sin θ [ω̂] + (1 - cos θ)[ω̂]²`.
//! Every function is accurate to round-off near `θ = 0` (Taylor series) and near `θ = π`.

use super::{skew, unskew, Mat3, Vec3};
use crate::error::RotationError;
use nalgebra::{Quaternion, Rotation3, UnitQuaternion};

/// Below this angle the trigonometric coefficients are evaluated by their Taylor series.
const SMALL_ANGLE: f64 = 1e-4;

/// `exp([ω])`: the rotation by angle `|ω|` about the axis `ω/|ω|` (Rodrigues' formula).
///
/// ```
/// use rigid::spatial::{so3, Vec3};
/// let r = so3::exp(&Vec3::new(0.0, 0.0, std::f64::consts::FRAC_PI_2));
/// assert!((r * Vec3::x() - Vec3::y()).norm() < 1e-15);
/// ```
#[must_use]
pub fn exp(w: &Vec3) -> Mat3 {
    let theta2 = w.norm_squared();
    let theta = theta2.sqrt();
    // sin θ / θ and (1 - cos θ) / θ²
    let (a, b) = if theta < SMALL_ANGLE {
        (1.0 - theta2 / 6.0, 0.5 - theta2 / 24.0)
    } else {
        (theta.sin() / theta, (1.0 - theta.cos()) / theta2)
    };
    let k = skew(w);
    Mat3::identity() + k * a + k * k * b
}

/// `log R`: the rotation vector `ω = ω̂ θ`, `θ ∈ [0, π]`, with `exp([ω]) = R`.
///
/// `θ` comes from `atan2(|vee(R - Rᵀ)|/2, (tr R - 1)/2)`, accurate over the whole range; near
/// `θ = π`, where `R - Rᵀ` vanishes, the axis is read from the symmetric part `R + Rᵀ`.
///
/// ```
/// use rigid::spatial::{so3, Vec3};
/// let w = Vec3::new(0.3, -1.2, 2.0);
/// assert!((so3::log(&so3::exp(&w)) - w).norm() < 1e-12);
/// ```
#[must_use]
pub fn log(r: &Mat3) -> Vec3 {
    let s = unskew(r); // = sin θ ω̂
    let sin_t = s.norm();
    let cos_t = 0.5 * (r.trace() - 1.0);
    let theta = sin_t.atan2(cos_t);
    if theta < SMALL_ANGLE {
        // θ / sin θ ≈ 1 + θ²/6
        return s * (1.0 + theta * theta / 6.0);
    }
    if theta < std::f64::consts::PI - 1e-3 {
        return s * (theta / sin_t);
    }
    // Near π: (R + Rᵀ)/2 - cos θ I = (1 - cos θ) ω̂ ω̂ᵀ. Take the largest column for the axis.
    let b = (r + r.transpose()) * 0.5 - Mat3::identity() * cos_t;
    let (mut k, mut best) = (0, b[(0, 0)]);
    for i in 1..3 {
        if b[(i, i)] > best {
            best = b[(i, i)];
            k = i;
        }
    }
    let mut axis = b.column(k).into_owned();
    axis /= axis.norm();
    // The sign is fixed by sin θ ω̂ = vee((R - Rᵀ)/2), when it is not lost in round-off.
    if axis.dot(&s) < 0.0 {
        axis = -axis;
    }
    axis * theta
}

/// The rotation of angle `theta` about the unit `axis`.
///
/// # Errors
/// [`RotationError::ZeroAxis`] if `axis` has zero or non-finite length.
pub fn from_axis_angle(axis: &Vec3, theta: f64) -> Result<Mat3, RotationError> {
    let n = axis.norm();
    if !(n.is_finite() && n > 0.0 && theta.is_finite()) {
        return Err(RotationError::ZeroAxis);
    }
    Ok(exp(&(axis * (theta / n))))
}

/// URDF roll-pitch-yaw (fixed axes x, then y, then z): `R = Rz(yaw) Ry(pitch) Rx(roll)`.
///
/// ```
/// use rigid::spatial::{so3, Vec3};
/// let r = so3::from_rpy(0.1, -0.4, 2.0);
/// let (roll, pitch, yaw) = so3::to_rpy(&r);
/// assert!((roll - 0.1).abs() + (pitch + 0.4).abs() + (yaw - 2.0).abs() < 1e-12);
/// ```
#[must_use]
pub fn from_rpy(roll: f64, pitch: f64, yaw: f64) -> Mat3 {
    let (sr, cr) = roll.sin_cos();
    let (sp, cp) = pitch.sin_cos();
    let (sy, cy) = yaw.sin_cos();
    Mat3::new(
        cy * cp,
        cy * sp * sr - sy * cr,
        cy * sp * cr + sy * sr,
        sy * cp,
        sy * sp * sr + cy * cr,
        sy * sp * cr - cy * sr,
        -sp,
        cp * sr,
        cp * cr,
    )
}

/// The roll, pitch, yaw of [`from_rpy`], with pitch in `[-π/2, π/2]`.
#[must_use]
pub fn to_rpy(r: &Mat3) -> (f64, f64, f64) {
    let pitch = (-r[(2, 0)]).atan2((r[(0, 0)].powi(2) + r[(1, 0)].powi(2)).sqrt());
    if (std::f64::consts::FRAC_PI_2 - pitch.abs()) < 1e-9 {
        // Gimbal lock: only roll ∓ yaw is defined; put it all in yaw.
        return (0.0, pitch, (-r[(0, 1)]).atan2(r[(1, 1)]));
    }
    let roll = r[(2, 1)].atan2(r[(2, 2)]);
    let yaw = r[(1, 0)].atan2(r[(0, 0)]);
    (roll, pitch, yaw)
}

/// The rotation matrix of the quaternion `(x, y, z, w)` (scalar last, as in ROS).
///
/// # Errors
/// [`RotationError::NotUnitQuaternion`] if the norm differs from 1 by more than `tol` (the
/// quaternion is normalised otherwise), or a component is not finite.
pub fn from_quaternion(x: f64, y: f64, z: f64, w: f64, tol: f64) -> Result<Mat3, RotationError> {
    let q = Quaternion::new(w, x, y, z);
    let n = q.norm();
    if !n.is_finite() || (n - 1.0).abs() > tol {
        return Err(RotationError::NotUnitQuaternion { norm: n });
    }
    Ok(*UnitQuaternion::from_quaternion(q)
        .to_rotation_matrix()
        .matrix())
}

/// The unit quaternion `(x, y, z, w)` of a rotation matrix, with `w ≥ 0`.
#[must_use]
pub fn to_quaternion(r: &Mat3) -> [f64; 4] {
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(*r));
    let s = if q.w < 0.0 { -1.0 } else { 1.0 };
    [s * q.i, s * q.j, s * q.k, s * q.w]
}

/// Checks that `r` is a rotation: `RᵀR = I` within `tol` (max abs entry) and `det R = +1`.
///
/// # Errors
/// [`RotationError::NotOrthonormal`] or [`RotationError::Reflection`] saying which test failed.
pub fn check(r: &Mat3, tol: f64) -> Result<(), RotationError> {
    if r.iter().any(|x| !x.is_finite()) {
        return Err(RotationError::NonFinite);
    }
    let err = (r.transpose() * r - Mat3::identity()).amax();
    if err > tol {
        return Err(RotationError::NotOrthonormal { error: err });
    }
    if r.determinant() < 0.0 {
        return Err(RotationError::Reflection);
    }
    Ok(())
}

/// The rotation closest to `m` in the Frobenius norm (polar decomposition by SVD), for cleaning up
/// a matrix that is a rotation up to round-off.
#[must_use]
pub fn orthonormalize(m: &Mat3) -> Mat3 {
    let svd = m.svd(true, true);
    let (u, vt) = (svd.u.unwrap_or_default(), svd.v_t.unwrap_or_default());
    let mut d = Mat3::identity();
    if (u * vt).determinant() < 0.0 {
        d[(2, 2)] = -1.0;
    }
    u * d * vt
}

// --- quaternions (x, y, z, w), scalar last as in ROS: the joints' configuration kernels ---

/// Quaternion `(x, y, z, w)` → rotation matrix, normalising first.
#[inline]
pub(crate) fn quat_to_rot(x: f64, y: f64, z: f64, w: f64) -> Mat3 {
    let n2 = x * x + y * y + z * z + w * w;
    let s = 2.0 / n2;
    let (xx, yy, zz) = (x * x * s, y * y * s, z * z * s);
    let (xy, xz, yz) = (x * y * s, x * z * s, y * z * s);
    let (wx, wy, wz) = (w * x * s, w * y * s, w * z * s);
    Mat3::new(
        1.0 - yy - zz,
        xy - wz,
        xz + wy,
        xy + wz,
        1.0 - xx - zz,
        yz - wx,
        xz - wy,
        yz + wx,
        1.0 - xx - yy,
    )
}

/// Hamilton product `a ⊗ b` of quaternions stored `(x, y, z, w)`.
#[inline]
pub(crate) fn quat_mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    let [ax, ay, az, aw] = a;
    let [bx, by, bz, bw] = b;
    [
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    ]
}

/// `exp(ω/2)` as a unit quaternion `(x, y, z, w)`: the rotation `exp([ω])`.
#[inline]
pub(crate) fn quat_exp(w: &Vec3) -> [f64; 4] {
    let t = w.norm();
    let h = 0.5 * t;
    let s = if t < 1e-4 {
        0.5 - t * t / 48.0
    } else {
        h.sin() / t
    };
    [w.x * s, w.y * s, w.z * s, h.cos()]
}

/// Normalise a quaternion in place, with the sign `w ≥ 0`.
#[inline]
pub(crate) fn quat_normalize(q: &mut [f64]) {
    let n = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
    let s = if q[3] < 0.0 { -1.0 / n } else { 1.0 / n };
    for x in q.iter_mut().take(4) {
        *x *= s;
    }
}

/// The quaternion norm `|q|` of the four numbers `q[0..4]`.
#[inline]
pub(crate) fn quat_norm(q: &[f64]) -> f64 {
    (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt()
}
