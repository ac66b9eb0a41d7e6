//! A mobile manipulator: an arm given by its screw axes on a wheeled base, its kinematics and the
//! task-space feedback that drives its end effector along a reference (Lynch & Park §13.5,
//! §11.3; the capstone project).

use super::{Base, MobileError};
use crate::kinematics::poe::{fkin_body, jacobian_body};
use crate::spatial::{Mat6, Transform, Twist, Vec3};
use nalgebra::{DMatrix, DVector};

/// An arm on a wheeled base: the chassis frame {b} at height `height` above the floor, the arm's
/// base frame {0} at `T_b0` in {b}, the end effector {e} at `M_0e` in {0} at the arm's home, and
/// the arm's screw axes `B_i` in {e} (Lynch & Park §13.5).
///
/// ```
/// use rigid::mobile::MobileManipulator;
/// let youbot = MobileManipulator::youbot();
/// let je = youbot.jacobian(&[0.0, 0.0, 0.2, -1.6, 0.0])?;
/// assert_eq!((je.nrows(), je.ncols()), (6, 9)); // 4 wheels, then 5 arm joints
/// # Ok::<(), rigid::mobile::MobileError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct MobileManipulator {
    /// The wheeled base.
    pub base: Base,
    /// `T_b0`: the arm's base frame in the chassis frame.
    pub T_b0: Transform,
    /// `M_0e`: the end effector in the arm's base frame at `θ = 0`.
    pub M_0e: Transform,
    /// The arm's screw axes in the end-effector frame at home, `B_1 … B_n`.
    pub Blist: Vec<Twist>,
    /// The chassis frame's height above the floor (m): `T_sb = (Rot(z, φ), (x, y, height))`.
    pub height: f64,
}

impl MobileManipulator {
    /// The arm on the base, the chassis frame on the floor (`height = 0`).
    ///
    /// # Errors
    /// [`MobileError::NotFinite`] for a non-finite pose or screw axis.
    pub fn new(
        base: Base,
        T_b0: Transform,
        M_0e: Transform,
        Blist: Vec<Twist>,
    ) -> Result<Self, MobileError> {
        for (what, t) in [("T_b0", &T_b0), ("M_0e", &M_0e)] {
            finite(what, t.rotation.as_slice())?;
            finite(what, t.translation.as_slice())?;
        }
        for b in &Blist {
            finite("Blist", b.to_vector().as_slice())?;
        }
        Ok(Self {
            base,
            T_b0,
            M_0e,
            Blist,
            height: 0.0,
        })
    }

    /// The KUKA youBot of the capstone project: its mecanum base ([`Base::youbot`]), the
    /// chassis frame 0.0963 m up, `T_b0 = (I, (0.1662, 0, 0.0026))`,
    /// `M_0e = (I, (0.033, 0, 0.6546))` and the 5R arm's `B_i`.
    #[must_use]
    pub fn youbot() -> Self {
        let b = |w: [f64; 3], v: [f64; 3]| Twist::new(Vec3::from(w), Vec3::from(v));
        Self {
            base: Base::youbot(),
            T_b0: Transform::from_translation(Vec3::new(0.1662, 0.0, 0.0026)),
            M_0e: Transform::from_translation(Vec3::new(0.033, 0.0, 0.6546)),
            Blist: vec![
                b([0.0, 0.0, 1.0], [0.0, 0.033, 0.0]),
                b([0.0, -1.0, 0.0], [-0.5076, 0.0, 0.0]),
                b([0.0, -1.0, 0.0], [-0.3526, 0.0, 0.0]),
                b([0.0, -1.0, 0.0], [-0.2176, 0.0, 0.0]),
                b([0.0, 0.0, 1.0], [0.0, 0.0, 0.0]),
            ],
            height: 0.0963,
        }
    }

    /// The number of arm joints `n`.
    #[must_use]
    pub fn n_arm(&self) -> usize {
        self.Blist.len()
    }

    /// The number of wheels `m`.
    #[must_use]
    pub fn n_wheels(&self) -> usize {
        self.base.wheels().len()
    }

