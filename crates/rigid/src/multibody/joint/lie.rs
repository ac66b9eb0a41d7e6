//! The Lie group of each joint's configuration ([`Group`]): `q ⊕ v dt`, `q₁ ⊖ q₀`, their
//! Jacobians in tangent coordinates, and the differential of the exponential `dexp` with its
//! inverse. Vector joints (`ℝⁿ`) are abelian: `ad = 0`, `dexp = 1`.
//!
//! Sources: right Jacobians of SO(3), SE(3) and SE(2) from Barfoot 2017, "State Estimation for
//! Robotics", §7.1.5 and §7.2.5, and Solà, Deray & Atchuthan 2018, "A micro Lie theory for state
//! estimation in robotics" (Pinocchio's `dIntegrate` and `dDifference`); `dexp` from Iserles,
//! Munthe-Kaas, Nørsett & Zanna, "Lie-group methods", Acta Numerica 2000, §2.3: with
//! `q(t) = q₀ exp(Θ(t))` the body velocity is `v = dexp_{-Θ}(Θ̇)`.

use super::{quat_log_between, Group, JointType};
use crate::spatial::{quat_exp, quat_mul, quat_normalize, quat_to_rot, skew, Mat3, Mat6};
use crate::spatial::{Transform, Twist, Vec3};

impl JointType {
    /// `q_out = q ⊕ v dt`: the configuration reached from `q` moving with the constant joint
    /// velocity `v` for `dt`. Vector joints add; rotations compose on the right with the
    /// exponential of the body velocity (`R ← R exp([ω] dt)`, `T ← T exp([V] dt)`, SE(2) for the
    /// planar joint).
    pub fn integrate(&self, q: &[f64], v: &[f64], dt: f64, q_out: &mut [f64]) {
        match self.group() {
            Group::Vector => {
                for ((o, q), v) in q_out.iter_mut().zip(q).zip(v).take(self.nq()) {
                    *o = q + v * dt;
                }
            }
            Group::SO3 => {
                let w = Vec3::new(v[0], v[1], v[2]) * dt;
                let r = quat_mul([q[0], q[1], q[2], q[3]], quat_exp(&w));
                q_out[..4].copy_from_slice(&r);
                quat_normalize(&mut q_out[..4]);
            }
            Group::SE3 => {
                let t0 = se3(q);
                let dv = Twist::new(Vec3::new(v[0], v[1], v[2]), Vec3::new(v[3], v[4], v[5])) * dt;
                let p = t0.act_point(&Transform::exp(&dv).translation);
                let r = quat_mul([q[3], q[4], q[5], q[6]], quat_exp(&dv.w));
                q_out[..3].copy_from_slice(p.as_slice());
                q_out[3..7].copy_from_slice(&r);
                quat_normalize(&mut q_out[3..7]);
            }
            Group::SE2 => {
                let (dx, dy) = se2_exp(v[0] * dt, v[1] * dt, v[2] * dt);
                let (s, c) = q[2].sin_cos();
                q_out[0] = q[0] + c * dx - s * dy;
                q_out[1] = q[1] + s * dx + c * dy;
                q_out[2] = q[2] + v[2] * dt;
            }
        }
    }

