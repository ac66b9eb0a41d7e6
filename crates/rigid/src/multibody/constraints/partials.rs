//! The partial derivatives that the constrained dynamics' derivatives are made of: of the
//! constraint residual `r = J(q) q̈ + γ(q, q̇)` (or `J(q) w` at the velocity level) and of the
//! generalised constraint force `Q = J(q)ᵀ λ`, with respect to `q` along `q ⊕ δ` and to `q̇`, at
//! fixed `q̈`, `w` and `λ`.
//!
//! Everything is first written in the world (spatial twists `V_b`, `A_b = V̇_b` of the two
//! bodies, spatial Jacobian columns `S_k`), where Carpentier & Mansard (2018, §III) give the
//! derivatives of `V_b` and `A_b` ([`joint_kinematics_derivatives`]); the constraint's own
//! frame then enters through `p_1`, `R_1` and `oMc1`, which move with body 1:
//! `∂p_1/∂q_k = u_k = v_k + ω_k × p_1`, `∂R_1/∂q_k = [ω_k] R_1`, `∂oMc1/∂q_k = [S_k] oMc1` for
//! the dofs k of body 1's chain (zero columns elsewhere).

use super::kinematics::{polynomial, ConstraintPlacement, JointCoords};
use super::{ConstraintKind, ConstraintModel, ReferenceFrame};
use crate::multibody::{
    joint_kinematics_derivatives, se3_right_jacobian_inverse, Data, JointId, Model, MultibodyError,
};
use crate::spatial::{Twist, Vec3, Wrench};
use nalgebra::DMatrix;

/// One end of a constraint: its body's spatial twist `V` and acceleration `A = V̇` at
/// `(q, q̇, q̈)`, its spatial Jacobian `S` (columns of its chain only) and the derivatives
/// `∂V/∂q`, `∂A/∂q`, `∂A/∂q̇` (6 x nv each). All zero for the world.
#[derive(Clone, Debug)]
pub(crate) struct BodyMotion {
    V: Twist,
    A: Twist,
    S: DMatrix<f64>,
    dV: DMatrix<f64>,
    dA_dq: DMatrix<f64>,
    dA_dv: DMatrix<f64>,
}

fn col(m: &DMatrix<f64>, k: usize) -> Twist {
    let c = m.column(k);
    Twist::new(Vec3::new(c[0], c[1], c[2]), Vec3::new(c[3], c[4], c[5]))
}

impl BodyMotion {
    pub fn new(nv: usize) -> Self {
        Self {
            V: Twist::zero(),
            A: Twist::zero(),
            S: DMatrix::zeros(6, nv),
            dV: DMatrix::zeros(6, nv),
            dA_dq: DMatrix::zeros(6, nv),
            dA_dv: DMatrix::zeros(6, nv),
        }
    }

    /// Loads joint `j`'s body at `(q, q̇, q̈)` (the world for `None`).
    pub fn load(
        &mut self,
        model: &Model,
        data: &mut Data,
        (q, v, a): (&[f64], &[f64], &[f64]),
        j: Option<JointId>,
    ) -> Result<(), MultibodyError> {
        let Some(j) = j else {
            self.V = Twist::zero();
            self.A = Twist::zero();
            for m in [&mut self.S, &mut self.dV, &mut self.dA_dq, &mut self.dA_dv] {
                m.fill(0.0);
            }
            return Ok(());
        };
        let d = joint_kinematics_derivatives(model, data, q, v, a, j, ReferenceFrame::Spatial)?;
        self.S.copy_from(d.velocity_dv);
        self.dV.copy_from(d.velocity_dq);
        self.dA_dq.copy_from(d.acceleration_dq);
        self.dA_dv.copy_from(d.acceleration_dv);
        let oMi = data.placements[j.0];
        self.V = oMi.act_twist(&data.velocities[j.0]);
        self.A = oMi.act_twist(&data.accelerations[j.0]);
        Ok(())
    }

    /// A point `p` fixed in the body: `∂p/∂q_k = u_k`, its velocity `ṗ = v + ω × p` and
    /// classical acceleration `p̈ = a + α × p + ω × ṗ`.
    fn point(&self, p: &Vec3) -> (Vec3, Vec3) {
        let pd = self.V.v + self.V.w.cross(p);
        (pd, self.A.v + self.A.w.cross(p) + self.V.w.cross(&pd))
    }

