//! Joint types: everything that depends on the kind of a joint lives in this module, so that a
//! new joint type is one arm in each `match` here and nothing anywhere else.
//!
//! | file | what |
//! | --- | --- |
//! | `mod.rs` | the [`JointType`] enum: `nq`, `nv`, the joint transform `X_J(q)`, the motion subspace `S(q)` and bias `c_J = Ṡ q̇`, neutral and random configurations, and the [`Shape`] and [`Group`] by which the algorithms and the Lie-group code dispatch |
//! | `lie.rs` | the Lie group of the configuration: `q ⊕ v dt`, `q₁ ⊖ q₀`, their Jacobians, `ad`, `dexp` and `dexp⁻¹` |
//! | `coords.rs` | names of the coordinates (CSV columns) and how they differ in Pinocchio's layout |
//!
//! The joint frame {J} is fixed in the parent body at `q = neutral`; the child body frame is {J}
//! moved by `X_J(q)`, the pose of the child frame in {J} (Featherstone 2008, §4.4: `jcalc`). The
//! motion subspace `S(q)` maps `q̇` to the child's body twist relative to the parent, in the child
//! frame. It is constant for most joints ("S is constant in body coordinates"), and then the bias
//! acceleration `c_J = Ṡ q̇` is zero; [`JointType::constant_subspace`] says which are not.
//!
//! The algorithms never match on `JointType`: they ask for a joint's [`Shape`] (revolute,
//! prismatic and free-flyer joints have written-out fast paths, every other joint takes the
//! general path through [`JointType::subspace`] and [`JointType::bias`]) and the Lie-group code
//! for its [`Group`].

mod coords;
pub(crate) mod lie;

pub use coords::{column_names, MujocoCoords, PinocchioCoords};

use crate::spatial::{
    quat_norm, quat_normalize, quat_to_rot, rodrigues, rotate_about, so3, trig, Mat3, Transform,
    Twist, Vec3,
};

/// A joint type. Axes are unit vectors in the joint frame. In files (JSON): an object tagged by
/// [`name`](Self::name), e.g. `{"type": "revolute", "axis": [0, 0, 1]}`.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)
)]
pub enum JointType {
    /// Rotation `q` (rad) about `axis` through the joint-frame origin:
    /// `X_J = (exp([axis] q), 0)`, `S = (axis, 0)`. A URDF `continuous` joint is a revolute joint
    /// without limits ([`Joint::continuous`](super::Joint::continuous) remembers the name).
    Revolute {
        /// Unit axis in the joint frame.
        #[cfg_attr(feature = "serde", serde(with = "crate::spatial::wire::vec3"))]
        axis: Vec3,
    },
    /// Translation `q` (m) along `axis`: `X_J = (1, axis q)`, `S = (0, axis)`.
    Prismatic {
        /// Unit axis in the joint frame.
        #[cfg_attr(feature = "serde", serde(with = "crate::spatial::wire::vec3"))]
        axis: Vec3,
    },
    /// Ball joint: `q = (qx, qy, qz, qw)` a unit quaternion, velocity the body angular velocity
    /// `ω_b`: `X_J = (R(q), 0)`, `S = [1₃; 0]`.
    Spherical,
    /// Free-flyer (floating base): `q = (x, y, z, qx, qy, qz, qw)`, velocity the body twist
    /// `(ω_b, v_b)`: `X_J = (R(q), p)`, `S = 1₆`.
    FreeFlyer,
    /// Planar joint in the joint frame's x-y plane: `q = (x, y, θ)`, velocity the body-frame
    /// `(v_x, v_y, ω_z)` (as Pinocchio's planar joint): `X_J = (Rz(θ), (x, y, 0))`,
    /// `S = [e_vx, e_vy, e_ωz]` constant in the child frame.
    Planar,
    /// Screw joint: rotation `q` (rad) about `axis` and translation `pitch q` (m) along it:
    /// `X_J = (exp([axis] q), pitch q axis)`, `S = (axis, pitch axis)` (Pinocchio's
    /// `JointModelHelicalUnaligned`).
    Helical {
        /// Unit axis in the joint frame.
        #[cfg_attr(feature = "serde", serde(with = "crate::spatial::wire::vec3"))]
        axis: Vec3,
        /// Translation per radian (m/rad).
        pitch: f64,
    },
    /// Universal (Cardan) joint: rotation `q₁` about `axis1`, then `q₂` about `axis2` in the
    /// frame so moved: `X_J = (exp([a₁] q₁) exp([a₂] q₂), 0)`. `S(q) = [(R₂ᵀ a₁, 0), (a₂, 0)]`
    /// with `R₂ = exp([a₂] q₂)` depends on `q₂`, and `c_J = Ṡ q̇ = ((R₂ᵀ a₁) × a₂ q̇₁ q̇₂, 0)`
    /// (Pinocchio's `JointModelUniversal`).
    Universal {
        /// Unit first axis, in the joint frame.
        #[cfg_attr(feature = "serde", serde(with = "crate::spatial::wire::vec3"))]
        axis1: Vec3,
        /// Unit second axis, in the frame moved by the first rotation (not parallel to
        /// `axis1`).
        #[cfg_attr(feature = "serde", serde(with = "crate::spatial::wire::vec3"))]
        axis2: Vec3,
    },
}

