//! The Lie-group variational integrator of one rigid body ([`Integrator::Lgvi`]): Lee, Leok &
//! McClamroch, "Lie group variational integrators for the full body problem" (CMAME 2007), for
//! the rotation about the CoM (free body) or the pivot, with the translation of the CoM by
//! velocity Verlet. With `Π = J ω`, `M` the moment about that point and `F = exp([f])`:
//! `h Π_k + h²/2 M_k = (sin|f|/|f|) J f + ((1 - cos|f|)/|f|²) f × J f` (solved by Newton),
//! `R_{k+1} = R_k F`, `Π_{k+1} = Fᵀ (Π_k + h/2 M_k) + h/2 M_{k+1}`.
//!
//! The pose is updated by right-multiplying with an exponential, `R' = R F`, so the rotation
//! stays orthonormal to round-off with no re-normalisation; a step allocates nothing.

use super::rigid_body::{RigidBody, State, Support, WrenchFn};
use super::BodyError;
#[cfg(doc)]
use super::Integrator;
use crate::mass::RotationalInertia;
use crate::spatial::{skew, so3, Mat3, Transform, Twist, Vec3};

/// Coefficients of the LGVI map `Φ(f) = a J f + b f × J f` and of its Jacobian:
/// `a = sin x / x`, `b = (1 - cos x)/x²`, `a'/x = (x cos x - sin x)/x³`,
/// `b'/x = (x sin x - 2(1 - cos x))/x⁴`, with Taylor series near `x = 0`.
#[inline]
fn lgvi_coefficients(x: f64) -> (f64, f64, f64, f64) {
    let x2 = x * x;
    if x < 1e-2 {
        let x4 = x2 * x2;
        (
            1.0 - x2 / 6.0 + x4 / 120.0,
            0.5 - x2 / 24.0 + x4 / 720.0,
            -1.0 / 3.0 + x2 / 30.0 - x4 / 840.0,
            -1.0 / 12.0 + x2 / 180.0 - x4 / 6720.0,
        )
    } else {
        let (s, c) = x.sin_cos();
        let half = (0.5 * x).sin();
        let b = 2.0 * half * half / x2; // (1 - cos x)/x² without cancellation
        (
            s / x,
            b,
            (x * c - s) / (x2 * x),
            (x * s - 2.0 * (1.0 - c)) / (x2 * x2),
        )
    }
}

/// Solves `Φ(f) = a(|f|) J f + b(|f|) f × J f = rhs` for `f` by Newton's method, starting from
/// `f₀ = J⁻¹ rhs`. The Jacobian is `∇Φ = (a'/x) J f fᵀ + a J + (b'/x)(f × J f) fᵀ
/// + b ([f] J - [J f])` (Lee, Leok & McClamroch 2007).
fn solve_lgvi(j: &RotationalInertia, j_inv: &Mat3, rhs: &Vec3) -> Result<Vec3, BodyError> {
    const MAX_ITER: usize = 30;
    let jm = j.matrix();
    let scale = rhs.norm();
    let mut f = j_inv * rhs;
    let mut residual = f64::INFINITY;
    for _ in 0..MAX_ITER {
        let x = f.norm();
        let (a, b, da, db) = lgvi_coefficients(x);
        let jf = jm * f;
        let fjf = f.cross(&jf);
        let r = jf * a + fjf * b - rhs;
        residual = r.norm();
        if residual <= 4.0 * f64::EPSILON * scale || scale == 0.0 {
            return Ok(f);
        }
        let jac = jf * f.transpose() * da
            + jm * a
            + fjf * f.transpose() * db
            + (skew(&f) * jm - skew(&jf)) * b;
        let Some(delta) = jac.lu().solve(&r) else {
            break;
        };
        f -= delta;
        if delta.norm() <= 1e-15 * x.max(f64::MIN_POSITIVE) {
            return Ok(f);
        }
    }
    Err(BodyError::NoConvergence {
        iterations: MAX_ITER,
        residual,
    })
}

