//! Constraint kinematics: the frames c1 and c2, the Jacobian `J`, the velocity `J q̇`, the error
//! `e` and the drift `γ`, with Pinocchio's formulas (`contact-info.hxx`: `calc`, `jacobian`;
//! `constrained-dynamics.hxx`: the right-hand side of `constraintDynamics`).
//!
//! Notation: `J_k = (ω_k, v_k)` the spatial (world) Jacobian column of dof k, `p_1`, `p_2` the
//! origins of c1, c2 in the world, `R_1` c1's rotation, `V_c`, `A_c` the body twist and the
//! drift body acceleration (`q̈ = 0`) of a frame c fixed in a body: `V_c = [Ad_{P⁻¹}] V_i`,
//! `A_c = [Ad_{P⁻¹}] A_i` for c = i · P.

use super::workspace::Support;
use super::{ConstraintKind, ConstraintModel, ReferenceFrame};
use crate::spatial::{Transform, Twist, Vec3};
use nalgebra::DMatrix;

/// A constraint's two frames in the world and their relative pose (Pinocchio's `oMc1`, `oMc2`,
/// `c1Mc2`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ConstraintPlacement {
    /// c1 in the world.
    pub oMc1: Transform,
    /// c2 in the world.
    pub oMc2: Transform,
    /// c2 seen from c1, `oMc1⁻¹ oMc2`.
    pub c1Mc2: Transform,
}

impl ConstraintPlacement {
    /// The frames of `c` from the joints' world poses `oMi`.
    pub(crate) fn of(c: &ConstraintModel, oMi: &[Transform]) -> Self {
        let at = |j: Option<crate::multibody::JointId>, P: &Transform| match j {
            Some(i) => oMi[i.0] * *P,
            None => *P,
        };
        let oMc1 = at(c.joint1, &c.placement1);
        let oMc2 = at(c.joint2, &c.placement2);
        Self {
            oMc1,
            oMc2,
            c1Mc2: oMc1.inverse() * oMc2,
        }
    }
}

/// The motion of a frame fixed in a body: body twist and drift body acceleration, in the frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FrameMotion {
    pub V: Twist,
    pub A: Twist,
}

impl FrameMotion {
    /// The frame `P` of a body with body twist `V_i` and drift acceleration `A_i` (`None`: the
    /// world, at rest).
    pub fn of(body: Option<(Twist, Twist)>, P: &Transform) -> Self {
        match body {
            Some((V, A)) => Self {
                V: P.inv_act_twist(&V),
                A: P.inv_act_twist(&A),
            },
            None => Self {
                V: Twist::zero(),
                A: Twist::zero(),
            },
        }
    }

    /// The classical acceleration `v̇ + ω × v` of the frame's origin, in the frame's axes.
    fn classical(&self) -> Vec3 {
        self.A.v + self.V.w.cross(&self.V.v)
    }
}

/// `p(x) = Σ c_k x^k`, `p'(x)`, `p''(x)`.
pub(crate) fn polynomial(c: &[f64; 5], x: f64) -> (f64, f64, f64) {
    let mut p = 0.0;
    let mut dp = 0.0;
    let mut ddp = 0.0;
    for k in (0..5).rev() {
        ddp = ddp * x + 2.0 * dp;
        dp = dp * x + p;
        p = p * x + c[k];
    }
    (p, dp, ddp)
}

/// The joint coordinates a joint-coordinate constraint reads: `(q_1, q̇_1, dof_1)` and the same of
/// joint2 (or `None`).
pub(crate) type JointCoords = ((f64, f64, usize), Option<(f64, f64, usize)>);

/// Writes constraint `c`'s rows of `J` (columns of its support only: the others stay zero) from
/// the spatial Jacobian `Js` (6 x nv, angular rows first).
pub(crate) fn jacobian_rows(
    c: &ConstraintModel,
    pl: &ConstraintPlacement,
    support: &Support,
    Js: &DMatrix<f64>,
    joints: Option<JointCoords>,
    J: &mut DMatrix<f64>,
    row: usize,
) {
    let (p1, p2, R1) = (pl.oMc1.translation, pl.oMc2.translation, &pl.oMc1.rotation);
    let local = c.reference == ReferenceFrame::Body;
    for &(k, on1, on2) in &support.cols {
        let col = Js.column(k);
        let (w, v) = (
            Vec3::new(col[0], col[1], col[2]),
            Vec3::new(col[3], col[4], col[5]),
        );
        match c.kind {
            ConstraintKind::Point => {
                // velocity of p_1 on body 1 minus that of p_2 on body 2 (v + ω × p)
                let mut x = Vec3::zeros();
                if on1 {
                    x += v + w.cross(&p1);
                }
                if on2 {
                    x -= v + w.cross(&p2);
                }
                if local {
                    x = R1.tr_mul(&x);
                }
                for r in 0..3 {
                    J[(row + r, k)] = x[r];
                }
            }
            ConstraintKind::Frame => {
                let s = f64::from(i8::from(on1) - i8::from(on2));
                // the twist J_k at c1's origin: in c1's axes, or in the world's
                let t = if local {
                    pl.oMc1.inv_act_twist(&Twist::new(w, v))
                } else {
                    Twist::new(w, v + w.cross(&p1))
                };
                let x = t.to_vector() * s;
                for r in 0..6 {
                    J[(row + r, k)] = x[r];
                }
            }
            ConstraintKind::JointCoordinate { .. } => J[(row, k)] = 0.0,
        }
    }
    if let (ConstraintKind::JointCoordinate { polycoef }, Some(((_, _, k1), j2))) = (c.kind, joints)
    {
        J[(row, k1)] = 1.0;
        if let Some((q2, _, k2)) = j2 {
            J[(row, k2)] = -polynomial(&polycoef, q2).1;
        }
    }
}