    /// `T_sb(q)`: the chassis frame for the chassis configuration `q = (φ, x, y)`.
    #[must_use]
    pub fn chassis_pose(&self, q: [f64; 3]) -> Transform {
        Transform::new(
            crate::spatial::so3::from_rpy(0.0, 0.0, q[0]),
            Vec3::new(q[1], q[2], self.height),
        )
    }

    /// `X = T_se = T_sb(q) T_b0 M_0e e^{[B_1]θ_1} ⋯ e^{[B_n]θ_n}`.
    ///
    /// # Errors
    /// [`MobileError::Dimension`] when `theta` is not `n` numbers; [`MobileError::NotFinite`].
    pub fn forward(&self, q: [f64; 3], theta: &[f64]) -> Result<Transform, MobileError> {
        finite("chassis configuration", &q)?;
        finite("theta", theta)?;
        Ok(self.chassis_pose(q) * self.T_b0 * fkin_body(&self.M_0e, &self.Blist, theta)?)
    }

    /// `J_e(θ) = [J_base  J_arm]` (`6 × (m + n)`, Lynch & Park §13.5): the end-effector body twist
    /// `V_e = J_e (u, θ̇)` for wheel speeds `u` and joint speeds `θ̇`, with
    /// `J_base = [Ad_{T_0e⁻¹(θ) T_b0⁻¹}] F6` and `J_arm` the arm's body Jacobian. It does not
    /// depend on the chassis configuration.
    ///
    /// # Errors
    /// As [`MobileManipulator::forward`].
    pub fn jacobian(&self, theta: &[f64]) -> Result<DMatrix<f64>, MobileError> {
        finite("theta", theta)?;
        let t_0e = fkin_body(&self.M_0e, &self.Blist, theta)?;
        let j_base = (t_0e.inverse() * self.T_b0.inverse()).adjoint() * self.base.F6();
        let j_arm = jacobian_body(&self.Blist, theta)?;
        let (m, n) = (self.n_wheels(), self.n_arm());
        let mut je = DMatrix::zeros(6, m + n);
        je.columns_mut(0, m).copy_from(&j_base);
        je.columns_mut(m, n).copy_from(&j_arm);
        Ok(je)
    }
}

/// What [`Feedback::command`] returns.
#[derive(Clone, Debug, PartialEq)]
pub struct Command {
    /// `V`: the commanded end-effector twist in the end-effector frame.
    pub V: Twist,
    /// `(u, θ̇) = J_e† V`: wheel speeds first, then joint speeds (rad/s).
    pub speeds: Vec<f64>,
    /// `X_err`: `[X_err] = log(X⁻¹ X_d)`, the error twist.
    pub X_err: Twist,
}

/// Task-space feedforward plus PI feedback on the end-effector pose (Lynch & Park eq. 11.16 and
/// 13.37): `V = [Ad_{X⁻¹X_d}] V_d + K_p X_err + K_i ∫X_err dt`, with `[V_d] = log(X_d⁻¹ X_d,next)/Δt`.
/// It holds the integral of the error between calls.
///
/// ```
/// use rigid::mobile::{Feedback, MobileManipulator};
/// use rigid::spatial::{Mat6, Transform};
/// let youbot = MobileManipulator::youbot();
/// let theta = [0.0, 0.0, 0.2, -1.6, 0.0];
/// let x = youbot.forward([0.0; 3], &theta)?;
/// let mut fb = Feedback::new(Mat6::identity(), Mat6::zeros())?;
/// // the reference where the end effector is, at rest: nothing to do
/// let c = fb.command(&youbot, &x, &x, &x, 0.01, &theta)?;
/// assert!(c.speeds.iter().all(|s| s.abs() < 1e-12));
/// # Ok::<(), rigid::mobile::MobileError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Feedback {
    /// `K_p` (1/s).
    pub Kp: Mat6,
    /// `K_i` (1/s²).
    pub Ki: Mat6,
    /// `∫X_err dt` so far.
    pub integral: Twist,
    /// Singular values of `J_e` below this are treated as zero in `J_e†` (the capstone's advice
    /// against huge speeds near singularities). Default 1e-4.
    pub tolerance: f64,
    /// Arm joint limits `(low, high)` (rad), one per arm joint: a joint whose next position
    /// `θ + θ̇ Δt` would leave its range (or, outside it, move further out) gets its column of
    /// `J_e` zeroed, and the speeds are solved again (the capstone's `testJointLimits`); a joint
    /// outside its range may move back in. Empty: no limits.
    pub limits: Vec<(f64, f64)>,
}