/// The natural variables of the variational integrator, carried from step to step by the
/// simulator so that no round trip `Π → ω → Π` (or body ↔ world velocity) adds a systematic
/// round-off drift: `Π = J ω` (body axes, about the reference point `o`), and the world position
/// and velocity of `o`. The position is summed with Kahan's compensation (`c` holds the
/// low-order bits lost), so a body drifting far keeps its spatial momentum about the world origin
/// to round-off.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Momenta {
    pi: Vec3,
    p_o: Vec3,
    c: Vec3,
    v_o: Vec3,
}

impl Momenta {
    /// The momenta of the state `x`.
    pub(crate) fn of<W: WrenchFn>(body: &RigidBody<W>, x: &State) -> Self {
        let (o, j, _) = body.rotational();
        let w = x.twist.w;
        Self {
            pi: j.mul_vec(&w),
            p_o: x.pose.act_point(&o),
            c: Vec3::zeros(),
            v_o: x.pose.rotation * (x.twist.v + w.cross(&o)),
        }
    }
}

/// One step of the Lie-group variational integrator (see [`Integrator::Lgvi`]) from the state
/// `x` whose momenta are `k`.
pub(crate) fn lgvi_step<W: WrenchFn>(
    body: &RigidBody<W>,
    t: f64,
    x: &State,
    k: &Momenta,
    h: f64,
) -> Result<(State, Momenta), BodyError> {
    let (o, j, inv_j) = body.rotational();
    let free = body.support() == Support::Free;
    let m = body.inertia().mass();
    let r = x.pose.rotation;
    let Momenta { pi, p_o, c, v_o } = *k;
    // Moment about o (body axes) and force (world axes) at the start.
    let f_k = body.wrench(t, x);
    let m_k = f_k.m - o.cross(&f_k.f);
    let force_k = r * f_k.f;
    // Implicit rotation update.
    let f = solve_lgvi(j, inv_j.matrix(), &((pi + m_k * (0.5 * h)) * h))?;
    let big_f = so3::exp(&f);
    let r1 = r * big_f;
    // CoM translation by velocity Verlet; a pivot does not move.
    let (p1, c1, v_pred) = if free {
        // Kahan: p1 = p_o + dp with the rounding error kept in c1.
        let y = v_o * h + force_k * (0.5 * h * h / m) - c;
        let p1 = p_o + y;
        (p1, (p1 - p_o) - y, v_o + force_k * (h / m))
    } else {
        (p_o, c, Vec3::zeros())
    };
    let pose = Transform::new(
        r1,
        if free {
            p1 - r1 * o
        } else {
            x.pose.translation
        },
    );
    let to_state = |pi1: &Vec3, v1: &Vec3| {
        let w1 = inv_j.solve(pi1);
        // v_b = R'ᵀ v_o - ω × o (zero on a pivot)
        let v_b = if free {
            r1.tr_mul(v1) - w1.cross(&o)
        } else {
            Vec3::zeros()
        };
        State::new(pose, Twist::new(w1, v_b))
    };
    // Predicted end state for the wrench at t + h.
    let pi_pred = big_f.tr_mul(&(pi + m_k * h));
    let f_k1 = body.wrench(t + h, &to_state(&pi_pred, &v_pred));
    let m_k1 = f_k1.m - o.cross(&f_k1.f);
    let pi1 = big_f.tr_mul(&(pi + m_k * (0.5 * h))) + m_k1 * (0.5 * h);
    let v1 = if free {
        v_o + (force_k + r1 * f_k1.f) * (0.5 * h / m)
    } else {
        Vec3::zeros()
    };
    Ok((
        to_state(&pi1, &v1),
        Momenta {
            pi: pi1,
            p_o: p1,
            c: c1,
            v_o: v1,
        },
    ))
}
