//! Control laws `τ = u(t, q, v)`: a closure, or a built-in [`Controller`] (none, gravity
//! compensation, joint PD to a target, computed torque along a [`JointTrajectory`]), named by a
//! [`ControlKind`].

use super::{JointTrajectory, SimulationError, TimeScaling};
use crate::error::DimensionError;
use crate::multibody::{
    check_q, crba, difference, gravity_torques, rnea, Data, Model, MultibodyError,
};
use std::fmt;
use std::str::FromStr;

/// A control law `τ = u(t, q, v)`, evaluated by the integrators at every stage (so it should be
/// a function of its arguments: the RK4 stages are not in time order). Implemented by
/// closures `FnMut(t, q, v, τ)` and by [`Controller`].
pub trait Control {
    /// Write the joint torques (length `nv`) for time `t` and state `(q, v)` into `tau`.
    ///
    /// # Errors
    /// An algorithm's error (a bad state).
    fn torque(
        &mut self,
        model: &Model,
        t: f64,
        q: &[f64],
        v: &[f64],
        tau: &mut [f64],
    ) -> Result<(), MultibodyError>;

    /// The joint-space stiffness and damping `(K_p, K_d)`, per dof, of a PD part of this law
    /// (`τ = … + K_p (q* ⊖ q) − K_d v`), which the contact time stepper integrates implicitly;
    /// `None` (the default) when there is none.
    fn pd_gains(&self) -> Option<(&[f64], &[f64])> {
        None
    }

    /// Whether the torque depends on neither `q` nor `v` (an open-loop law): what
    /// [`Simulator::step_derivatives`](super::Simulator::step_derivatives) needs, as it holds
    /// the torque as an input. `false` (the default) when unknown.
    fn open_loop(&self) -> bool {
        false
    }
}

impl<F: FnMut(f64, &[f64], &[f64], &mut [f64])> Control for F {
    fn torque(
        &mut self,
        _model: &Model,
        t: f64,
        q: &[f64],
        v: &[f64],
        tau: &mut [f64],
    ) -> Result<(), MultibodyError> {
        self(t, q, v, tau);
        Ok(())
    }
}

/// An open-loop torque `τ(t, q, v) = u` (length `nv`), held until changed: the input of
/// [`Simulator::step_derivatives`](super::Simulator::step_derivatives) and of a step-by-step
/// loop (`sim.control_mut().0 = u`).
#[derive(Clone, Debug, PartialEq)]
pub struct OpenLoop(pub Vec<f64>);

impl Control for OpenLoop {
    fn torque(
        &mut self,
        model: &Model,
        _t: f64,
        _q: &[f64],
        _v: &[f64],
        tau: &mut [f64],
    ) -> Result<(), MultibodyError> {
        crate::error::DimensionError::check("torque", model.nv, self.0.len())?;
        if let Some(index) = self.0.iter().position(|x| !x.is_finite()) {
            return Err(MultibodyError::NonFinite {
                what: "torque",
                index,
            });
        }
        tau.copy_from_slice(&self.0);
        Ok(())
    }

    fn open_loop(&self) -> bool {
        true
    }
}