    /// The step of a joint whose velocity is held in world-aligned axes over a step `h` (the
    /// time-stepping scheme's free-flyer, as MuJoCo's free joint; every other joint: `q ⊕ h v`):
    /// the origin moves in a straight line, `p⁺ = p + h R v_b`, the rotation as
    /// [`integrate`](Self::integrate), and the twist `carry` (the velocity after the step, body
    /// axes at `q`) is carried to the new body axes, `V ← ΔRᵀ V` with `ΔR = Rᵀ R⁺`. In body axes
    /// the explicit step would turn `v_b` by `−h ω × v_b`, which lengthens it by `√(1 + h²ω²)`
    /// each step (a ball rolling at 20 rad/s would gain 20 % of its speed a second); see
    /// [`world_aligned_turn`](Self::world_aligned_turn) for the other half.
    pub(crate) fn integrate_world_aligned(
        &self,
        q: &[f64],
        v: &[f64],
        h: f64,
        q_out: &mut [f64],
        carry: &mut [f64],
    ) {
        self.integrate(q, v, h, q_out);
        if self.group() != Group::SE3 {
            return;
        }
        let r0 = quat_to_rot(q[3], q[4], q[5], q[6]);
        let r1 = quat_to_rot(q_out[3], q_out[4], q_out[5], q_out[6]);
        let p = Vec3::new(q[0], q[1], q[2]) + r0 * Vec3::new(v[3], v[4], v[5]) * h;
        q_out[..3].copy_from_slice(p.as_slice());
        let turn = r1.tr_mul(&r0);
        for at in [0, 3] {
            let x = turn * Vec3::new(carry[at], carry[at + 1], carry[at + 2]);
            carry[at..at + 3].copy_from_slice(x.as_slice());
        }
    }

    /// The frame's turning that a body-axes acceleration holds for a joint stepped in
    /// world-aligned axes ([`integrate_world_aligned`](Self::integrate_world_aligned)): for a
    /// free-flyer `h ω × v_b` added to the linear velocity `dv` (the `−ω × v_b` of the body-axes
    /// equations is not a force there); nothing for the others.
    pub(crate) fn world_aligned_turn(&self, v: &[f64], h: f64, dv: &mut [f64]) {
        if self.group() == Group::SE3 {
            let w = Vec3::new(v[0], v[1], v[2]);
            let turn = w.cross(&Vec3::new(v[3], v[4], v[5])) * h;
            for i in 0..3 {
                dv[3 + i] += turn[i];
            }
        }
    }

    /// `v = q1 ⊖ q0`, the velocity with `q0 ⊕ v = q1` (dt = 1): the inverse of
    /// [`integrate`](Self::integrate) (`log(R0ᵀ R1)`, `log(T0⁻¹ T1)` and the SE(2) logarithm).
    pub fn difference(&self, q0: &[f64], q1: &[f64], v: &mut [f64]) {
        match self.group() {
            Group::Vector => {
                for ((v, a), b) in v.iter_mut().zip(q0).zip(q1).take(self.nv()) {
                    *v = b - a;
                }
            }
            Group::SO3 => v[..3].copy_from_slice(quat_log_between(q0, q1).as_slice()),
            Group::SE3 => {
                let d = (se3(q0).inverse() * se3(q1)).log();
                v[..3].copy_from_slice(d.w.as_slice());
                v[3..6].copy_from_slice(d.v.as_slice());
            }
            Group::SE2 => {
                let w = q1[2] - q0[2];
                let (s, c) = q0[2].sin_cos();
                let (gx, gy) = (q1[0] - q0[0], q1[1] - q0[1]);
                // displacement in the starting frame, then invert the SE(2) exponential's V(ω)
                let (dx, dy) = (c * gx + s * gy, -s * gx + c * gy);
                let (a, b) = se2_v(w);
                let det = a * a + b * b;
                v[0] = (a * dx + b * dy) / det;
                v[1] = (-b * dx + a * dy) / det;
                v[2] = w;
            }
        }
    }

    /// The joint's blocks of the Jacobians of `q ⊕ v dt` with respect to `q` (along `q ⊕ δ`) and
    /// to `v`, in the tangent coordinates at the result: vector joints `1` and `dt`; SO(3)
    /// `exp([ω dt])ᵀ` and `J_r(ω dt) dt`; SE(3) `[Ad_{exp(-ξ dt)}]` and `J_r(ξ dt) dt` (angular
    /// first); SE(2) the same rows and columns of SE(3). (`T exp(δ) exp(ξ) =
    /// T exp(ξ) exp([Ad_{exp(-ξ)}] δ)` and `exp(ξ + δ) ≈ exp(ξ) exp(J_r(ξ) δ)`.) Only the top-left
    /// `nv x nv` of each output is written.
    pub(crate) fn integrate_jacobians(&self, v: &[f64], dt: f64, d_dq: &mut Mat6, d_dv: &mut Mat6) {
        let Some(xi) = self.tangent_twist(v) else {
            *d_dq = Mat6::identity();
            *d_dv = Mat6::identity() * dt;
            return;
        };
        let xi = xi * dt;
        *d_dq = self.restrict(&Transform::exp(&-xi).adjoint());
        *d_dv = self.restrict(&(se3_jr(&xi) * dt));
    }

