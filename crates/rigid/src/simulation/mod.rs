//! Multibody simulation on the configuration manifold: a state `(q, v)` with quaternions moved
//! by [`integrate`](crate::multibody::integrate) (never renormalised by hand), forward dynamics by ABA,
//! three fixed-step integrators, passive joint forces, control laws, external wrenches, and
//! many initial states at once on every core ([`simulate_batch`]).
//!
//! | notes | code | source |
//! | --- | --- | --- |
//! | `q̈ = M⁻¹(τ + τ_passive + Σ Jᵢᵀ Fᵢ - c - g)` | [`Simulator::step`] | Featherstone 2008 Table 7.1 |
//! | `v⁺ = v + h q̈(q, v)`, `q⁺ = q ⊕ h v⁺` | [`Integrator::SemiImplicitEuler`] | symplectic Euler |
//! | RK4 on the joint groups, `Θ̇ = dexp⁻¹_{-Θ}(v)` | [`Integrator::Rk4`] | Munthe-Kaas 1999 (RKMK) |
//! | discrete Euler-Lagrange, 4th order by composition | [`Integrator::Variational`] | Marsden & West 2001; Suzuki 1990 |
//! | one rigid body: discrete Moser-Veselov on SO(3) | [`Integrator::Lgvi`] ([`body::Simulator`](crate::body::Simulator)) | Lee, Leok & McClamroch 2007 |
//! | `τ = -b v - F_c tanh(v / v_s)` | [`SimulationOptions::joint_dynamics`] | URDF `<dynamics>` |
//! | `τ = -D (e/τ_c² + 2ζ v/τ_c)` past a limit | [`JointLimits::Spring`] | MuJoCo's soft limits (`solref`) |
//! | contacts with friction, unilateral joint limits: impulses per step | [`Simulator::with_collision`], [`JointLimits::Unilateral`] ([`contact`](crate::simulation::contact)) | Moreau–Jean time stepping; Jean 1999 |
//! | quintic / trapezoidal `s(t)` | [`TimeScaling`] | Lynch & Park §9.2 |
//! | screw and Cartesian pose paths `X(s)` | [`PoseTrajectory`] | Lynch & Park §9.1.3 |
//! | gravity compensation, PD, computed torque | [`ControlLaw`] | Lynch & Park §11.4 |
//!
//! ```
//! use rigid::multibody::builtin;
//! use rigid::simulation::{Controller, SimulationOptions, Simulator};
//! let model = builtin("pendulum").unwrap();
//! let opts = SimulationOptions { dt: 1e-3, ..SimulationOptions::default() };
//! let mut sim = Simulator::new(&model, &[1.0], &[0.0], opts, Controller::none(&model))?;
//! let e0 = sim.energy()?;
//! sim.run(1000, |_| {})?;
//! assert!((sim.energy()? - e0).abs() < 1e-9 * e0.abs()); // RK4, 1 s of swinging
//! # Ok::<(), rigid::simulation::SimulationError>(())
//! ```

// loops over several per-dof arrays at once read better indexed
#![allow(clippy::needless_range_loop)]

#[cfg(feature = "parallel")]
mod batch;
pub mod contact;
mod contact_step;
mod control;
mod free_body;
mod integrators;
#[cfg(feature = "collision")]
mod linearised;
pub mod loops;
mod momentum;
mod scenario;
mod simulator;
#[cfg(feature = "collision")]
mod stance;
#[cfg(feature = "collision")]
mod step_derivatives;
mod trajectory;

#[cfg(feature = "parallel")]
pub use batch::simulate_batch;
pub use control::{Control, ControlKind, ControlLaw, Controller, OpenLoop};
pub use loops::{ConstraintOptions, Violation, MAX_INITIAL_VIOLATION};
pub use scenario::{Scenario, Start};
pub use simulator::Simulator;
#[cfg(feature = "collision")]
pub use step_derivatives::{ContactMode, StepDerivatives};
pub use trajectory::{JointTrajectory, PosePath, PoseTrajectory, TimeScaling};

use crate::multibody::MultibodyError;
use std::fmt;
use std::str::FromStr;
use thiserror::Error;