/// The built-in control laws.
#[derive(Clone, Debug, PartialEq)]
pub enum ControlLaw {
    /// `τ = 0`.
    None,
    /// `τ = g(q)`: the generalised gravity (RNEA with `q̇ = q̈ = 0`); a robot at rest stays at
    /// rest.
    GravityCompensation,
    /// Joint PD to a target with gravity compensation (Lynch & Park §11.4.1, "PD control with
    /// gravity compensation"): `τ = g(q) + K_p (q_target ⊖ q) - K_d v`, gains per degree of
    /// freedom (N·m/rad and N·m·s/rad).
    Pd {
        /// Target configuration (length `nq`).
        target: Vec<f64>,
        /// `K_p` per dof.
        kp: Vec<f64>,
        /// `K_d` per dof.
        kd: Vec<f64>,
    },
    /// Standing on contacts ([`ControlLaw::stance`], [`ControlLaw::standing`]): joint PD to a
    /// stance with the torques that hold it there, `τ = τ_ff + K_p (q_target ⊖ q) − K_d v`, zero
    /// on a free-flyer's dofs (no actuator moves a floating base). `τ_ff` is PD with gravity
    /// compensation's `g(q)` for a robot on the ground: the least-norm torques that, with the
    /// contact forces, hold the stance at rest (contact inverse dynamics at the target).
    Stance {
        /// Target configuration (length `nq`).
        target: Vec<f64>,
        /// `K_p` per dof (0 on a free-flyer's).
        kp: Vec<f64>,
        /// `K_d` per dof (0 on a free-flyer's).
        kd: Vec<f64>,
        /// `τ_ff` per dof (0 on a free-flyer's).
        feedforward: Vec<f64>,
    },
    /// Computed torque (Lynch & Park §11.4.1, eq. 11.35): `τ = M(q) (q̈_d + K_p e + K_d ė) +
    /// c(q, v) + g(q)` with `e = q_d ⊖ q`, `ė = v_d - v`, computed as one RNEA; gains in s⁻²
    /// and s⁻¹. With the exact model the error obeys `ë + K_d ė + K_p e = 0`. The model is the
    /// rigid-body one: joint damping and friction in the simulation, if on, are not compensated
    /// and show as tracking error.
    ComputedTorque {
        /// The reference `(q_d, v_d, q̈_d)(t)`.
        trajectory: JointTrajectory,
        /// `K_p` (s⁻²).
        kp: f64,
        /// `K_d` (s⁻¹).
        kd: f64,
    },
}

/// The built-in control laws by name, as `rigid simulate --controller` and Python's
/// `rigid.simulate(controller=...)` take them: `none`, `gravity`, `pd` and `track` (see
/// [`ControlLaw::builtin`] for the law and gains each stands for).
///
/// ```
/// use rigid::simulation::{ControlKind, SimulationError};
/// assert_eq!("pd".parse::<ControlKind>()?, ControlKind::Pd);
/// assert_eq!(ControlKind::Track.to_string(), "track");
/// assert!(matches!("fly".parse::<ControlKind>(), Err(SimulationError::UnknownController { .. })));
/// # Ok::<(), SimulationError>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ControlKind {
    /// `none`: [`ControlLaw::None`].
    #[default]
    None,
    /// `gravity`: [`ControlLaw::GravityCompensation`].
    Gravity,
    /// `pd`: [`ControlLaw::Pd`] to a target.
    Pd,
    /// `track`: [`ControlLaw::ComputedTorque`] along a motion to a target.
    Track,
}

impl ControlKind {
    /// Every kind, in the order of the command line's help.
    pub const ALL: [ControlKind; 4] = [Self::None, Self::Gravity, Self::Pd, Self::Track];

    /// The name on the command line and in Python: `none`, `gravity`, `pd`, `track`.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Gravity => "gravity",
            Self::Pd => "pd",
            Self::Track => "track",
        }
    }

    /// Whether the law needs a target configuration (`pd` and `track`).
    #[must_use]
    pub fn needs_target(&self) -> bool {
        matches!(self, Self::Pd | Self::Track)
    }
}

impl fmt::Display for ControlKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ControlKind {
    type Err = SimulationError;
    fn from_str(s: &str) -> Result<Self, SimulationError> {
        Self::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| SimulationError::UnknownController { name: s.into() })
    }
}