    /// The joint's blocks of the Jacobians of `q₁ ⊖ q₀` with respect to `q₀` and `q₁` (each
    /// along `q ⊕ δ`): vector joints `-1` and `1`; for a rotation or rigid motion with
    /// `d = log(T₀⁻¹ T₁)`, `-J_r(-d)⁻¹` and `J_r(d)⁻¹`, since `log(exp(d) exp(δ)) ≈ d + J_r(d)⁻¹ δ`
    /// and `log(exp(-δ) exp(d)) ≈ d - J_l(d)⁻¹ δ`, `J_l(d) = J_r(-d)`.
    pub(crate) fn difference_jacobians(
        &self,
        q0: &[f64],
        q1: &[f64],
        d_dq0: &mut Mat6,
        d_dq1: &mut Mat6,
    ) {
        let mut d = [0.0; 6];
        self.difference(q0, q1, &mut d[..self.nv()]);
        let Some(xi) = self.tangent_twist(&d) else {
            *d_dq0 = -Mat6::identity();
            *d_dq1 = Mat6::identity();
            return;
        };
        *d_dq0 = self.restrict(&(-se3_jr_inv(&-xi)));
        *d_dq1 = self.restrict(&se3_jr_inv(&xi));
    }

    /// The tangent vector `x` (length `nv`) as an se(3) twist, `None` for a vector joint: SO(3)
    /// `(ω, 0)`, SE(3) itself, SE(2) `(0, 0, ω, v_x, v_y, 0)`.
    fn tangent_twist(&self, x: &[f64]) -> Option<Twist> {
        match self.group() {
            Group::Vector => None,
            Group::SO3 => Some(Twist::new(Vec3::new(x[0], x[1], x[2]), Vec3::zeros())),
            Group::SE3 => Some(Twist::from_slice(&x[..6])),
            Group::SE2 => Some(Twist::new(
                Vec3::new(0.0, 0.0, x[2]),
                Vec3::new(x[0], x[1], 0.0),
            )),
        }
    }

    /// The joint's `nv x nv` block (top-left) of an se(3) matrix: SO(3) and SE(3) are the
    /// leading rows and columns, SE(2) rows and columns `(3, 4, 2)` (a subgroup).
    fn restrict(&self, g: &Mat6) -> Mat6 {
        const SE2: [usize; 3] = [3, 4, 2];
        let mut m = Mat6::zeros();
        match self.group() {
            Group::SE2 => {
                for (r, &gr) in SE2.iter().enumerate() {
                    for (c, &gc) in SE2.iter().enumerate() {
                        m[(r, c)] = g[(gr, gc)];
                    }
                }
            }
            Group::Vector | Group::SO3 | Group::SE3 => {
                let n = self.nv();
                m.view_mut((0, 0), (n, n))
                    .copy_from(&g.view((0, 0), (n, n)));
            }
        }
        m
    }

    /// `out = dexp_x y` or `dexp_xᵀ y`, `dexp_x = Σ_{k≥0} ad_xᵏ / (k + 1)!` (the left Jacobian
    /// of the group's exponential, `J_l(x) = J_r(-x)`), in closed form: SO(3)'s and SE(3)'s right
    /// Jacobians at `-x` (SE(2) the rows and columns of SE(3)'s); the identity for a vector joint.
    pub(crate) fn dexp(&self, x: &[f64], y: &[f64], transpose: bool, out: &mut [f64]) {
        match self.tangent_twist(x) {
            None => out[..self.nv()].copy_from_slice(&y[..self.nv()]),
            Some(xi) => self.apply(&self.restrict(&se3_jr(&-xi)), y, transpose, out),
        }
    }