/// How the algorithms treat a joint: the three joints with written-out fast paths, and the
/// general path for every other joint (`X_J` from [`JointType::placed_transform`], `S` from
/// [`JointType::subspace`], `c_J` from [`JointType::bias`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Shape {
    /// `S = (axis, 0)` constant, one dof, `X_J` a rotation about `axis`.
    Revolute(Vec3),
    /// `S = (0, axis)` constant, one dof, `X_J` a translation along `axis`.
    Prismatic(Vec3),
    /// `S = 1₆`.
    FreeFlyer,
    /// Anything else.
    General,
}

/// The Lie group of a joint's configuration, which decides `q ⊕ v`, `q₁ ⊖ q₀` and their
/// Jacobians ([`lie`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Group {
    /// `ℝⁿ` with `v = q̇`: the vector joints.
    Vector,
    /// SO(3), `q` a unit quaternion `(x, y, z, w)`, `v = ω_b`.
    SO3,
    /// SE(3), `q = (p, quaternion)`, `v = (ω_b, v_b)`.
    SE3,
    /// SE(2), `q = (x, y, θ)`, `v = (v_x, v_y, ω)` in the body frame.
    SE2,
}

impl JointType {
    /// Number of configuration coordinates `nq`.
    #[must_use]
    #[inline]
    pub fn nq(&self) -> usize {
        match self {
            Self::Revolute { .. } | Self::Prismatic { .. } | Self::Helical { .. } => 1,
            Self::Universal { .. } => 2,
            Self::Spherical => 4,
            Self::FreeFlyer => 7,
            Self::Planar => 3,
        }
    }

    /// Number of velocity coordinates `nv` (degrees of freedom).
    #[must_use]
    #[inline]
    pub fn nv(&self) -> usize {
        match self {
            Self::Revolute { .. } | Self::Prismatic { .. } | Self::Helical { .. } => 1,
            Self::Universal { .. } => 2,
            Self::Spherical | Self::Planar => 3,
            Self::FreeFlyer => 6,
        }
    }