impl ControlLaw {
    /// The built-in law `kind`, with the gains `rigid simulate` and Python's `rigid.simulate`
    /// use: `none`; `gravity` (compensation); `pd`, joint PD with gravity compensation to
    /// `target`, every joint alone at 2 Hz and critically damped ([`ControlLaw::pd`] with
    /// `ω = 4π`, `ζ = 1`); `track`, computed torque along a straight joint-space motion from
    /// `q0` to `target` in `move_time` seconds with the time scaling `scaling`, error dynamics
    /// `ë + 20 ė + 100 e = 0` (critically damped at 10 rad/s).
    ///
    /// ```
    /// use rigid::multibody::builtin;
    /// use rigid::simulation::{ControlKind, ControlLaw, TimeScaling};
    /// let model = builtin("pendulum").unwrap();
    /// let law = ControlLaw::builtin(&model, ControlKind::Track, &[0.0], Some(&[1.0]), 2.0, TimeScaling::Quintic)?;
    /// assert!(matches!(law, ControlLaw::ComputedTorque { kp, .. } if kp == 100.0));
    /// # Ok::<(), rigid::simulation::SimulationError>(())
    /// ```
    ///
    /// # Errors
    /// [`SimulationError::MissingTarget`] for `pd` or `track` without a target; a bad target or
    /// start.
    pub fn builtin(
        model: &Model,
        kind: ControlKind,
        q0: &[f64],
        target: Option<&[f64]>,
        move_time: f64,
        scaling: TimeScaling,
    ) -> Result<Self, SimulationError> {
        let target = || {
            target.ok_or(SimulationError::MissingTarget {
                controller: kind,
                nq: model.nq,
            })
        };
        match kind {
            ControlKind::None => Ok(Self::None),
            ControlKind::Gravity => Ok(Self::GravityCompensation),
            ControlKind::Pd => Self::pd(model, target()?, 4.0 * std::f64::consts::PI, 1.0),
            ControlKind::Track => Ok(Self::ComputedTorque {
                trajectory: JointTrajectory::new(model, q0, target()?, move_time, scaling)?,
                kp: 100.0,
                kd: 20.0,
            }),
        }
    }

    /// PD gains that give every joint, taken alone at `target`, the natural frequency `ω`
    /// (rad/s) and damping ratio `ζ`: `K_p,k = ω² M_kk`, `K_d,k = 2ζω M_kk` with `M_kk` the
    /// diagonal of the mass matrix at the target (so that light wrist joints get soft gains and a
    /// fixed step stays stable).
    ///
    /// ```
    /// use rigid::multibody::builtin;
    /// use rigid::simulation::ControlLaw;
    /// let model = builtin("pendulum").unwrap(); // M = 1/3 kg·m²
    /// let ControlLaw::Pd { kp, kd, .. } = ControlLaw::pd(&model, &[0.0], 10.0, 1.0)? else { panic!() };
    /// assert!((kp[0] - 100.0 / 3.0).abs() < 1e-12 && (kd[0] - 20.0 / 3.0).abs() < 1e-12);
    /// # Ok::<(), rigid::simulation::SimulationError>(())
    /// ```
    ///
    /// # Errors
    /// A bad target.
    pub fn pd(
        model: &Model,
        target: &[f64],
        omega: f64,
        zeta: f64,
    ) -> Result<Self, SimulationError> {
        let mut data = Data::new(model);
        let m = crba(model, &mut data, target)?;
        let d: Vec<f64> = (0..model.nv).map(|k| m[(k, k)]).collect();
        Ok(ControlLaw::Pd {
            target: target.to_vec(),
            kp: d.iter().map(|m| omega * omega * m).collect(),
            kd: d.iter().map(|m| 2.0 * zeta * omega * m).collect(),
        })
    }
}

/// A built-in control law with its workspace (allocated once).
///
/// ```
/// use rigid::multibody::builtin;
/// use rigid::simulation::{Control, ControlLaw, Controller};
/// let model = builtin("double_pendulum").unwrap();
/// let mut c = Controller::new(&model, ControlLaw::GravityCompensation)?;
/// let mut tau = [0.0; 2];
/// c.torque(&model, 0.0, &[1.0, 0.0], &[0.0, 0.0], &mut tau)?;
/// assert!(tau[0] > 0.0); // holds the arm up against gravity
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct Controller {
    law: ControlLaw,
    data: Data,
    qd: Vec<f64>,
    vd: Vec<f64>,
    ad: Vec<f64>,
    e: Vec<f64>,
}

