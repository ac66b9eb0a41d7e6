//! Twists `V = (ω, v)`, angular first.

use super::{skew, Mat6, Vec3, Vec6, Wrench};
use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// A twist (spatial velocity) `V = (ω, v)`, **angular first**.
///
/// In a frame {b}: `ω` is the angular velocity and `v` the velocity of the point of the body at
/// the origin of {b}, both in {b} axes (the body twist `[V_b] = T⁻¹ Ṫ`); likewise for the
/// spatial twist `[V_s] = Ṫ T⁻¹`. Twists change frame by `V_a = [Ad_{T_ab}] V_b`
/// ([`Transform::act_twist`](super::Transform::act_twist)).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Twist {
    /// Angular velocity `ω` (rad/s).
    pub w: Vec3,
    /// Linear velocity `v` (m/s) of the point at the frame origin.
    pub v: Vec3,
}

impl Twist {
    /// `V = (ω, v)`.
    #[must_use]
    #[inline]
    pub fn new(w: Vec3, v: Vec3) -> Self {
        Self { w, v }
    }

    /// The zero twist.
    #[must_use]
    #[inline]
    pub fn zero() -> Self {
        Self::new(Vec3::zeros(), Vec3::zeros())
    }

    /// From the 6-vector `[ωx ωy ωz vx vy vz]`.
    #[must_use]
    #[inline]
    pub fn from_vector(x: &Vec6) -> Self {
        Self::new(x.fixed_rows::<3>(0).into(), x.fixed_rows::<3>(3).into())
    }

    /// From a slice of six numbers `[ωx ωy ωz vx vy vz]` (panics unless `x.len() == 6`).
    #[must_use]
    #[inline]
    pub fn from_slice(x: &[f64]) -> Self {
        Self::new(Vec3::new(x[0], x[1], x[2]), Vec3::new(x[3], x[4], x[5]))
    }

    /// The 6-vector `[ωx ωy ωz vx vy vz]`.
    #[must_use]
    #[inline]
    pub fn to_vector(&self) -> Vec6 {
        Vec6::new(self.w.x, self.w.y, self.w.z, self.v.x, self.v.y, self.v.z)
    }

    /// The Euclidean norm of the 6-vector (mixes units: for tests and tolerances).
    #[must_use]
    #[inline]
    pub fn norm(&self) -> f64 {
        (self.w.norm_squared() + self.v.norm_squared()).sqrt()
    }

    /// `[ad_V] = [[[ω], 0], [[v], [ω]]]`, the Lie bracket matrix (Lynch & Park, Def. 8.2).
    #[must_use]
    pub fn ad(&self) -> Mat6 {
        let (kw, kv) = (skew(&self.w), skew(&self.v));
        let mut m = Mat6::zeros();
        m.fixed_view_mut::<3, 3>(0, 0).copy_from(&kw);
        m.fixed_view_mut::<3, 3>(3, 3).copy_from(&kw);
        m.fixed_view_mut::<3, 3>(3, 0).copy_from(&kv);
        m
    }

    /// The Lie bracket `[ad_V1] V2 = (ω1 × ω2, v1 × ω2 + ω1 × v2)`, the twist cross product
    /// (Featherstone's `v1 ×`).
    ///
    /// ```
    /// use rigid::spatial::{Twist, Vec3};
    /// let a = Twist::new(Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
    /// let b = Twist::new(Vec3::new(0.0, 1.0, 3.0), Vec3::new(1.0, 0.0, 0.0));
    /// assert!((a.cross(&b) + b.cross(&a)).norm() < 1e-15);
    /// assert!((a.cross(&b).to_vector() - a.ad() * b.to_vector()).norm() < 1e-15);
    /// ```
    #[must_use]
    #[inline]
    pub fn cross(&self, other: &Twist) -> Twist {
        Twist::new(
            self.w.cross(&other.w),
            self.v.cross(&other.w) + self.w.cross(&other.v),
        )
    }

    /// `[ad_V]ᵀ F = (-(ω × m) - v × f, -(ω × f))`, the action on wrenches in the Newton-Euler
    /// equations `F = G V̇ - [ad_V]ᵀ G V`. (Featherstone's `v ×* F` is `-[ad_V]ᵀ F`.)
    #[must_use]
    #[inline]
    pub fn ad_transpose(&self, f: &Wrench) -> Wrench {
        Wrench::new(
            -(self.w.cross(&f.m) + self.v.cross(&f.f)),
            -self.w.cross(&f.f),
        )
    }

    /// The power pairing `Fᵀ V = m·ω + f·v` (W).
    #[must_use]
    #[inline]
    pub fn dot(&self, f: &Wrench) -> f64 {
        self.w.dot(&f.m) + self.v.dot(&f.f)
    }
}

macro_rules! spatial_vector_ops {
    ($t:ident, $a:ident, $b:ident) => {
        impl Add for $t {
            type Output = $t;
            #[inline]
            fn add(self, o: $t) -> $t {
                $t::new(self.$a + o.$a, self.$b + o.$b)
            }
        }
        impl Sub for $t {
            type Output = $t;
            #[inline]
            fn sub(self, o: $t) -> $t {
                $t::new(self.$a - o.$a, self.$b - o.$b)
            }
        }
        impl AddAssign for $t {
            #[inline]
            fn add_assign(&mut self, o: $t) {
                self.$a += o.$a;
                self.$b += o.$b;
            }
        }
        impl SubAssign for $t {
            #[inline]
            fn sub_assign(&mut self, o: $t) {
                self.$a -= o.$a;
                self.$b -= o.$b;
            }
        }
        impl Neg for $t {
            type Output = $t;
            #[inline]
            fn neg(self) -> $t {
                $t::new(-self.$a, -self.$b)
            }
        }
        impl Mul<f64> for $t {
            type Output = $t;
            #[inline]
            fn mul(self, s: f64) -> $t {
                $t::new(self.$a * s, self.$b * s)
            }
        }
        impl Mul<$t> for f64 {
            type Output = $t;
            #[inline]
            fn mul(self, x: $t) -> $t {
                x * self
            }
        }
    };
}
pub(crate) use spatial_vector_ops;

spatial_vector_ops!(Twist, w, v);