    /// Column k of the derivatives of the point `p` whose velocity is `pd`:
    /// `(u_k, ∂ṗ/∂q_k, ∂p̈/∂q_k, ∂p̈/∂q̇_k)` (`∂ṗ/∂q̇_k = u_k`).
    fn point_col(&self, p: &Vec3, pd: &Vec3, k: usize) -> [Vec3; 4] {
        let (S, dV, dAq, dAv) = (
            col(&self.S, k),
            col(&self.dV, k),
            col(&self.dA_dq, k),
            col(&self.dA_dv, k),
        );
        let (w, alpha) = (self.V.w, self.A.w);
        let u = S.v + S.w.cross(p);
        let dpd_q = dV.v + dV.w.cross(p) + w.cross(&u);
        let dpdd_q = dAq.v + dAq.w.cross(p) + alpha.cross(&u) + dV.w.cross(pd) + w.cross(&dpd_q);
        let dpdd_v = dAv.v + dAv.w.cross(p) + S.w.cross(pd) + w.cross(&u);
        [u, dpd_q, dpdd_q, dpdd_v]
    }
}

/// What the residual is: `J q̈ + γ` with the Baumgarte terms (forward dynamics) or `J w`
/// (impulse dynamics, `w = q̇⁺ + e q̇⁻`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Level {
    Acceleration,
    Velocity,
}