impl Controller {
    /// The controller `law` for `model`.
    ///
    /// # Errors
    /// Gains or a target of the wrong length, a non-finite gain, a bad target configuration.
    pub fn new(model: &Model, law: ControlLaw) -> Result<Self, SimulationError> {
        match &law {
            ControlLaw::Pd { target, kp, kd } | ControlLaw::Stance { target, kp, kd, .. } => {
                check_q(model, target)?;
                DimensionError::check("kp", model.nv, kp.len()).map_err(MultibodyError::from)?;
                DimensionError::check("kd", model.nv, kd.len()).map_err(MultibodyError::from)?;
                if kp.iter().chain(kd).any(|k| !k.is_finite()) {
                    return Err(SimulationError::Invalid("PD gains must be finite".into()));
                }
                if let ControlLaw::Stance { feedforward, .. } = &law {
                    DimensionError::check("feedforward", model.nv, feedforward.len())
                        .map_err(MultibodyError::from)?;
                }
            }
            ControlLaw::ComputedTorque { trajectory, kp, kd } => {
                if trajectory.end(model).len() != model.nq {
                    return Err(SimulationError::Invalid(
                        "the trajectory was made for another model".into(),
                    ));
                }
                if !(kp.is_finite() && kd.is_finite()) {
                    return Err(SimulationError::Invalid("gains must be finite".into()));
                }
            }
            ControlLaw::None | ControlLaw::GravityCompensation => {}
        }
        Ok(Self {
            law,
            data: Data::new(model),
            qd: vec![0.0; model.nq],
            vd: vec![0.0; model.nv],
            ad: vec![0.0; model.nv],
            e: vec![0.0; model.nv],
        })
    }

    /// The control law.
    #[must_use]
    pub fn law(&self) -> &ControlLaw {
        &self.law
    }

    /// `τ = 0`.
    #[must_use]
    pub fn none(model: &Model) -> Self {
        Self::new(model, ControlLaw::None).expect("no parameters to check")
    }

    /// The reference `(q_d, v_d)` at `t` of a computed-torque controller, or the PD target
    /// (with `v_d = 0`); `None` for the others.
    #[must_use]
    pub fn reference(&mut self, model: &Model, t: f64) -> Option<(&[f64], &[f64])> {
        match &self.law {
            ControlLaw::ComputedTorque { trajectory, .. } => {
                trajectory.sample(model, t, &mut self.qd, &mut self.vd, &mut self.ad);
                Some((&self.qd, &self.vd))
            }
            ControlLaw::Pd { target, .. } | ControlLaw::Stance { target, .. } => {
                self.vd.fill(0.0);
                Some((target, &self.vd))
            }
            _ => None,
        }
    }
}

impl Control for Controller {
    fn open_loop(&self) -> bool {
        self.law == ControlLaw::None
    }

    fn pd_gains(&self) -> Option<(&[f64], &[f64])> {
        match &self.law {
            ControlLaw::Pd { kp, kd, .. } | ControlLaw::Stance { kp, kd, .. } => Some((kp, kd)),
            ControlLaw::None
            | ControlLaw::GravityCompensation
            | ControlLaw::ComputedTorque { .. } => None,
        }
    }

    fn torque(
        &mut self,
        model: &Model,
        t: f64,
        q: &[f64],
        v: &[f64],
        tau: &mut [f64],
    ) -> Result<(), MultibodyError> {
        match &self.law {
            ControlLaw::None => tau.fill(0.0),
            ControlLaw::GravityCompensation => {
                tau.copy_from_slice(gravity_torques(model, &mut self.data, q)?.as_slice());
            }
            ControlLaw::Pd { target, kp, kd } => {
                difference(model, q, target, &mut self.e)?;
                let g = gravity_torques(model, &mut self.data, q)?;
                for k in 0..model.nv {
                    tau[k] = g[k] + kp[k] * self.e[k] - kd[k] * v[k];
                }
            }
            ControlLaw::Stance {
                target,
                kp,
                kd,
                feedforward,
            } => {
                difference(model, q, target, &mut self.e)?;
                for k in 0..model.nv {
                    tau[k] = feedforward[k] + kp[k] * self.e[k] - kd[k] * v[k];
                }
            }
            ControlLaw::ComputedTorque { trajectory, kp, kd } => {
                trajectory.sample(model, t, &mut self.qd, &mut self.vd, &mut self.ad);
                difference(model, q, &self.qd, &mut self.e)?;
                for k in 0..model.nv {
                    self.ad[k] += kp * self.e[k] + kd * (self.vd[k] - v[k]);
                }
                tau.copy_from_slice(rnea(model, &mut self.data, q, v, &self.ad)?.as_slice());
            }
        }
        Ok(())
    }
}
