//! Wrenches `F = (m, f)`, moment first.

use super::twist::spatial_vector_ops;
use super::{Vec3, Vec6};
use std::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// A wrench (spatial force) `F = (m, f)`, **moment first**: the moment `m` about the frame
/// origin and the force `f`, both in the frame's axes. Wrenches change frame by
/// `F_b = [Ad_{T_ab}]ᵀ F_a` ([`Transform::inv_act_wrench`](super::Transform::inv_act_wrench)), so
/// that the power `Fᵀ V` is the same in every frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Wrench {
    /// Moment `m` (N·m) about the frame origin.
    pub m: Vec3,
    /// Force `f` (N).
    pub f: Vec3,
}

impl Wrench {
    /// `F = (m, f)`.
    #[must_use]
    #[inline]
    pub fn new(m: Vec3, f: Vec3) -> Self {
        Self { m, f }
    }

    /// The zero wrench.
    #[must_use]
    #[inline]
    pub fn zero() -> Self {
        Self::new(Vec3::zeros(), Vec3::zeros())
    }

    /// The wrench of a force `f` applied at the point `r` (both in the frame's axes):
    /// `F = (r × f, f)`.
    #[must_use]
    #[inline]
    pub fn from_force_at(f: Vec3, r: &Vec3) -> Self {
        Self::new(r.cross(&f), f)
    }

    /// From the 6-vector `[mx my mz fx fy fz]`.
    #[must_use]
    #[inline]
    pub fn from_vector(x: &Vec6) -> Self {
        Self::new(x.fixed_rows::<3>(0).into(), x.fixed_rows::<3>(3).into())
    }

    /// From a slice of six numbers `[mx my mz fx fy fz]` (panics unless `x.len() == 6`).
    #[must_use]
    #[inline]
    pub fn from_slice(x: &[f64]) -> Self {
        Self::new(Vec3::new(x[0], x[1], x[2]), Vec3::new(x[3], x[4], x[5]))
    }

    /// The 6-vector `[mx my mz fx fy fz]`.
    #[must_use]
    #[inline]
    pub fn to_vector(&self) -> Vec6 {
        Vec6::new(self.m.x, self.m.y, self.m.z, self.f.x, self.f.y, self.f.z)
    }

    /// The Euclidean norm of the 6-vector (mixes units: for tests and tolerances).
    #[must_use]
    #[inline]
    pub fn norm(&self) -> f64 {
        (self.m.norm_squared() + self.f.norm_squared()).sqrt()
    }
}

spatial_vector_ops!(Wrench, m, f);
