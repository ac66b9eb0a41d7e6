//! Joint types: one `Copy` enum and one `impl` holding every per-joint formula (joint transform
//! `X_J(q)`, motion subspace `S`, and the Lie-group operations on the joint's configuration).
//!
//! The joint frame {J} is fixed in the parent body at `q = neutral`; the child body frame is {J}
//! moved by `X_J(q)`, the pose of the child frame in {J}. Every joint's motion subspace is
//! constant when expressed in the child frame (Featherstone 2008, §4.4, "S is constant in body
//! coordinates" for these joints), so the algorithms read `S` from the model and never
//! differentiate it: the joint bias acceleration `c_J = Ṡ q̇` is zero for all of them.

use crate::spatial::{so3, Mat3, Transform, Twist, Vec3};

/// A joint type. Axes are unit vectors in the joint frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointType {
    /// Rotation `q` (rad) about `axis` through the joint-frame origin, with limits:
    /// `X_J = (exp([axis] q), 0)`, `S = (axis, 0)`.
    Revolute {
        /// Unit axis in the joint frame.
        axis: Vec3,
    },
    /// A revolute joint without position limits (one angle, no cos/sin pair).
    Continuous {
        /// Unit axis in the joint frame.
        axis: Vec3,
    },
    /// Translation `q` (m) along `axis`: `X_J = (1, axis q)`, `S = (0, axis)`.
    Prismatic {
        /// Unit axis in the joint frame.
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
}

