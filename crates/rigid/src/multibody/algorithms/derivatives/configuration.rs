//! Jacobians of `q ⊕ v dt` and `q₁ ⊖ q₀` in the tangent coordinates of each joint's Lie group
//! (right Jacobians of SO(3), SE(3) and SE(2): Barfoot 2017, "State Estimation for Robotics",
//! §7.1.5 and §7.2.5; Solà, Deray & Atchuthan 2018, "A micro Lie theory for state estimation in
//! robotics"; Pinocchio's `dIntegrate` and `dDifference`).

use crate::error::DimensionError;
use crate::multibody::{check_q, check_v, JointType, Model, MultibodyError};
use crate::spatial::{skew, Mat3, Mat6, Transform, Twist, Vec3};
use nalgebra::DMatrix;

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
/// `exp([ω + δ]) ≈ exp([ω]) exp([J_r δ])`.
fn so3_jr(w: &Vec3) -> Mat3 {
    let [a, b, ..] = coefficients(w.norm_squared());
    let k = skew(w);
    Mat3::identity() - k * a + k * k * b
}

/// `J_r(ω)⁻¹ = 1 + ½[ω] + (1/θ² - cot(θ/2)/(2θ)) [ω]²` (finite for `θ < 2π`).
fn so3_jr_inv(w: &Vec3) -> Mat3 {
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
/// `[[J_r(ω), 0], [Q(-v, -ω), J_r(ω)]]` (`J_r(ξ) = J_l(-ξ)`): `T exp(ξ + δ) ≈ T exp(ξ) exp(J_r δ)`.
fn se3_jr(x: &Twist) -> Mat6 {
    let j = so3_jr(&x.w);
    let q = se3_q(&-x.w, &-x.v);
    blocks(&j, &q)
}

/// `J_r(ξ)⁻¹ = [[J⁻¹, 0], [-J⁻¹ Q J⁻¹, J⁻¹]]` with the blocks of [`se3_jr`].
fn se3_jr_inv(x: &Twist) -> Mat6 {
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

/// The planar joint's tangent `(vx, vy, ω)` is the SE(3) twist `(0, 0, ω, vx, vy, 0)`: SE(2) is
/// a subgroup, so its Jacobians are these rows and columns of the SE(3) ones.
const PLANAR: [usize; 3] = [3, 4, 2];

fn planar_twist(x: &[f64]) -> Twist {
    Twist::new(Vec3::new(0.0, 0.0, x[2]), Vec3::new(x[0], x[1], 0.0))
}

/// Write the joint's block (rows and columns `iv..iv + nv`) of `m` from its group matrix `g`.
fn put(m: &mut DMatrix<f64>, kind: &JointType, iv: usize, g: &Mat6) {
    match kind {
        JointType::Planar => {
            for (r, &gr) in PLANAR.iter().enumerate() {
                for (c, &gc) in PLANAR.iter().enumerate() {
                    m[(iv + r, iv + c)] = g[(gr, gc)];
                }
            }
        }
        _ => {
            let n = kind.nv();
            m.view_mut((iv, iv), (n, n))
                .copy_from(&g.view((0, 0), (n, n)));
        }
    }
}

fn check_square(what: &'static str, model: &Model, m: &DMatrix<f64>) -> Result<(), MultibodyError> {
    DimensionError::check(what, model.nv() * model.nv(), m.nrows() * m.ncols())?;
    DimensionError::check(what, model.nv(), m.nrows())?;
    Ok(())
}

/// The Jacobians of `q ⊕ v dt` ([`integrate`](crate::multibody::integrate)) with respect to `q`
/// (along `q ⊕ δ`) and to `v`, in the tangent coordinates at the result: column k of `d_dq` is
/// `d/dε ((q ⊕ ε e_k) ⊕ v dt) ⊖ (q ⊕ v dt)`. Block diagonal, one block per joint: vector joints
/// `1` and `dt`; a spherical joint `exp([ω dt])ᵀ` and `J_r(ω dt) dt` (SO(3)); a free-flyer
/// `[Ad_{exp(-ξ dt)}]` and `J_r(ξ dt) dt` (SE(3), angular first); a planar joint the same in
/// SE(2). (`T exp(δ) exp(ξ) = T exp(ξ) exp([Ad_{exp(-ξ)}] δ)` and
/// `exp(ξ + δ) ≈ exp(ξ) exp(J_r(ξ) δ)`.) Pinocchio's `dIntegrate` (`ARG0`, `ARG1`), free-flyer
/// blocks permuted.
///
/// # Errors
/// Wrong lengths (of `q`, `v`, or matrices that are not `nv x nv`), non-finite entries or a
/// non-unit quaternion.
///
/// ```
/// use nalgebra::DMatrix;
/// use rigid::multibody::{integrate_jacobians, pendulum};
/// let model = pendulum();
/// let (mut dq, mut dv) = (DMatrix::zeros(1, 1), DMatrix::zeros(1, 1));
/// integrate_jacobians(&model, &[0.3], &[2.0], 0.1, &mut dq, &mut dv)?;
/// assert_eq!((dq[(0, 0)], dv[(0, 0)]), (1.0, 0.1));
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn integrate_jacobians(
    model: &Model,
    q: &[f64],
    v: &[f64],
    dt: f64,
    d_dq: &mut DMatrix<f64>,
    d_dv: &mut DMatrix<f64>,
) -> Result<(), MultibodyError> {
    check_q(model, q)?;
    check_v(model, "v", v)?;
    check_square("d_dq", model, d_dq)?;
    check_square("d_dv", model, d_dv)?;
    if !dt.is_finite() {
        return Err(MultibodyError::NonFinite {
            what: "dt",
            index: 0,
        });
    }
    d_dq.fill(0.0);
    d_dv.fill(0.0);
    for j in model.joints() {
        let (iv, x) = (j.idx_v, &v[j.idx_v..j.idx_v + j.nv]);
        let xi = match j.kind {
            JointType::Revolute { .. }
            | JointType::Continuous { .. }
            | JointType::Prismatic { .. } => {
                d_dq[(iv, iv)] = 1.0;
                d_dv[(iv, iv)] = dt;
                continue;
            }
            JointType::Spherical => Twist::new(Vec3::new(x[0], x[1], x[2]), Vec3::zeros()),
            JointType::FreeFlyer => Twist::from_slice(x),
            JointType::Planar => planar_twist(x),
        } * dt;
        put(d_dq, &j.kind, iv, &Transform::exp(&-xi).adjoint());
        put(d_dv, &j.kind, iv, &(se3_jr(&xi) * dt));
    }
    Ok(())
}

/// The Jacobians of `q₁ ⊖ q₀` ([`difference`](crate::multibody::difference)) with respect to
/// `q₀` and `q₁` (each along `q ⊕ δ`). Block diagonal: vector joints `-1` and `1`; for a
/// rotation or rigid motion with `d = log(T₀⁻¹ T₁)`, `-J_r(-d)⁻¹` and `J_r(d)⁻¹` (SO(3) for a
/// spherical joint, SE(3) angular first for a free-flyer, SE(2) for a planar joint), since
/// `log(exp(d) exp(δ)) ≈ d + J_r(d)⁻¹ δ` and `log(exp(-δ) exp(d)) ≈ d - J_l(d)⁻¹ δ`,
/// `J_l(d) = J_r(-d)`. Pinocchio's `dDifference` (`ARG0`, `ARG1`), free-flyer blocks permuted.
///
/// # Errors
/// Wrong lengths (of `q₀`, `q₁`, or matrices that are not `nv x nv`), non-finite entries or a
/// non-unit quaternion.
///
/// ```
/// use nalgebra::DMatrix;
/// use rigid::multibody::{difference_jacobians, pendulum};
/// let model = pendulum();
/// let (mut d0, mut d1) = (DMatrix::zeros(1, 1), DMatrix::zeros(1, 1));
/// difference_jacobians(&model, &[0.3], &[0.5], &mut d0, &mut d1)?;
/// assert_eq!((d0[(0, 0)], d1[(0, 0)]), (-1.0, 1.0));
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn difference_jacobians(
    model: &Model,
    q0: &[f64],
    q1: &[f64],
    d_dq0: &mut DMatrix<f64>,
    d_dq1: &mut DMatrix<f64>,
) -> Result<(), MultibodyError> {
    check_q(model, q0)?;
    check_q(model, q1)?;
    check_square("d_dq0", model, d_dq0)?;
    check_square("d_dq1", model, d_dq1)?;
    d_dq0.fill(0.0);
    d_dq1.fill(0.0);
    let mut d = [0.0; 6];
    for j in model.joints() {
        let iv = j.idx_v;
        let iq = j.idx_q..j.idx_q + j.nq;
        j.kind.difference(&q0[iq.clone()], &q1[iq], &mut d[..j.nv]);
        let xi = match j.kind {
            JointType::Revolute { .. }
            | JointType::Continuous { .. }
            | JointType::Prismatic { .. } => {
                d_dq0[(iv, iv)] = -1.0;
                d_dq1[(iv, iv)] = 1.0;
                continue;
            }
            JointType::Spherical => Twist::new(Vec3::new(d[0], d[1], d[2]), Vec3::zeros()),
            JointType::FreeFlyer => Twist::from_slice(&d),
            JointType::Planar => planar_twist(&d),
        };
        put(d_dq0, &j.kind, iv, &(-se3_jr_inv(&-xi)));
        put(d_dq1, &j.kind, iv, &se3_jr_inv(&xi));
    }
    Ok(())
}