/// Constraint `c`'s rows of `∂r/∂q` and (acceleration level) `∂r/∂q̇`, at `row`, for the
/// columns `cols`, from its two ends `b1`, `b2` loaded at `(q, q̇, q̈)` (or `(q, w, 0)`). The
/// residual, from [the module](super)'s definitions rewritten in the world:
///
/// - point: `r = R_1ᵀ x` (local) or `x` (world-aligned), `x = Δp̈ + kd Δṗ + kp Δp` with
///   `Δ = (·)_1 − (·)_2`; `∂(R_1ᵀ x) = R_1ᵀ (∂x + x × ω_k)`;
/// - frame, local: `r = [Ad_{oMc1}]⁻¹ Z − kp log(c1Mc2)`, `Z = ΔA + kd ΔV + V_1 × V_2`, with
///   `∂([Ad]⁻¹ Z) = [Ad]⁻¹ (∂Z − S_1k × Z)` and `∂log(c1Mc2) = J_r⁻¹ [Ad_{oMc2}]⁻¹ (S_2k − S_1k)`;
/// - frame, world-aligned: `r = X(ΔA + kd ΔV) − kp R_1 log(c1Mc2)` (`R_1` on both halves),
///   `X(Y) = (Y_ω, Y_v + Y_ω × p_1)` the twist at p_1 in world axes;
/// - joint coordinate: `r = q̈_1 − p' q̈_2 − p'' q̇_2² + kp (q_1 − p) + kd (q̇_1 − p' q̇_2)`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn residual_rows(
    c: &ConstraintModel,
    pl: &ConstraintPlacement,
    (b1, b2): (&BodyMotion, &BodyMotion),
    joints: Option<JointCoords>,
    acc: (&[f64], Level),
    cols: &[(usize, bool, bool)],
    row: usize,
    (dq, dv): (&mut DMatrix<f64>, &mut DMatrix<f64>),
) {
    let (a, level) = acc;
    let accel = level == Level::Acceleration;
    let (kp, kd) = if accel {
        (c.baumgarte.kp, c.baumgarte.kd)
    } else {
        (0.0, 0.0)
    };
    let local = c.reference == ReferenceFrame::Body;
    let (p1, p2, R1) = (pl.oMc1.translation, pl.oMc2.translation, pl.oMc1.rotation);
    let put = |m: &mut DMatrix<f64>, k: usize, x: &[f64]| {
        for (r, x) in x.iter().enumerate() {
            m[(row + r, k)] = *x;
        }
    };
    match c.kind {
        ConstraintKind::Point => {
            let ((pd1, pdd1), (pd2, pdd2)) = (b1.point(&p1), b2.point(&p2));
            let x = if accel {
                (pdd1 - pdd2) + (pd1 - pd2) * kd + (p1 - p2) * kp
            } else {
                pd1 - pd2
            };
            for &(k, _, _) in cols {
                let ([u1, dpd1, dpdd1, dv1], [u2, dpd2, dpdd2, dv2]) =
                    (b1.point_col(&p1, &pd1, k), b2.point_col(&p2, &pd2, k));
                let (mut xq, xv) = if accel {
                    (
                        (dpdd1 - dpdd2) + (dpd1 - dpd2) * kd + (u1 - u2) * kp,
                        (dv1 - dv2) + (u1 - u2) * kd,
                    )
                } else {
                    (dpd1 - dpd2, u1 - u2)
                };
                let (rq, rv) = if local {
                    xq += x.cross(&col(&b1.S, k).w);
                    (R1.tr_mul(&xq), R1.tr_mul(&xv))
                } else {
                    (xq, xv)
                };
                put(dq, k, rq.as_slice());
                if accel {
                    put(dv, k, rv.as_slice());
                }
            }
        }
        ConstraintKind::Frame => {
            let (V1, V2) = (b1.V, b2.V);
            let dV = V1 - V2;
            let Y = if accel { (b1.A - b2.A) + dV * kd } else { dV };
            let log = pl.c1Mc2.log();
            let jlog = se3_right_jacobian_inverse(&log);
            for &(k, _, _) in cols {
                let (S1, S2) = (col(&b1.S, k), col(&b2.S, k));
                let ddV = col(&b1.dV, k) - col(&b2.dV, k);
                let (mut Yq, Yv) = if accel {
                    (
                        (col(&b1.dA_dq, k) - col(&b2.dA_dq, k)) + ddV * kd,
                        (col(&b1.dA_dv, k) - col(&b2.dA_dv, k)) + (S1 - S2) * kd,
                    )
                } else {
                    (ddV, S1 - S2)
                };
                // ∂log(c1Mc2)/∂q_k
                let dlog =
                    Twist::from_vector(&(jlog * pl.oMc2.inv_act_twist(&(S2 - S1)).to_vector()));
                let (rq, rv) = if local {
                    let (mut Z, mut Zv) = (Y, Yv);
                    if accel {
                        Z += V1.cross(&V2);
                        Yq += col(&b1.dV, k).cross(&V2) + V1.cross(&col(&b2.dV, k));
                        Zv += S1.cross(&V2) + V1.cross(&S2);
                    }
                    let rq = pl.oMc1.inv_act_twist(&(Yq - S1.cross(&Z))) - dlog * kp;
                    (rq, pl.oMc1.inv_act_twist(&Zv))
                } else {
                    let X = |t: &Twist| Twist::new(t.w, t.v + t.w.cross(&p1));
                    let u1 = S1.v + S1.w.cross(&p1);
                    let mut rq = X(&Yq);
                    rq.v += Y.w.cross(&u1);
                    // ∂(R_1 ℓ) = ω_k × R_1 ℓ + R_1 ∂ℓ, on both halves
                    let turn = |l: &Vec3, dl: &Vec3| S1.w.cross(&(R1 * l)) + R1 * dl;
                    rq.w -= turn(&log.w, &dlog.w) * kp;
                    rq.v -= turn(&log.v, &dlog.v) * kp;
                    (rq, X(&Yv))
                };
                put(dq, k, rq.to_vector().as_slice());
                if accel {
                    put(dv, k, rv.to_vector().as_slice());
                }
            }
        }
        ConstraintKind::JointCoordinate { polycoef } => {
            // the other columns of the row stay zero
            let Some(((_, _, k1), j2)) = joints else {
                return;
            };
            if accel {
                dq[(row, k1)] = kp;
                dv[(row, k1)] = kd;
            }
            if let Some((q2, v2, k2)) = j2 {
                let (_, dp, ddp) = polynomial(&polycoef, q2);
                let dddp = 6.0 * polycoef[3] + 24.0 * polycoef[4] * q2;
                if accel {
                    dq[(row, k2)] = -ddp * a[k2] - dddp * v2 * v2 - kp * dp - kd * ddp * v2;
                    dv[(row, k2)] = -2.0 * ddp * v2 - kd * dp;
                } else {
                    // here v2 is w's entry
                    dq[(row, k2)] = -ddp * v2;
                }
            }
        }
    }
}

