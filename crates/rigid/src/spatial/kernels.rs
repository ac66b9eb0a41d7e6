//! The small dense kernels of the spatial layer, written out on nalgebra's column-major storage
//! because nalgebra's generic 3x3 and 6x6 products are not fully unrolled on the hot paths of the
//! multibody algorithms. One home for each formula; the algorithms call these and never index
//! raw 6-vectors themselves.
//!
//! | formula | kernel |
//! | --- | --- |
//! | `R x`, `Rᵀ x`, `R_a R_b`, `T_a T_b` | [`mat3_vec`], [`mat3_tr_vec`], [`mat3_mul`], [`compose`] |
//! | `R exp([a] q)` (Rodrigues; two columns for a coordinate axis) | [`rotate_about`], [`rotate_about_sc`], [`rodrigues`] |
//! | `R x` for a constant model vector on a coordinate axis | [`ModelVec3`] |
//! | `I V` for a 6x6 inertia | [`mat6_twist`] |
//!
//! The congruence `Xᵀ I X` (`X = [Ad_{T⁻¹}]`) of a general symmetric 6x6 `I` (ABA's articulated
//! inertias) is the lane kernels' `I6::add_congruence` (`multibody/batch/aba.rs`); for a
//! *spatial inertia* `G` (structured `(m, h, I_O)`) it is
//! [`SpatialInertia::transformed`](crate::mass::SpatialInertia::transformed), with its one
//! specialised variant [`PrincipalForm::transformed`](crate::mass::PrincipalForm::transformed).

use super::{Mat3, Mat6, Transform, Twist, Vec3, Wrench};

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

/// `R_a R_b` written out (nalgebra's generic 3x3 product is not fully unrolled).
#[inline(always)]
pub(crate) fn mat3_mul(a: &Mat3, b: &Mat3) -> Mat3 {
    let a = a.as_slice();
    let b = b.as_slice();
    let mut c = [0.0; 9];
    // column-major: c[j*3 + i] = Σ_k a[k*3 + i] b[j*3 + k]
    for j in 0..3 {
        for i in 0..3 {
            c[j * 3 + i] = a[i] * b[j * 3] + a[3 + i] * b[j * 3 + 1] + a[6 + i] * b[j * 3 + 2];
        }
    }
    Mat3::from_column_slice(&c)
}

/// `T_a T_b = (R_a R_b, R_a p_b + p_a)` with [`mat3_mul`].
#[inline(always)]
pub(crate) fn compose(a: &Transform, b: &Transform) -> Transform {
    Transform::new(
        mat3_mul(&a.rotation, &b.rotation),
        mat3_vec(&a.rotation, &b.translation) + a.translation,
    )
}

/// Rodrigues' formula `exp([a] q) = c 1 + s [a] + (1 - c) a aᵀ` with `s = sin q`, `c = cos q`
/// (Lynch & Park, Prop. 3.11), for a unit axis `a`.
#[inline]
pub(crate) fn rodrigues(a: &Vec3, s: f64, c: f64) -> Mat3 {
    let t = 1.0 - c;
    let (x, y, z) = (a.x, a.y, a.z);
    Mat3::new(
        c + t * x * x,
        t * x * y - s * z,
        t * x * z + s * y,
        t * x * y + s * z,
        c + t * y * y,
        t * y * z - s * x,
        t * x * z - s * y,
        t * y * z + s * x,
        c + t * z * z,
    )
}

/// `R exp([a] q)`: for a coordinate axis `a = ±e_k` only two columns of `R` mix
/// (12 multiplications); otherwise Rodrigues' formula and a 3x3 product.
#[inline(always)]
pub(crate) fn rotate_about(r: &Mat3, a: &Vec3, q: f64) -> Mat3 {
    let (s, c) = super::trig::sin_cos(q);
    rotate_about_sc(r, a, s, c)
}

/// [`rotate_about`] with `s = sin q` and `c = cos q` given.
#[inline(always)]
pub(crate) fn rotate_about_sc(r: &Mat3, a: &Vec3, s: f64, c: f64) -> Mat3 {
    // columns j and k turn: u' = c u + s w, w' = c w - s u (constant indices in each arm)
    #[inline(always)]
    fn turn(r: &Mat3, j: usize, k: usize, s: f64, c: f64) -> Mat3 {
        let m = r.as_slice();
        let mut out = [0.0; 9];
        out.copy_from_slice(m);
        for t in 0..3 {
            let (u, w) = (m[3 * j + t], m[3 * k + t]);
            out[3 * j + t] = u * c + w * s;
            out[3 * k + t] = w * c - u * s;
        }
        Mat3::from_column_slice(&out)
    }
    if a.x == 0.0 && a.y == 0.0 {
        turn(r, 0, 1, s * a.z, c) // about ±z: columns 0 and 1 turn (a = -e_k turns by -q)
    } else if a.y == 0.0 && a.z == 0.0 {
        turn(r, 1, 2, s * a.x, c) // about ±x: columns 1 and 2 turn
    } else if a.x == 0.0 && a.z == 0.0 {
        turn(r, 2, 0, s * a.y, c) // about ±y: columns 2 and 0 turn
    } else {
        let rj = rodrigues(a, s, c);
        mat3_mul(r, &rj)
    }
}

/// `I V` for a 6x6 (articulated) inertia acting on a twist, giving a wrench (column-major loop
/// over a fixed-size array: unrolled, no bounds checks).
#[inline]
pub(crate) fn mat6_twist(m: &Mat6, t: &Twist) -> Wrench {
    let x = [t.w.x, t.w.y, t.w.z, t.v.x, t.v.y, t.v.z];
    let a: &[f64; 36] = m.as_slice().try_into().expect("6x6");
    let mut y = [0.0; 6];
    for c in 0..6 {
        for r in 0..6 {
            y[r] += a[c * 6 + r] * x[c];
        }
    }
    Wrench::new(Vec3::new(y[0], y[1], y[2]), Vec3::new(y[3], y[4], y[5]))
}

#[cfg(test)]
mod tests {
    use super::ModelVec3;
    use crate::spatial::Vec3;

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