/// What can go wrong in a simulation.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SimulationError {
    /// A bad state or input to an algorithm.
    #[error(transparent)]
    Multibody(#[from] MultibodyError),
    /// A bad constraint, or a constraint solve that failed.
    #[error(transparent)]
    Constraint(#[from] crate::multibody::constraints::ConstraintError),
    /// Bilateral constraints asked of the variational integrator.
    #[error(
        "closed loops and other bilateral constraints are stepped by rk4 or semi-implicit \
         (with contacts: the time-stepping scheme), not by {integrator}"
    )]
    ConstrainedIntegrator {
        /// The integrator given.
        integrator: Integrator,
    },
    /// A constraint that does not hold at the start: farther than
    /// [`MAX_INITIAL_VIOLATION`] from closing.
    #[error(
        "constraint {index} is {violation:.3e} (m or rad) from closing at the start (at most \
         {MAX_INITIAL_VIOLATION}): assemble the mechanism (q0) or fix the constraint's frames"
    )]
    OpenLoop {
        /// The constraint (its position in the list).
        index: usize,
        /// Its largest error at the start.
        violation: f64,
    },
    /// A start, velocity or target of the wrong length.
    #[error("{what} has {got} numbers; the model has {expected} ({joints})")]
    Length {
        /// `q0`, `v0` or `target`.
        what: &'static str,
        /// The length given.
        got: usize,
        /// The length it needs (`nq` or `nv`).
        expected: usize,
        /// The joints and their `nq`.
        joints: String,
    },
    /// A bad option or parameter (the message says which).
    #[error("{0}")]
    Invalid(String),
    /// A simulator whose step [`Simulator::step_derivatives`] does not differentiate (the
    /// message says why).
    #[error("step derivatives: {0}")]
    NotDifferentiable(&'static str),
    /// A controller name that is not one of [`ControlKind`]'s.
    #[error("unknown controller {name:?}: expected none, gravity, pd or track")]
    UnknownController {
        /// The name given.
        name: String,
    },
    /// A built-in controller that needs a target ([`ControlKind::needs_target`]) was given none.
    #[error("controller {controller} needs a target configuration (nq = {nq} numbers)")]
    MissingTarget {
        /// The controller.
        controller: ControlKind,
        /// The length of the target it needs.
        nq: usize,
    },
    /// An integrator name that is not one of [`Integrator`]'s.
    #[error("unknown integrator {name:?}: expected semi-implicit, rk4, variational or lgvi")]
    UnknownIntegrator {
        /// The name given.
        name: String,
    },
    /// An integrator a multibody [`Simulator`] does not take ([`Integrator::Lgvi`], which steps
    /// one rigid body).
    #[error(
        "the {integrator} integrator steps one rigid body (a body spec; rigid::body::Simulator): \
         a multibody model takes semi-implicit, rk4 or variational"
    )]
    UnsupportedIntegrator {
        /// The integrator given.
        integrator: Integrator,
    },
    /// A name of joint limits that is not one of [`JointLimits`]'s (`spring`, `ignored`,
    /// `unilateral`).
    #[error("unknown joint limits {name:?}: expected spring, ignored or unilateral")]
    UnknownLimits {
        /// The name given.
        name: String,
    },
    /// Contacts or unilateral joint limits asked of an integrator other than `semi-implicit`:
    /// impulses are applied by the time-stepping scheme, which is first order.
    #[error(
        "contacts and unilateral joint limits are stepped by the time-stepping scheme \
         (--integrator semi-implicit), not by {integrator}"
    )]
    ContactIntegrator {
        /// The integrator given.
        integrator: Integrator,
    },
    /// Contact solver settings out of range.
    #[error("contact settings: max_iterations >= 1, tolerance >= 0, stabilization in [0, 1], restitution_speed >= 0")]
    ContactSettings,
    /// A bad collision model.
    #[cfg(feature = "collision")]
    #[error(transparent)]
    Collision(#[from] crate::collision::CollisionError),
    /// A time-scaling name that is not one of [`TimeScaling`]'s.
    #[error("unknown time scaling {name:?}: expected quintic or trapezoidal")]
    UnknownTimeScaling {
        /// The name given.
        name: String,
    },
    /// A time step that is not positive and finite.
    #[error("time step dt must be positive and finite, got {dt}")]
    TimeStep {
        /// The step given (s).
        dt: f64,
    },
    /// A duration that is not positive and finite ([`step_count`]).
    #[error("duration must be positive and finite, got {duration}")]
    Duration {
        /// The duration given (s).
        duration: f64,
    },
    /// A run of more than [`MAX_STEPS`] steps ([`step_count`]).
    #[error("{steps:.0} steps is too many (at most {MAX_STEPS}): raise the time step")]
    TooManySteps {
        /// `duration / dt`.
        steps: f64,
    },
    /// The fixed-point iteration of the variational integrator did not converge.
    #[error("the implicit step did not converge in {iterations} iterations (change {residual:.3e}); reduce the time step")]
    NoConvergence {
        /// Iterations done.
        iterations: usize,
        /// The last change of the velocity.
        residual: f64,
    },
    /// The state became NaN or infinite (an unstable step: stiff limits, friction or gains for
    /// this time step).
    #[error("the state is no longer finite at t = {time} s (unstable for this time step: reduce it, or soften gains, limits or friction)")]
    Diverged {
        /// Time of the step that failed.
        time: f64,
    },
}