impl Feedback {
    /// The gains, a zero integral, no joint limits.
    ///
    /// # Errors
    /// [`MobileError::NotFinite`] for a non-finite gain.
    pub fn new(Kp: Mat6, Ki: Mat6) -> Result<Self, MobileError> {
        finite("Kp", Kp.as_slice())?;
        finite("Ki", Ki.as_slice())?;
        Ok(Self {
            Kp,
            Ki,
            integral: Twist::zero(),
            tolerance: 1e-4,
            limits: Vec::new(),
        })
    }

    /// One control step: the commanded twist for the current pose `X`, the reference `X_d` now and
    /// `X_d,next` one step `dt` later, the arm at `theta`; adds `X_err dt` to the integral first.
    ///
    /// # Errors
    /// [`MobileError::NotPositive`] for `dt` or a negative tolerance; wrong lengths of `theta` or
    /// `limits`; limits with `low > high` or NaN ([`MobileError::Limits`]); non-finite input or
    /// gains. Nothing changes (the integral neither) when it fails.
    pub fn command(
        &mut self,
        robot: &MobileManipulator,
        X: &Transform,
        Xd: &Transform,
        Xd_next: &Transform,
        dt: f64,
        theta: &[f64],
    ) -> Result<Command, MobileError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(MobileError::NotPositive {
                what: "dt",
                value: dt,
            });
        }
        for (what, t) in [("X", X), ("Xd", Xd), ("Xd_next", Xd_next)] {
            finite(what, t.rotation.as_slice())?;
            finite(what, t.translation.as_slice())?;
        }
        finite("Kp", self.Kp.as_slice())?;
        finite("Ki", self.Ki.as_slice())?;
        if !(self.tolerance >= 0.0 && self.tolerance.is_finite()) {
            return Err(MobileError::NotPositive {
                what: "pseudo-inverse tolerance",
                value: self.tolerance,
            });
        }
        if !self.limits.is_empty() {
            crate::error::DimensionError::check("joint limits", robot.n_arm(), self.limits.len())?;
        }
        for (joint, &(low, high)) in self.limits.iter().enumerate() {
            if low.is_nan() || high.is_nan() || low > high {
                return Err(MobileError::Limits { joint, low, high });
            }
        }
        // everything checked (J_e checks theta) before the integral moves
        let mut je = robot.jacobian(theta)?;
        let X_err = (X.inverse() * *Xd).log();
        let Vd = (Xd.inverse() * *Xd_next).log() * (1.0 / dt);
        self.integral += X_err * dt;
        let V = (X.inverse() * *Xd).act_twist(&Vd)
            + Twist::from_vector(
                &(self.Kp * X_err.to_vector() + self.Ki * self.integral.to_vector()),
            );
        let m = robot.n_wheels();
        // a joint whose step would take it out of its range, or further out, stops; at most one
        // pass per joint
        let speeds = loop {
            let speeds =
                pinv(&je, self.tolerance) * DVector::from_column_slice(V.to_vector().as_slice());
            let mut blocked = false;
            for (j, &(lo, hi)) in self.limits.iter().enumerate() {
                let s = speeds[m + j];
                let next = theta[j] + s * dt;
                let leaving = (next < lo && s < 0.0) || (next > hi && s > 0.0);
                if leaving && je.column(m + j).iter().any(|&x| x != 0.0) {
                    je.column_mut(m + j).fill(0.0);
                    blocked = true;
                }
            }
            if !blocked {
                break speeds;
            }
        };
        Ok(Command {
            V,
            speeds: speeds.iter().copied().collect(),
            X_err,
        })
    }
}

/// `J†` by the SVD, singular values below `tolerance` dropped.
fn pinv(j: &DMatrix<f64>, tolerance: f64) -> DMatrix<f64> {
    j.clone()
        .svd(true, true)
        .pseudo_inverse(tolerance)
        .expect("the SVD was computed with U and V")
}

pub(super) fn finite(what: &'static str, x: &[f64]) -> Result<(), MobileError> {
    if x.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(MobileError::NotFinite { what })
    }
}
