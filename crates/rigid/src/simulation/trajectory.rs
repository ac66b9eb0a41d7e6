//! Point-to-point joint trajectories: a straight line in joint space (on each joint's group,
//! `q(t) = q_start ⊕ s(t) Δ`, `Δ = q_end ⊖ q_start`) timed by a quintic or a trapezoidal time
//! scaling `s: [0, T] → [0, 1]` (Lynch & Park, *Modern Robotics*, §9.2). Before `t = 0` the
//! trajectory rests at `q_start`, after `T` at `q_end`. And pose trajectories in SE(3), along a
//! constant screw or a straight line with a decoupled rotation (§9.1.3).

use super::SimulationError;
use crate::error::DimensionError;
use crate::multibody::{check_q, difference, Model};
use crate::spatial::{so3, Transform};

/// How the path parameter `s` goes from 0 to 1 in time `T`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TimeScaling {
    /// Quintic `s(τ) = 10τ³ - 15τ⁴ + 6τ⁵`, `τ = t/T`: zero velocity and acceleration at both
    /// ends (Lynch & Park §9.2.2.1, eq. 9.11 with the six boundary conditions).
    Quintic,
    /// Trapezoidal velocity: constant acceleration `a` for `t_a`, coasting at `v`, constant
    /// deceleration for `t_a`, with `t_a = accel_fraction T`, `v = 1/(T - t_a)`, `a = v/t_a`
    /// (Lynch & Park §9.2.2.2). `accel_fraction` in `(0, ½]`; `½` is the bang-bang profile.
    Trapezoidal {
        /// `t_a / T`.
        accel_fraction: f64,
    },
}

impl std::str::FromStr for TimeScaling {
    type Err = SimulationError;
    /// `quintic`, or `trapezoidal` (accelerating for a quarter of the time at each end).
    fn from_str(s: &str) -> Result<Self, SimulationError> {
        match s {
            "quintic" => Ok(Self::Quintic),
            "trapezoidal" => Ok(Self::Trapezoidal {
                accel_fraction: 0.25,
            }),
            other => Err(SimulationError::UnknownTimeScaling { name: other.into() }),
        }
    }
}

impl TimeScaling {
    /// `(s, ṡ, s̈)` at time `t` for a motion of duration `T`.
    ///
    /// ```
    /// use rigid::simulation::TimeScaling;
    /// let (s, ds, _) = TimeScaling::Trapezoidal { accel_fraction: 0.25 }.eval(1.0, 2.0);
    /// assert!((s - 0.5).abs() < 1e-15 && (ds - 1.0 / 1.5).abs() < 1e-15); // cruising at 1/(T - t_a)
    /// ```
    #[must_use]
    pub fn eval(&self, t: f64, T: f64) -> (f64, f64, f64) {
        if t <= 0.0 {
            return (0.0, 0.0, 0.0);
        }
        if t >= T {
            return (1.0, 0.0, 0.0);
        }
        match *self {
            TimeScaling::Quintic => {
                let u = t / T;
                let (u2, u3) = (u * u, u * u * u);
                (
                    10.0 * u3 - 15.0 * u3 * u + 6.0 * u3 * u2,
                    (30.0 * u2 - 60.0 * u3 + 30.0 * u2 * u2) / T,
                    (60.0 * u - 180.0 * u2 + 120.0 * u3) / (T * T),
                )
            }
            TimeScaling::Trapezoidal { accel_fraction } => {
                let ta = accel_fraction * T;
                let v = 1.0 / (T - ta);
                let a = v / ta;
                if t < ta {
                    (0.5 * a * t * t, a * t, a)
                } else if t <= T - ta {
                    (v * t - 0.5 * v * v / a, v, 0.0)
                } else {
                    let r = T - t;
                    (1.0 - 0.5 * a * r * r, a * r, -a)
                }
            }
        }
    }
}

/// A duration that is positive and finite, a trapezoid's `accel_fraction` in `(0, ½]`.
fn check_timing(duration: f64, scaling: TimeScaling) -> Result<(), SimulationError> {
    if !(duration.is_finite() && duration > 0.0) {
        return Err(SimulationError::Invalid(format!(
            "trajectory duration must be positive and finite, got {duration}"
        )));
    }
    if let TimeScaling::Trapezoidal { accel_fraction: f } = scaling {
        if !(f > 0.0 && f <= 0.5) {
            return Err(SimulationError::Invalid(format!(
                "trapezoid accel_fraction must be in (0, 0.5], got {f}"
            )));
        }
    }
    Ok(())
}