    /// `out = dexp_x⁻¹ y` (or `dexp_x⁻ᵀ y`): the inverse right Jacobian at `-x` in closed form
    /// ([`so3_jr_inv`] finite for rotations below 2π); the identity for a vector joint.
    pub(crate) fn dexp_inv(&self, x: &[f64], y: &[f64], transpose: bool, out: &mut [f64]) {
        match self.tangent_twist(x) {
            None => out[..self.nv()].copy_from_slice(&y[..self.nv()]),
            Some(xi) => self.apply(&self.restrict(&se3_jr_inv(&-xi)), y, transpose, out),
        }
    }

    /// `out = A y` or `Aᵀ y` for the joint's `nv x nv` block `A` (top-left) of a 6x6.
    fn apply(&self, a: &Mat6, y: &[f64], transpose: bool, out: &mut [f64]) {
        let n = self.nv();
        for (r, o) in out.iter_mut().enumerate().take(n) {
            *o = (0..n)
                .map(|c| if transpose { a[(c, r)] } else { a[(r, c)] } * y[c])
                .sum();
        }
    }
}

/// The pose `(R(quaternion), p)` of a free-flyer configuration `(p, quaternion)`.
fn se3(q: &[f64]) -> Transform {
    Transform::new(
        quat_to_rot(q[3], q[4], q[5], q[6]),
        Vec3::new(q[0], q[1], q[2]),
    )
}

/// `(sin ω / ω, (1 - cos ω) / ω)`, the entries of SE(2)'s `V(ω)` (Taylor series near 0).
fn se2_v(w: f64) -> (f64, f64) {
    if w.abs() < 1e-4 {
        (1.0 - w * w / 6.0, 0.5 * w - w * w * w / 24.0)
    } else {
        (w.sin() / w, (1.0 - w.cos()) / w)
    }
}

/// SE(2) exponential of the body velocity `(vx, vy, ω)`: the displacement `(dx, dy)` in the
/// starting frame, `V(ω) (vx, vy)` with `V = [[s/ω, -(1-c)/ω], [(1-c)/ω, s/ω]]`.
fn se2_exp(vx: f64, vy: f64, w: f64) -> (f64, f64) {
    let (a, b) = se2_v(w);
    (a * vx - b * vy, b * vx + a * vy)
}

/// Below this rotation angle the coefficients of the Jacobians are evaluated by their Taylor
/// series (the closed forms lose digits to cancellation).
const SMALL: f64 = 0.25;

/// `(1 - cos θ)/θ²`, `(θ - sin θ)/θ³`, `(θ² + 2 cos θ - 2)/(2θ⁴)` and
/// `(2θ - 3 sin θ + θ cos θ)/(2θ⁵)` for `θ² = t2`.
fn coefficients(t2: f64) -> [f64; 4] {
    if t2 < SMALL * SMALL {
        let t4 = t2 * t2;
        let t6 = t4 * t2;
        return [
            0.5 - t2 / 24.0 + t4 / 720.0 - t6 / 40320.0,
            1.0 / 6.0 - t2 / 120.0 + t4 / 5040.0 - t6 / 362880.0,
            1.0 / 24.0 - t2 / 720.0 + t4 / 40320.0 - t6 / 3628800.0,
            1.0 / 120.0 - t2 / 2520.0 + t4 / 120960.0 - t6 / 9979200.0,
        ];
    }
    let t = t2.sqrt();
    let (s, c) = t.sin_cos();
    [
        (1.0 - c) / t2,
        (t - s) / (t2 * t),
        (t2 + 2.0 * c - 2.0) / (2.0 * t2 * t2),
        (2.0 * t - 3.0 * s + t * c) / (2.0 * t2 * t2 * t),
    ]
}