/// The time stepper: one vocabulary for robots ([`Simulator`]) and single bodies
/// ([`body::Simulator`](crate::body::Simulator), whose free body or body on a pivot is the
/// one-joint case of a multibody model, stepped by the same code). Three steppers work on every
/// model; [`Lgvi`](Self::Lgvi) is the one that only a single body takes.
///
/// The default is [`Rk4`](Self::Rk4), for bodies and robots alike: it is explicit and 4th-order
/// accurate, costs four force evaluations a step, and takes every force as it comes (control
/// laws, limit springs, friction, an applied wrench that depends on time or velocity), so it is
/// the right first choice for both. Its energy and momentum drift slowly (`O(t h⁴)`); for long
/// conservative runs where they must not drift, choose [`Variational`](Self::Variational) (or,
/// for one body, [`Lgvi`](Self::Lgvi)).
///
/// | name | method | order | force evaluations per step | conserves |
/// | --- | --- | --- | --- | --- |
/// | `semi-implicit` | symplectic Euler | 1 | 1 | energy bounded |
/// | `rk4` (default) | Runge-Kutta-Munthe-Kaas | 4 | 4 | (drifts as `O(t h⁴)`) |
/// | `variational` | Störmer-Verlet on the joint groups, Suzuki's composition | 4 | ~100 passes | momentum maps exactly, energy bounded |
/// | `lgvi` | Lee-Leok-McClamroch, one rigid body only | 2 | 2 (3x3 Newton solve) | momentum exactly, energy bounded |
///
/// Until the vocabulary was shared, `variational` on a single body (`rigid simulate SPEC.toml
/// --integrator variational`, Python's `simulate_body`) named the 2nd-order LGVI, which is now
/// `lgvi`; `variational` is accepted there as before and runs the 4th-order variational
/// integrator, as for a robot.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Integrator {
    /// `semi-implicit`: symplectic Euler, `v⁺ = v + h q̈(q, v)`, `q⁺ = q ⊕ h v⁺`. One ABA per
    /// step, first order, bounded energy error for conservative systems.
    SemiImplicitEuler,
    /// `rk4`: the classical Runge-Kutta method lifted to the joint groups
    /// (Runge-Kutta-Munthe-Kaas): the stages are `q₀ ⊕ Θᵢ` with `Θ̇ = dexp⁻¹_{-Θ}(v)`
    /// ([`JointType::dexp`](crate::multibody::JointType) and its inverse, the one home of
    /// `dexp`). Four ABA per step, 4th order. The default.
    #[default]
    Rk4,
    /// `variational`: a variational (discrete Euler-Lagrange) integrator on the joint groups, in
    /// the state `(q, p = M(q) v)`. The base step is Störmer-Verlet built from the discrete
    /// Lagrangian `L_d(q₀, q₁) = h L(q₀, log(q₀⁻¹q₁)/h)` and its adjoint (`h L(q₁, …)`), with
    /// the discrete Legendre transforms `p₀ = dexp⁻ᵀ_ξ M v - h ∇_q L`, `p₁ = dexp⁻ᵀ_{-ξ} M v`
    /// (`ξ = h v`), solved by fixed-point iteration; five base steps of
    /// `γh, γh, (1 - 4γ)h, γh, γh` (Suzuki 1990, `γ = 1/(4 - 4^⅓)`) make it 4th order. Symplectic, and the momentum of
    /// every symmetry of `L` is kept exactly: for a free-flyer without gravity, the world spatial
    /// momentum `[Ad_{T⁻¹}]ᵀ p_base` is carried by `p₁ = [Ad_{exp ξ}]ᵀ p₀` at round-off. Energy
    /// error bounded (no drift). About 100 O(n) passes per step: for accuracy, not speed.
    Variational,
    /// `lgvi`: the Lie-group variational integrator of Lee, Leok & McClamroch (2007) for one
    /// rigid body (free, or on a pivot), [`body::Simulator`](crate::body::Simulator) only: the
    /// rotation about the CoM or the pivot by the discrete Moser-Veselov map (a 3x3 Newton solve
    /// per step), the CoM by velocity Verlet. 2nd order, symplectic; the world angular momentum
    /// of a torque-free body is kept to round-off, and so is its energy. Two force evaluations
    /// per step. A multibody [`Simulator`] refuses it
    /// ([`SimulationError::UnsupportedIntegrator`]).
    Lgvi,
}