/// A straight-line joint trajectory from `start` to `end` in `duration` seconds.
///
/// ```
/// use rigid::multibody::builtin;
/// use rigid::simulation::{JointTrajectory, TimeScaling};
/// let model = builtin("double_pendulum").unwrap();
/// let traj = JointTrajectory::new(&model, &[0.0, 0.0], &[1.0, -0.5], 2.0, TimeScaling::Quintic)?;
/// let (mut q, mut v, mut a) = ([0.0; 2], [0.0; 2], [0.0; 2]);
/// traj.sample(&model, 1.0, &mut q, &mut v, &mut a);
/// assert!((q[0] - 0.5).abs() < 1e-15 && (v[0] - 0.9375).abs() < 1e-15); // s(½) = ½, ṡ = 15/8 / T
/// # Ok::<(), rigid::simulation::SimulationError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct JointTrajectory {
    start: Vec<f64>,
    delta: Vec<f64>,
    duration: f64,
    scaling: TimeScaling,
}

impl JointTrajectory {
    /// The trajectory from `start` to `end` (configurations, length `nq`) in `duration` s.
    ///
    /// # Errors
    /// Wrong lengths, non-finite or non-unit-quaternion configurations, a duration that is not
    /// positive and finite, or a trapezoid's `accel_fraction` outside `(0, ½]`.
    pub fn new(
        model: &Model,
        start: &[f64],
        end: &[f64],
        duration: f64,
        scaling: TimeScaling,
    ) -> Result<Self, SimulationError> {
        check_q(model, start)?;
        check_q(model, end)?;
        check_timing(duration, scaling)?;
        let mut delta = vec![0.0; model.nv];
        difference(model, start, end, &mut delta)?;
        Ok(Self {
            start: start.to_vec(),
            delta,
            duration,
            scaling,
        })
    }

    /// The duration `T` (s).
    #[must_use]
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// The end configuration.
    #[must_use]
    pub fn end(&self, model: &Model) -> Vec<f64> {
        let mut q = vec![0.0; self.start.len()];
        let (mut v, mut a) = (vec![0.0; self.delta.len()], vec![0.0; self.delta.len()]);
        self.sample(model, self.duration, &mut q, &mut v, &mut a);
        q
    }

    /// The desired configuration, velocity and acceleration at `t`:
    /// `q = start ⊕ s Δ`, `v = ṡ Δ`, `a = s̈ Δ` (a one-parameter subgroup on each joint, whose
    /// body velocity is `ṡ Δ`). No allocation. `model` must be the one the trajectory was made
    /// for (lengths are asserted).
    pub fn sample(&self, model: &Model, t: f64, q: &mut [f64], v: &mut [f64], a: &mut [f64]) {
        assert!(
            DimensionError::check("q", self.start.len(), q.len()).is_ok()
                && v.len() == self.delta.len()
                && a.len() == self.delta.len(),
            "trajectory sampled with buffers of another model"
        );
        let (s, ds, dds) = self.scaling.eval(t, self.duration);
        for j in model.joints() {
            let (iq, iv) = (j.idx_q..j.idx_q + j.nq, j.idx_v..j.idx_v + j.nv);
            j.kind
                .integrate(&self.start[iq.clone()], &self.delta[iv], s, &mut q[iq]);
        }
        for k in 0..self.delta.len() {
            v[k] = ds * self.delta[k];
            a[k] = dds * self.delta[k];
        }
    }
}

/// The path a pose follows from `start` to `end` (Lynch & Park §9.1.3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PosePath {
    /// The constant screw motion `X(s) = X_start exp(log(X_start⁻¹ X_end) s)` (`ScrewTrajectory`):
    /// the origin moves on a helix in general.
    Screw,
    /// The origin on a straight line and the rotation about a constant axis, decoupled:
    /// `p(s) = p_start + s (p_end - p_start)`, `R(s) = R_start exp(log(R_startᵀ R_end) s)`
    /// (`CartesianTrajectory`, eq. 9.7).
    Cartesian,
}