/// The right Jacobian of SO(3), `J_r(ω) = 1 - (1 - cos θ)/θ² [ω] + (θ - sin θ)/θ³ [ω]²`:
/// `exp([ω + δ]) ≈ exp([ω]) exp([J_r δ])` (Barfoot 2017, §7.1.5; Pinocchio's `Jexp3`).
///
/// ```
/// use rigid::multibody::{so3_right_jacobian, so3_right_jacobian_inverse};
/// use rigid::spatial::Vec3;
/// let w = Vec3::new(0.3, -1.1, 0.4);
/// let i = so3_right_jacobian(&w) * so3_right_jacobian_inverse(&w);
/// assert!((i - rigid::spatial::Mat3::identity()).norm() < 1e-14);
/// ```
pub fn so3_jr(w: &Vec3) -> Mat3 {
    let [a, b, ..] = coefficients(w.norm_squared());
    let k = skew(w);
    Mat3::identity() - k * a + k * k * b
}

/// `J_r(ω)⁻¹ = 1 + ½[ω] + (1/θ² - cot(θ/2)/(2θ)) [ω]²` (finite for `θ < 2π`): the derivative of
/// `log` in the body frame, `log(R exp([δ])) ≈ log R + J_r(log R)⁻¹ δ` (Pinocchio's `Jlog3`).
pub fn so3_jr_inv(w: &Vec3) -> Mat3 {
    let t2 = w.norm_squared();
    let e = if t2 < SMALL * SMALL {
        1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0 + t2 * t2 * t2 / 1209600.0
    } else {
        let t = t2.sqrt();
        1.0 / t2 - 1.0 / ((0.5 * t).tan() * 2.0 * t)
    };
    let k = skew(w);
    Mat3::identity() + k * 0.5 + k * k * e
}

/// Barfoot's `Q(ρ, φ)`, the lower-left block of the left Jacobian of SE(3) (angular first) for
/// the twist `(φ, ρ)` (Barfoot 2017, eq. 7.86).
fn se3_q(phi: &Vec3, rho: &Vec3) -> Mat3 {
    let [_, c1, c2, c3] = coefficients(phi.norm_squared());
    let (P, R) = (skew(phi), skew(rho));
    let (PR, RP) = (P * R, R * P);
    let PRP = PR * P;
    R * 0.5 + (PR + RP + PRP) * c1 + (P * PR + RP * P - PRP * 3.0) * c2 + (PRP * P + P * PRP) * c3
}

/// The right Jacobian of SE(3) for the twist `ξ = (ω, v)`, angular first:
/// `[[J_r(ω), 0], [Q(-v, -ω), J_r(ω)]]` (`J_r(ξ) = J_l(-ξ)`): `T exp(ξ + δ) ≈ T exp(ξ) exp(J_r δ)`
/// (Barfoot 2017, §7.2.5; Pinocchio's `Jexp6`, linear first).
pub fn se3_jr(x: &Twist) -> Mat6 {
    let j = so3_jr(&x.w);
    let q = se3_q(&-x.w, &-x.v);
    blocks(&j, &q)
}

/// `J_r(ξ)⁻¹ = [[J⁻¹, 0], [-J⁻¹ Q J⁻¹, J⁻¹]]` with the blocks of [`se3_jr`]: the derivative of
/// `log` in the body frame, `log(T exp(δ)) ≈ log T + J_r(log T)⁻¹ δ` (Pinocchio's `Jlog6`,
/// linear first).
pub fn se3_jr_inv(x: &Twist) -> Mat6 {
    let ji = so3_jr_inv(&x.w);
    let q = se3_q(&-x.w, &-x.v);
    blocks(&ji, &(-(ji * q * ji)))
}

/// `[[d, 0], [l, d]]`.
fn blocks(d: &Mat3, l: &Mat3) -> Mat6 {
    let mut m = Mat6::zeros();
    m.fixed_view_mut::<3, 3>(0, 0).copy_from(d);
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(d);
    m.fixed_view_mut::<3, 3>(3, 0).copy_from(l);
    m
}