/// Constraint `c`'s error `e`, velocity `J q̇` and drift `γ` (with the Baumgarte terms:
/// `J q̈ + γ = 0` makes `ë = −kp e − kd ė`), written at `row` of `e`, `vel`, `gamma`.
///
/// `γ = acc_1 − acc_2 − (−kp e − kd ė)` with Pinocchio's `acc_1`, `acc_2`:
/// - point: the classical accelerations of p_1 and p_2 (`A.v + V.ω × V.v` of c1 and of c2, the
///   latter rotated by `c1Rc2`), in c1's axes; world-aligned: all rotated by `R_1`;
/// - frame, local: `acc_1 = A_c1 + [ad_{ė}] [Ad_{c1Mc2}] V_c2`, `acc_2 = [Ad_{c1Mc2}] A_c2`;
///   world-aligned: `R_1 (A_c1 − [Ad_{c1Mc2}] A_c2)` without the bracket term;
/// - joint coordinate: `γ = −p''(q_2) q̇_2² + kp e + kd ė`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn error_velocity_drift(
    c: &ConstraintModel,
    pl: &ConstraintPlacement,
    m1: &FrameMotion,
    m2: &FrameMotion,
    joints: Option<JointCoords>,
    row: usize,
    e: &mut [f64],
    vel: &mut [f64],
    gamma: &mut [f64],
) {
    let (kp, kd) = (c.baumgarte.kp, c.baumgarte.kd);
    let R1 = &pl.oMc1.rotation;
    let world = c.reference == ReferenceFrame::WorldAligned;
    let rot = |x: Vec3| if world { R1 * x } else { x };
    match c.kind {
        ConstraintKind::Point => {
            let c1Rc2 = &pl.c1Mc2.rotation;
            let err = -pl.c1Mc2.translation;
            let verr = m1.V.v - c1Rc2 * m2.V.v;
            let acc = m1.classical() - c1Rc2 * m2.classical();
            let g = acc + kp * err + kd * verr;
            for (r, (x, (y, z))) in rot(err)
                .iter()
                .zip(rot(verr).iter().zip(rot(g).iter()))
                .enumerate()
            {
                (e[row + r], vel[row + r], gamma[row + r]) = (*x, *y, *z);
            }
        }
        ConstraintKind::Frame => {
            let V2in1 = pl.c1Mc2.act_twist(&m2.V);
            let err = -pl.c1Mc2.log();
            let verr = m1.V - V2in1;
            let mut acc = m1.A - pl.c1Mc2.act_twist(&m2.A);
            if !world {
                acc += verr.cross(&V2in1);
            }
            let g = acc + err * kp + verr * kd;
            let rot6 = |t: Twist| Twist::new(rot(t.w), rot(t.v)).to_vector();
            for (r, (x, (y, z))) in rot6(err)
                .iter()
                .zip(rot6(verr).iter().zip(rot6(g).iter()))
                .enumerate()
            {
                (e[row + r], vel[row + r], gamma[row + r]) = (*x, *y, *z);
            }
        }
        ConstraintKind::JointCoordinate { polycoef } => {
            let Some(((q1, v1, _), j2)) = joints else {
                return;
            };
            let (q2, v2) = j2.map_or((0.0, 0.0), |(q, v, _)| (q, v));
            let (p, dp, ddp) = if j2.is_some() {
                polynomial(&polycoef, q2)
            } else {
                (polycoef[0], 0.0, 0.0)
            };
            let err = q1 - p;
            let verr = v1 - dp * v2;
            e[row] = err;
            vel[row] = verr;
            gamma[row] = -ddp * v2 * v2 + kp * err + kd * verr;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::polynomial;

    /// `p`, `p'`, `p''` by Horner equal the expanded forms.
    #[test]
    fn polynomial_and_its_derivatives() {
        let c = [0.5, -1.0, 2.0, 0.25, -0.75];
        let x: f64 = 1.3;
        let (p, dp, ddp) = polynomial(&c, x);
        let pe = c[0] + c[1] * x + c[2] * x * x + c[3] * x.powi(3) + c[4] * x.powi(4);
        let dpe = c[1] + 2.0 * c[2] * x + 3.0 * c[3] * x * x + 4.0 * c[4] * x.powi(3);
        let ddpe = 2.0 * c[2] + 6.0 * c[3] * x + 12.0 * c[4] * x * x;
        assert!((p - pe).abs() < 1e-12 && (dp - dpe).abs() < 1e-12 && (ddp - ddpe).abs() < 1e-12);
    }
}