/// A pose trajectory from `start` to `end` in `duration` seconds along a [`PosePath`] timed by a
/// [`TimeScaling`] (Lynch & Park §9.1–9.2; the code library's `ScrewTrajectory` and
/// `CartesianTrajectory` return it sampled at `N` equal steps).
///
/// ```
/// use rigid::simulation::{PosePath, PoseTrajectory, TimeScaling};
/// use rigid::spatial::{Transform, Vec3};
/// let end = Transform::from_translation(Vec3::new(1.0, 2.0, 0.0));
/// let traj = PoseTrajectory::new(Transform::identity(), end, 2.0, TimeScaling::Quintic, PosePath::Cartesian)?;
/// assert!((traj.sample(1.0).translation - Vec3::new(0.5, 1.0, 0.0)).norm() < 1e-15);
/// # Ok::<(), rigid::simulation::SimulationError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PoseTrajectory {
    start: Transform,
    end: Transform,
    duration: f64,
    scaling: TimeScaling,
    path: PosePath,
}

impl PoseTrajectory {
    /// The trajectory from `start` to `end` in `duration` s.
    ///
    /// # Errors
    /// A non-finite pose, a duration that is not positive and finite, or a trapezoid's
    /// `accel_fraction` outside `(0, ½]`.
    pub fn new(
        start: Transform,
        end: Transform,
        duration: f64,
        scaling: TimeScaling,
        path: PosePath,
    ) -> Result<Self, SimulationError> {
        let finite = |t: &Transform| {
            t.rotation
                .iter()
                .chain(t.translation.iter())
                .all(|x| x.is_finite())
        };
        if !(finite(&start) && finite(&end)) {
            return Err(SimulationError::Invalid(
                "trajectory poses must be finite".into(),
            ));
        }
        check_timing(duration, scaling)?;
        Ok(Self {
            start,
            end,
            duration,
            scaling,
            path,
        })
    }

    /// The duration `T` (s).
    #[must_use]
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// `X(s(t))`; `start` before 0 and `end` after `duration`.
    #[must_use]
    pub fn sample(&self, t: f64) -> Transform {
        let (s, _, _) = self.scaling.eval(t, self.duration);
        match self.path {
            PosePath::Screw => {
                self.start * Transform::exp(&((self.start.inverse() * self.end).log() * s))
            }
            PosePath::Cartesian => {
                let (r0, r1) = (self.start.rotation, self.end.rotation);
                let w = so3::log(&(r0.transpose() * r1));
                let p =
                    self.start.translation + (self.end.translation - self.start.translation) * s;
                Transform::new(r0 * so3::exp(&(w * s)), p)
            }
        }
    }

    /// The `n ≥ 2` poses at `t = k T/(n - 1)`, `k = 0 … n-1`, as the code library's
    /// `ScrewTrajectory(Xstart, Xend, Tf, N, method)` returns them.
    #[must_use]
    pub fn samples(&self, n: usize) -> Vec<Transform> {
        let n = n.max(2);
        (0..n)
            .map(|k| self.sample(self.duration * k as f64 / (n - 1) as f64))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::TimeScaling;

    /// Both scalings go from rest at 0 to rest at 1, and `ṡ`, `s̈` are the derivatives of `s`
    /// (central differences).
    #[test]
    fn time_scalings_are_consistent() {
        for sc in [
            TimeScaling::Quintic,
            TimeScaling::Trapezoidal {
                accel_fraction: 0.2,
            },
            TimeScaling::Trapezoidal {
                accel_fraction: 0.5,
            },
        ] {
            let T = 2.0;
            assert_eq!(sc.eval(0.0, T), (0.0, 0.0, 0.0));
            assert!((sc.eval(T, T).0 - 1.0).abs() < 1e-15);
            let h = 1e-6;
            for i in 1..40 {
                let t = T * (i as f64 + 0.37) / 41.0;
                let (s, ds, dds) = sc.eval(t, T);
                let (sp, dsp, _) = sc.eval(t + h, T);
                let (sm, dsm, _) = sc.eval(t - h, T);
                assert!(((sp - sm) / (2.0 * h) - ds).abs() < 1e-6, "{sc:?} ṡ at {t}");
                assert!(
                    ((dsp - dsm) / (2.0 * h) - dds).abs() < 1e-4,
                    "{sc:?} s̈ at {t}"
                );
                assert!((0.0..=1.0).contains(&s));
            }
        }
    }
}