    /// A short lower-case name (`revolute`, `prismatic`, `spherical`, `free_flyer`, `planar`,
    /// `helical`, `universal`).
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Self::Revolute { .. } => "revolute",
            Self::Prismatic { .. } => "prismatic",
            Self::Spherical => "spherical",
            Self::FreeFlyer => "free_flyer",
            Self::Planar => "planar",
            Self::Helical { .. } => "helical",
            Self::Universal { .. } => "universal",
        }
    }

    /// How the algorithms treat this joint.
    #[must_use]
    #[inline(always)]
    pub(crate) fn shape(&self) -> Shape {
        match *self {
            Self::Revolute { axis } => Shape::Revolute(axis),
            Self::Prismatic { axis } => Shape::Prismatic(axis),
            Self::FreeFlyer => Shape::FreeFlyer,
            Self::Spherical | Self::Planar | Self::Helical { .. } | Self::Universal { .. } => {
                Shape::General
            }
        }
    }

    /// The Lie group of the configuration.
    #[must_use]
    #[inline]
    pub(crate) fn group(&self) -> Group {
        match self {
            Self::Revolute { .. }
            | Self::Prismatic { .. }
            | Self::Helical { .. }
            | Self::Universal { .. } => Group::Vector,
            Self::Spherical => Group::SO3,
            Self::FreeFlyer => Group::SE3,
            Self::Planar => Group::SE2,
        }
    }

    /// Where `q` holds a unit quaternion `(x, y, z, w)`, if it does.
    #[must_use]
    #[inline]
    pub fn quaternion_offset(&self) -> Option<usize> {
        match self.group() {
            Group::SO3 => Some(0),
            Group::SE3 => Some(3),
            Group::Vector | Group::SE2 => None,
        }
    }

    /// The joint transform `X_J(q)`: the pose of the child frame in the joint frame.
    /// Quaternions are normalised (the algorithms check them first).
    #[must_use]
    #[inline]
    pub fn transform(&self, q: &[f64]) -> Transform {
        match self {
            Self::Revolute { axis } => {
                let (s, c) = trig::sin_cos(q[0]);
                Transform::from_rotation(rodrigues(axis, s, c))
            }
            Self::Prismatic { axis } => Transform::from_translation(axis * q[0]),
            Self::Spherical => Transform::from_rotation(quat_to_rot(q[0], q[1], q[2], q[3])),
            Self::FreeFlyer => Transform::new(
                quat_to_rot(q[3], q[4], q[5], q[6]),
                Vec3::new(q[0], q[1], q[2]),
            ),
            Self::Planar => {
                let (s, c) = trig::sin_cos(q[2]);
                Transform::new(
                    Mat3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
                    Vec3::new(q[0], q[1], 0.0),
                )
            }
            Self::Helical { axis, pitch } => {
                let (s, c) = trig::sin_cos(q[0]);
                Transform::new(rodrigues(axis, s, c), axis * (pitch * q[0]))
            }
            Self::Universal { axis1, axis2 } => {
                let R1 = rotate_about(&Mat3::identity(), axis1, q[0]);
                Transform::from_rotation(rotate_about(&R1, axis2, q[1]))
            }
        }
    }

    /// `X_T X_J(q)`: the pose of the child frame in the parent frame, given the joint
    /// placement `X_T`; skips the products by zero blocks of [`transform`](Self::transform)
    /// (a revolute joint keeps `X_T`'s translation, a prismatic joint its rotation).
    #[must_use]
    #[inline(always)]
    pub fn placed_transform(&self, placement: &Transform, q: &[f64]) -> Transform {
        match self {
            Self::Revolute { axis } => Transform::new(
                rotate_about(&placement.rotation, axis, q[0]),
                placement.translation,
            ),
            Self::Prismatic { axis } => Transform::new(
                placement.rotation,
                placement.rotation * (axis * q[0]) + placement.translation,
            ),
            Self::Spherical => Transform::new(
                crate::spatial::mat3_mul(&placement.rotation, &self.transform(q).rotation),
                placement.translation,
            ),
            Self::Helical { axis, pitch } => Transform::new(
                rotate_about(&placement.rotation, axis, q[0]),
                placement.rotation * (axis * (pitch * q[0])) + placement.translation,
            ),
            Self::Universal { axis1, axis2 } => {
                let R1 = rotate_about(&placement.rotation, axis1, q[0]);
                Transform::new(rotate_about(&R1, axis2, q[1]), placement.translation)
            }
            Self::FreeFlyer | Self::Planar => *placement * self.transform(q),
        }
    }

    /// Whether the motion subspace `S` is the same at every `q` (in the child frame). When it
    /// is, `c_J = Ṡ q̇ = 0` and [`subspace`](Self::subspace) need not be called again.
    #[must_use]
    #[inline]
    pub fn constant_subspace(&self) -> bool {
        match self {
            Self::Revolute { .. }
            | Self::Prismatic { .. }
            | Self::Spherical
            | Self::FreeFlyer
            | Self::Planar
            | Self::Helical { .. } => true,
            Self::Universal { .. } => false,
        }
    }

    /// The motion subspace `S(q)` (6 x nv), one twist per column, in the child frame: the body
    /// twist of the child relative to the parent is `Σ_k S_k q̇_k`. `S.len()` is `nv`.
    pub fn subspace(&self, q: &[f64], S: &mut [Twist]) {
        let z = Vec3::zeros();
        let e = |k| Vec3::ith(k, 1.0);
        match self {
            Self::Revolute { axis } => S[0] = Twist::new(*axis, z),
            Self::Prismatic { axis } => S[0] = Twist::new(z, *axis),
            Self::Spherical => (0..3).for_each(|k| S[k] = Twist::new(e(k), z)),
            Self::FreeFlyer => (0..3).for_each(|k| {
                S[k] = Twist::new(e(k), z);
                S[k + 3] = Twist::new(z, e(k));
            }),
            Self::Planar => {
                S[0] = Twist::new(z, e(0));
                S[1] = Twist::new(z, e(1));
                S[2] = Twist::new(e(2), z);
            }
            Self::Helical { axis, pitch } => S[0] = Twist::new(*axis, axis * *pitch),
            Self::Universal { axis1, axis2 } => {
                // R₂ᵀ a₁ = exp(-[a₂] q₂) a₁
                let R2t = rotate_about(&Mat3::identity(), axis2, -q[1]);
                S[0] = Twist::new(R2t * axis1, z);
                S[1] = Twist::new(*axis2, z);
            }
        }
    }

    /// The bias acceleration `c_J = Ṡ(q, q̇) q̇` in the child frame (zero when
    /// [`constant_subspace`](Self::constant_subspace)): the part of the child's acceleration
    /// relative to the parent that `S q̈` does not give.
    #[must_use]
    pub fn bias(&self, q: &[f64], v: &[f64]) -> Twist {
        match self {
            Self::Revolute { .. }
            | Self::Prismatic { .. }
            | Self::Spherical
            | Self::FreeFlyer
            | Self::Planar
            | Self::Helical { .. } => Twist::zero(),
            Self::Universal { axis1, axis2 } => {
                // Ṡ₁ = d/dt (R₂ᵀ a₁) = (R₂ᵀ a₁) × a₂ q̇₂, so c_J = Ṡ₁ q̇₁
                let S1 = rotate_about(&Mat3::identity(), axis2, -q[1]) * axis1;
                Twist::new(S1.cross(axis2) * (v[0] * v[1]), Vec3::zeros())
            }
        }
    }

    /// The neutral configuration (zero angles and translations, identity quaternion).
    pub fn neutral(&self, q: &mut [f64]) {
        q.iter_mut().take(self.nq()).for_each(|x| *x = 0.0);
        if let Some(o) = self.quaternion_offset() {
            q[o + 3] = 1.0;
        }
    }

    /// A random configuration: vector coordinates uniform in `[lower, upper]` (or in
    /// `[-π, π]` for angles and `[-1, 1]` m for translations where a bound is infinite),
    /// quaternions uniform on SO(3) (four normal deviates, normalised).
    pub fn random(&self, rng: &mut super::Rng, lower: &[f64], upper: &[f64], q: &mut [f64]) {
        use std::f64::consts::PI;
        let pick = |rng: &mut super::Rng, i: usize, default: f64| {
            let (lo, hi) = (lower[i], upper[i]);
            if lo.is_finite() && hi.is_finite() {
                rng.uniform(lo, hi)
            } else {
                rng.uniform(-default, default)
            }
        };
        // the scale of each coordinate before the quaternion where it has no finite bounds:
        // radians or metres
        let scales: &[f64] = match self {
            Self::Revolute { .. } | Self::Helical { .. } => &[PI],
            Self::Universal { .. } => &[PI, PI],
            Self::Prismatic { .. } => &[1.0],
            Self::Spherical => &[],
            Self::FreeFlyer => &[1.0, 1.0, 1.0],
            Self::Planar => &[1.0, 1.0, PI],
        };
        for (i, &scale) in scales.iter().enumerate() {
            q[i] = pick(rng, i, scale);
        }
        if let Some(o) = self.quaternion_offset() {
            loop {
                let g = [rng.normal(), rng.normal(), rng.normal(), rng.normal()];
                if quat_norm(&g) > 1e-3 {
                    q[o..o + 4].copy_from_slice(&g);
                    break;
                }
            }
            quat_normalize(&mut q[o..o + 4]);
        }
    }

    /// Normalise the quaternion of a spherical or free-flyer joint (sign `w ≥ 0`); other joints'
    /// coordinates are valid for any real value and are left alone.
    pub fn normalize(&self, q: &mut [f64]) {
        if let Some(o) = self.quaternion_offset() {
            quat_normalize(&mut q[o..o + 4]);
        }
    }

    /// The joint with its axis (if any) normalised, or `None` if an axis is zero or not finite,
    /// a pitch not finite, or a universal joint's two axes parallel.
    #[must_use]
    pub fn normalized_axis(&self) -> Option<Self> {
        let unit = |a: &Vec3| {
            let n = a.norm();
            (n.is_finite() && n > 1e-12).then(|| a / n)
        };
        Some(match self {
            Self::Revolute { axis } => Self::Revolute { axis: unit(axis)? },
            Self::Prismatic { axis } => Self::Prismatic { axis: unit(axis)? },
            Self::Helical { axis, pitch } => Self::Helical {
                axis: unit(axis)?,
                pitch: Some(*pitch).filter(|p| p.is_finite())?,
            },
            Self::Universal { axis1, axis2 } => {
                let (a1, a2) = (unit(axis1)?, unit(axis2)?);
                if a1.cross(&a2).norm() < 1e-6 {
                    return None;
                }
                Self::Universal {
                    axis1: a1,
                    axis2: a2,
                }
            }
            Self::Spherical | Self::FreeFlyer | Self::Planar => *self,
        })
    }
}

/// `log(R₀ᵀ R₁)` for two quaternions `(x, y, z, w)`.
pub(crate) fn quat_log_between(q0: &[f64], q1: &[f64]) -> Vec3 {
    let r0 = quat_to_rot(q0[0], q0[1], q0[2], q0[3]);
    let r1 = quat_to_rot(q1[0], q1[1], q1[2], q1[3]);
    so3::log(&(r0.transpose() * r1))
}