/// Rodrigues' formula `exp([a] q) = c 1 + s [a] + (1 - c) a aᵀ` with `s = sin q`, `c = cos q`
/// (Lynch & Park, Prop. 3.11), for a unit axis `a`.
#[inline]
fn rodrigues(a: &Vec3, s: f64, c: f64) -> Mat3 {
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
    let (s, c) = super::sincos::sin_cos(q);
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
        crate::multibody::algorithms::mat3_mul(r, &rj)
    }
}

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
fn quat_mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
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
fn quat_exp(w: &Vec3) -> [f64; 4] {
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
fn quat_normalize(q: &mut [f64]) {
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

/// SE(2) exponential of the body velocity `(vx, vy, ω)`: the displacement `(dx, dy, dθ)` in the
/// starting frame: `d = [[s/φ, -(1-c)/φ], [(1-c)/φ, s/φ]] (vx, vy)`, `φ = ω`.
#[inline]
fn se2_exp(vx: f64, vy: f64, w: f64) -> (f64, f64) {
    let (a, b) = if w.abs() < 1e-4 {
        (1.0 - w * w / 6.0, 0.5 * w - w * w * w / 24.0)
    } else {
        (w.sin() / w, (1.0 - w.cos()) / w)
    };
    (a * vx - b * vy, b * vx + a * vy)
}

impl JointType {
    /// Number of configuration coordinates `nq`.
    #[must_use]
    #[inline]
    pub fn nq(&self) -> usize {
        match self {
            Self::Revolute { .. } | Self::Continuous { .. } | Self::Prismatic { .. } => 1,
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
            Self::Revolute { .. } | Self::Continuous { .. } | Self::Prismatic { .. } => 1,
            Self::Spherical | Self::Planar => 3,
            Self::FreeFlyer => 6,
        }
    }

    /// A short lower-case name (`revolute`, `continuous`, `prismatic`, `spherical`, `free_flyer`,
    /// `planar`), as printed by the CLI.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Self::Revolute { .. } => "revolute",
            Self::Continuous { .. } => "continuous",
            Self::Prismatic { .. } => "prismatic",
            Self::Spherical => "spherical",
            Self::FreeFlyer => "free_flyer",
            Self::Planar => "planar",
        }
    }

    /// Whether `q` holds a quaternion at offset [`quaternion_offset`](Self::quaternion_offset).
    #[must_use]
    #[inline]
    pub fn quaternion_offset(&self) -> Option<usize> {
        match self {
            Self::Spherical => Some(0),
            Self::FreeFlyer => Some(3),
            _ => None,
        }
    }

    /// The joint transform `X_J(q)`: the pose of the child frame in the joint frame.
    /// Quaternions are normalised (the algorithms check them first).
    #[must_use]
    #[inline]
    pub fn transform(&self, q: &[f64]) -> Transform {
        match self {
            Self::Revolute { axis } | Self::Continuous { axis } => {
                let (s, c) = super::sincos::sin_cos(q[0]);
                let r = rodrigues(axis, s, c);
                Transform::from_rotation(r)
            }
            Self::Prismatic { axis } => Transform::from_translation(axis * q[0]),
            Self::Spherical => Transform::from_rotation(quat_to_rot(q[0], q[1], q[2], q[3])),
            Self::FreeFlyer => Transform::new(
                quat_to_rot(q[3], q[4], q[5], q[6]),
                Vec3::new(q[0], q[1], q[2]),
            ),
            Self::Planar => {
                let (s, c) = super::sincos::sin_cos(q[2]);
                Transform::new(
                    Mat3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
                    Vec3::new(q[0], q[1], 0.0),
                )
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
            Self::Revolute { axis } | Self::Continuous { axis } => Transform::new(
                rotate_about(&placement.rotation, axis, q[0]),
                placement.translation,
            ),
            Self::Spherical => Transform::new(
                crate::multibody::algorithms::mat3_mul(
                    &placement.rotation,
                    &self.transform(q).rotation,
                ),
                placement.translation,
            ),
            Self::Prismatic { axis } => Transform::new(
                placement.rotation,
                placement.rotation * (axis * q[0]) + placement.translation,
            ),
            Self::FreeFlyer | Self::Planar => *placement * self.transform(q),
        }
    }

    /// Column `k` of the motion subspace `S` (6 x nv), in the child frame: the body twist of the
    /// child relative to the parent is `Σ_k S_k q̇_k`.
    #[must_use]
    pub fn motion_subspace(&self, k: usize) -> Twist {
        let z = Vec3::zeros();
        match self {
            Self::Revolute { axis } | Self::Continuous { axis } => Twist::new(*axis, z),
            Self::Prismatic { axis } => Twist::new(z, *axis),
            Self::Spherical => Twist::new(Vec3::ith(k, 1.0), z),
            Self::FreeFlyer => {
                if k < 3 {
                    Twist::new(Vec3::ith(k, 1.0), z)
                } else {
                    Twist::new(z, Vec3::ith(k - 3, 1.0))
                }
            }
            Self::Planar => match k {
                0 => Twist::new(z, Vec3::x()),
                1 => Twist::new(z, Vec3::y()),
                _ => Twist::new(Vec3::z(), z),
            },
        }
    }

    /// The neutral configuration (zero angles and translations, identity quaternion).
    pub fn neutral(&self, q: &mut [f64]) {
        q.iter_mut().take(self.nq()).for_each(|x| *x = 0.0);
        if let Some(o) = self.quaternion_offset() {
            q[o + 3] = 1.0;
        }
    }

    /// `q_out = q ⊕ v dt`: the configuration reached from `q` moving with the constant joint
    /// velocity `v` for `dt`. Vector joints add; rotations compose on the right with the
    /// exponential of the body velocity (`R ← R exp([ω] dt)`, `T ← T exp([V] dt)`, SE(2) for the
    /// planar joint).
    pub fn integrate(&self, q: &[f64], v: &[f64], dt: f64, q_out: &mut [f64]) {
        match self {
            Self::Revolute { .. } | Self::Continuous { .. } | Self::Prismatic { .. } => {
                q_out[0] = q[0] + v[0] * dt;
            }
            Self::Spherical => {
                let w = Vec3::new(v[0], v[1], v[2]) * dt;
                let r = quat_mul([q[0], q[1], q[2], q[3]], quat_exp(&w));
                q_out[..4].copy_from_slice(&r);
                quat_normalize(&mut q_out[..4]);
            }
            Self::FreeFlyer => {
                let t0 = self.transform(q);
                let dv = Twist::new(Vec3::new(v[0], v[1], v[2]), Vec3::new(v[3], v[4], v[5])) * dt;
                let dt_ = Transform::exp(&dv);
                let p = t0.act_point(&dt_.translation);
                let r = quat_mul([q[3], q[4], q[5], q[6]], quat_exp(&dv.w));
                q_out[0] = p.x;
                q_out[1] = p.y;
                q_out[2] = p.z;
                q_out[3..7].copy_from_slice(&r);
                quat_normalize(&mut q_out[3..7]);
            }
            Self::Planar => {
                let (dx, dy) = se2_exp(v[0] * dt, v[1] * dt, v[2] * dt);
                let (s, c) = q[2].sin_cos();
                q_out[0] = q[0] + c * dx - s * dy;
                q_out[1] = q[1] + s * dx + c * dy;
                q_out[2] = q[2] + v[2] * dt;
            }
        }
    }

    /// `v = q1 ⊖ q0`, the velocity with `q0 ⊕ v = q1` (dt = 1): the inverse of
    /// [`integrate`](Self::integrate) (`log(R0ᵀ R1)`, `log(T0⁻¹ T1)` and the SE(2) logarithm).
    pub fn difference(&self, q0: &[f64], q1: &[f64], v: &mut [f64]) {
        match self {
            Self::Revolute { .. } | Self::Continuous { .. } | Self::Prismatic { .. } => {
                v[0] = q1[0] - q0[0];
            }
            Self::Spherical => {
                let r0 = quat_to_rot(q0[0], q0[1], q0[2], q0[3]);
                let r1 = quat_to_rot(q1[0], q1[1], q1[2], q1[3]);
                let w = so3::log(&(r0.transpose() * r1));
                v[..3].copy_from_slice(w.as_slice());
            }
            Self::FreeFlyer => {
                let d = (self.transform(q0).inverse() * self.transform(q1)).log();
                v[..3].copy_from_slice(d.w.as_slice());
                v[3..6].copy_from_slice(d.v.as_slice());
            }
            Self::Planar => {
                let w = q1[2] - q0[2];
                let (s, c) = q0[2].sin_cos();
                let (gx, gy) = (q1[0] - q0[0], q1[1] - q0[1]);
                // displacement in the starting frame, then invert the SE(2) exponential's V(ω)
                let (dx, dy) = (c * gx + s * gy, -s * gx + c * gy);
                let (a, b) = if w.abs() < 1e-4 {
                    (1.0 - w * w / 6.0, 0.5 * w - w * w * w / 24.0)
                } else {
                    (w.sin() / w, (1.0 - w.cos()) / w)
                };
                let det = a * a + b * b;
                v[0] = (a * dx + b * dy) / det;
                v[1] = (-b * dx + a * dy) / det;
                v[2] = w;
            }
        }
    }

    /// A random configuration: vector coordinates uniform in `[lower, upper]` (or in
    /// `[-π, π]` for angles and `[-1, 1]` m for translations where a bound is infinite),
    /// quaternions uniform on SO(3) (four normal deviates, normalised).
    pub fn random(&self, rng: &mut super::Rng, lower: &[f64], upper: &[f64], q: &mut [f64]) {
        let pick = |rng: &mut super::Rng, i: usize, default: f64| {
            let (lo, hi) = (lower[i], upper[i]);
            if lo.is_finite() && hi.is_finite() {
                rng.uniform(lo, hi)
            } else {
                rng.uniform(-default, default)
            }
        };
        match self {
            Self::Revolute { .. } => q[0] = pick(rng, 0, std::f64::consts::PI),
            Self::Continuous { .. } => {
                q[0] = rng.uniform(-std::f64::consts::PI, std::f64::consts::PI)
            }
            Self::Prismatic { .. } => q[0] = pick(rng, 0, 1.0),
            Self::Spherical | Self::FreeFlyer => {
                let o = self.quaternion_offset().unwrap_or(0);
                for (i, qi) in q.iter_mut().enumerate().take(o) {
                    *qi = pick(rng, i, 1.0);
                }
                loop {
                    let g = [rng.normal(), rng.normal(), rng.normal(), rng.normal()];
                    if quat_norm(&g) > 1e-3 {
                        q[o..o + 4].copy_from_slice(&g);
                        break;
                    }
                }
                quat_normalize(&mut q[o..o + 4]);
            }
            Self::Planar => {
                q[0] = pick(rng, 0, 1.0);
                q[1] = pick(rng, 1, 1.0);
                q[2] = pick(rng, 2, std::f64::consts::PI);
            }
        }
    }

    /// Normalise the quaternion of a spherical or free-flyer joint (sign `w ≥ 0`); other joints'
    /// coordinates are valid for any real value and are left alone.
    pub fn normalize(&self, q: &mut [f64]) {
        if let Some(o) = self.quaternion_offset() {
            quat_normalize(&mut q[o..o + 4]);
        }
    }

    /// Whether the axis (if any) is a finite non-zero vector; returns the joint with its axis
    /// normalised.
    #[must_use]
    pub fn normalized_axis(&self) -> Option<Self> {
        let unit = |a: &Vec3| {
            let n = a.norm();
            (n.is_finite() && n > 1e-12).then(|| a / n)
        };
        Some(match self {
            Self::Revolute { axis } => Self::Revolute { axis: unit(axis)? },
            Self::Continuous { axis } => Self::Continuous { axis: unit(axis)? },
            Self::Prismatic { axis } => Self::Prismatic { axis: unit(axis)? },
            other => *other,
        })
    }
}