impl Integrator {
    /// Every integrator, in the order of the command line's help.
    pub const ALL: [Integrator; 4] = [
        Self::SemiImplicitEuler,
        Self::Rk4,
        Self::Variational,
        Self::Lgvi,
    ];

    /// The command-line name: `semi-implicit`, `rk4`, `variational`, `lgvi`.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Self::SemiImplicitEuler => "semi-implicit",
            Self::Rk4 => "rk4",
            Self::Variational => "variational",
            Self::Lgvi => "lgvi",
        }
    }

    /// Whether a multibody [`Simulator`] takes it (every integrator but [`Lgvi`](Self::Lgvi)).
    #[must_use]
    pub fn steps_multibody(&self) -> bool {
        match self {
            Self::SemiImplicitEuler | Self::Rk4 | Self::Variational => true,
            Self::Lgvi => false,
        }
    }
}

impl fmt::Display for Integrator {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Integrator {
    type Err = SimulationError;
    fn from_str(s: &str) -> Result<Self, SimulationError> {
        Self::ALL
            .into_iter()
            .find(|i| i.name() == s)
            .ok_or_else(|| SimulationError::UnknownIntegrator { name: s.into() })
    }
}

/// Most steps a run may take ([`step_count`]): 10⁹, a day of simulated time at 0.1 ms, hours of
/// computing for a robot.
pub const MAX_STEPS: u64 = 1_000_000_000;

/// The number of fixed steps of `dt` in `duration` (rounded, at least one), as `rigid simulate`
/// and Python's `simulate` and `simulate_body` take them.
///
/// ```
/// use rigid::simulation::{step_count, SimulationError};
/// assert_eq!(step_count(1.0, 1e-3)?, 1000);
/// assert!(matches!(step_count(1e6, 1e-6), Err(SimulationError::TooManySteps { .. })));
/// # Ok::<(), SimulationError>(())
/// ```
///
/// # Errors
/// [`SimulationError::TimeStep`] or [`SimulationError::Duration`] unless both are positive and
/// finite; [`SimulationError::TooManySteps`] above [`MAX_STEPS`].
pub fn step_count(duration: f64, dt: f64) -> Result<u64, SimulationError> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(SimulationError::TimeStep { dt });
    }
    if !(duration.is_finite() && duration > 0.0) {
        return Err(SimulationError::Duration { duration });
    }
    let steps = (duration / dt).round().max(1.0);
    if steps > MAX_STEPS as f64 {
        return Err(SimulationError::TooManySteps { steps });
    }
    Ok(steps as u64)
}