/// Adds `∂(J(q)ᵀ λ_c)/∂q` of constraint `c` (its rows `lambda`) to `dQ` (nv x nv). With
/// `F_b` the world wrench the constraint puts on body b and `Q_k = Σ_b S_kᵀ F_b` over the dofs
/// of b's chain: `∂Q_k/∂q_j = Σ_b S_kᵀ ∂F_b/∂q_j + [j ⪯ k] (S_j × S_k)ᵀ F_b`
/// (`∂S_k/∂q_j = S_j × S_k` for j on k's chain up to k's own joint; Carpentier & Mansard 2018,
/// §III). The wrenches:
///
/// - point: the force `f` (`R_1 λ` local, `λ` world-aligned) at p_1 on body 1 and `−f` at p_2 on
///   body 2: `F_b = ±(p_b × f, f)`, `∂F_b = ±(u_bj × f + p_b × ∂f, ∂f)`, `∂f = ω_1j × f` (local)
///   or 0;
/// - frame: `F` on body 1 and `−F` on body 2, both about p_1: fixed in c1 (local,
///   `∂F = S_1j ×* F`) or with world axes at p_1 (world-aligned, `∂F = (u_1j × f, 0)`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn force_partials(
    model: &Model,
    c: &ConstraintModel,
    pl: &ConstraintPlacement,
    (b1, b2): (&BodyMotion, &BodyMotion),
    joints: Option<JointCoords>,
    lambda: &[f64],
    cols: &[(usize, bool, bool)],
    dQ: &mut DMatrix<f64>,
) {
    let local = c.reference == ReferenceFrame::Body;
    let (p1, p2, R1) = (pl.oMc1.translation, pl.oMc2.translation, pl.oMc1.rotation);
    // F_1, F_2, and the point force f of a point constraint
    let (F1, F2, point) = match c.kind {
        ConstraintKind::Point => {
            let l = Vec3::new(lambda[0], lambda[1], lambda[2]);
            let f = if local { R1 * l } else { l };
            let F1 = Wrench::new(p1.cross(&f), f);
            (F1, -Wrench::new(p2.cross(&f), f), Some(f))
        }
        ConstraintKind::Frame => {
            let w = Wrench::from_slice(lambda);
            let F1 = if local {
                pl.oMc1.act_wrench(&w)
            } else {
                Wrench::new(w.m + p1.cross(&w.f), w.f)
            };
            (F1, -F1, None)
        }
        ConstraintKind::JointCoordinate { polycoef } => {
            if let Some((_, Some((q2, _, k2)))) = joints {
                dQ[(k2, k2)] -= polynomial(&polycoef, q2).2 * lambda[0];
            }
            return;
        }
    };
    let ends = [(b1, F1, p1, 1.0), (b2, F2, p2, -1.0)];
    for &(j, _, _) in cols {
        let S1j = col(&b1.S, j);
        // ∂F_1/∂q_j of a frame constraint (∂F_2 = −∂F_1); zero off body 1's chain
        let G = if local {
            -S1j.ad_transpose(&F1)
        } else {
            Wrench::new((S1j.v + S1j.w.cross(&p1)).cross(&F1.f), Vec3::zeros())
        };
        for (b, (body, Fb, p, s)) in ends.iter().enumerate() {
            let Sbj = col(&body.S, j);
            let Gb = match point {
                Some(f) => {
                    let u = Sbj.v + Sbj.w.cross(p);
                    let df = if local {
                        S1j.w.cross(&f)
                    } else {
                        Vec3::zeros()
                    };
                    Wrench::new(u.cross(&f) + p.cross(&df), df) * *s
                }
                None => G * *s,
            };
            for &(k, on1, on2) in cols {
                if !(if b == 0 { on1 } else { on2 }) {
                    continue;
                }
                let Sk = col(&body.S, k);
                let mut t = Sk.dot(&Gb);
                if j <= k || model.dof_joint(j) == model.dof_joint(k) {
                    t += Sbj.cross(&Sk).dot(Fb);
                }
                dQ[(k, j)] += t;
            }
        }
    }
}