/// What happens at a joint's position limits.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum JointLimits {
    /// The limits are ignored: joints move through them.
    Ignored,
    /// A spring-damper that only pushes back, active past a limit, in acceleration units (as
    /// MuJoCo's soft limits with `solref = (τ_c, ζ)`): with `e` the penetration and `D_k` the
    /// joint's articulated inertia at the initial state (ABA's `Sᵀ I^A S + armature`),
    /// `τ_k = -D_k (e / τ_c² + 2ζ v_k / τ_c)`, clipped so that it never pulls the joint into the
    /// limit. A joint that is light or heavy gets the same time constant `τ_c`; a fixed step
    /// stays stable for `h ≲ τ_c / 4`. Only 1-dof joints have limits.
    Spring {
        /// `τ_c` (s); MuJoCo's default is 0.02.
        time_constant: f64,
        /// `ζ`; 1 is critical damping.
        damping_ratio: f64,
    },
    /// Unilateral constraints `lower ≤ q ≤ upper`: an impulse stops a joint at its limit (no
    /// bounce, no penetration beyond the position correction), solved with the contacts
    /// ([`contact`](crate::simulation::contact)); stepped by the time-stepping scheme, so the
    /// integrator must be `semi-implicit`. Only 1-dof joints have limits.
    Unilateral,
}

impl Default for JointLimits {
    fn default() -> Self {
        Self::Spring {
            time_constant: 0.02,
            damping_ratio: 1.0,
        }
    }
}

impl FromStr for JointLimits {
    type Err = SimulationError;
    /// `spring` (the default spring-damper, [`JointLimits::default`]), `ignored` or
    /// `unilateral`.
    fn from_str(s: &str) -> Result<Self, SimulationError> {
        match s {
            "spring" => Ok(Self::default()),
            "ignored" => Ok(Self::Ignored),
            "unilateral" => Ok(Self::Unilateral),
            _ => Err(SimulationError::UnknownLimits { name: s.into() }),
        }
    }
}

/// Options of a [`Simulator`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimulationOptions {
    /// Time step `h` (s), fixed.
    pub dt: f64,
    /// The integrator.
    pub integrator: Integrator,
    /// Position limits.
    pub limits: JointLimits,
    /// Apply the model's joint damping `b` and Coulomb friction `F_c` (URDF `<dynamics>`):
    /// `τ = -b v - F_c tanh(v / v_s)`.
    pub joint_dynamics: bool,
    /// `v_s` (rad/s or m/s), the speed below which Coulomb friction is smoothed into a viscous
    /// law (a regularisation: an explicit step stays stable for `h < 2 D v_s / F_c`).
    pub friction_speed: f64,
}

impl Default for SimulationOptions {
    fn default() -> Self {
        Self {
            dt: 1e-3,
            integrator: Integrator::Rk4,
            limits: JointLimits::default(),
            joint_dynamics: true,
            friction_speed: 0.01,
        }
    }
}

impl SimulationOptions {
    /// A conservative setting: no limits, no damping or friction (for energy checks).
    #[must_use]
    pub fn conservative(dt: f64, integrator: Integrator) -> Self {
        Self {
            dt,
            integrator,
            limits: JointLimits::Ignored,
            joint_dynamics: false,
            ..Self::default()
        }
    }

    fn check(&self) -> Result<(), SimulationError> {
        let bad = |m: String| Err(SimulationError::Invalid(m));
        if !(self.dt.is_finite() && self.dt > 0.0) {
            return Err(SimulationError::TimeStep { dt: self.dt });
        }
        if !self.integrator.steps_multibody() {
            return Err(SimulationError::UnsupportedIntegrator {
                integrator: self.integrator,
            });
        }
        if !(self.friction_speed.is_finite() && self.friction_speed > 0.0) {
            return bad(format!(
                "friction speed must be positive and finite, got {}",
                self.friction_speed
            ));
        }
        if let JointLimits::Spring {
            time_constant,
            damping_ratio,
        } = self.limits
        {
            let ok = time_constant.is_finite()
                && time_constant > 0.0
                && damping_ratio.is_finite()
                && damping_ratio >= 0.0;
            if !ok {
                return bad(format!(
                    "limit time constant must be positive and damping ratio non-negative, got {time_constant}, {damping_ratio}"
                ));
            }
        }
        Ok(())
    }
}
