//! The one home of a simulation's set-up policy: what `rigid simulate`, Python's `simulate`,
//! `simulate_body` and `simulate_batch` fill in, and the rules that turn it into a
//! [`Simulator`]:
//!
//! - **integrator**: anything that can touch (collision geometry, unilateral joint limits) is
//!   stepped by the time-stepping scheme: `rk4`, the default, gives way to `semi-implicit`;
//!   `variational` is refused ([`SimulationError::ContactIntegrator`]);
//! - **start**: `q0` when given, else the target when there is a ground and a target, else the
//!   model's home (an MJCF file's `qpos0`, else neutral); with a ground, a floating robot's
//!   target, and its start when neither `q0` nor a home places it (a URDF has no place in the
//!   world), are set down on it ([`place_on_ground`](crate::collision::place_on_ground)); a
//!   file that places its bodies (MJCF) starts where it places them, as in MuJoCo;
//! - **controller**: `pd` with a ground and a target holds the stance on the contacts
//!   ([`ControlLaw::standing`]); otherwise the built-in law ([`ControlLaw::builtin`]);
//! - **constraints**: held by the same step ([`Simulator::with_constraints`]), the start
//!   projected onto them.

use super::contact::ContactSettings;
use super::{
    ConstraintOptions, ControlKind, ControlLaw, Controller, Integrator, JointLimits,
    SimulationError, SimulationOptions, Simulator, TimeScaling,
};
use crate::multibody::constraints::kinematics::polynomial;
use crate::multibody::constraints::{ConstraintKind, ConstraintModel};
use crate::multibody::{neutral, Model};

/// What to simulate and how: a model, its world (collision geometry, constraints), its start,
/// its controller and the step's options. [`build`](Self::build) applies the rules of the
/// [module](self).
///
/// ```
/// use rigid::multibody::builtin;
/// use rigid::simulation::{ControlKind, Scenario};
/// let mut s = Scenario::new(builtin("double_pendulum").unwrap());
/// s.q0 = Some(vec![0.5, -0.3]);
/// s.controller = ControlKind::Gravity;
/// let mut sim = s.build()?;
/// sim.run(500, |_| {})?;
/// assert!((sim.q()[0] - 0.5).abs() < 1e-9); // held still by gravity compensation
/// # Ok::<(), rigid::simulation::SimulationError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Scenario {
    /// The model (gravity included).
    pub model: Model,
    /// Where the file places the model (an MJCF file's `qpos0`): the start when no `q0` is
    /// given, not set down; `None`: the neutral configuration, set down on a ground.
    pub home: Option<Vec<f64>>,
    /// The initial configuration (`nq` numbers).
    pub q0: Option<Vec<f64>>,
    /// The initial velocity (`nv` numbers; default zero).
    pub v0: Option<Vec<f64>>,
    /// The built-in controller.
    pub controller: ControlKind,
    /// The target of `pd` and `track` (`nq` numbers).
    pub target: Option<Vec<f64>>,
    /// The duration of `track`'s motion (s).
    pub move_time: f64,
    /// The time scaling of `track`'s motion.
    pub profile: TimeScaling,
    /// The step's options (the integrator as asked: [`build`](Self::build) may replace it).
    pub options: SimulationOptions,
    /// The collision geometry (the ground, the bodies' shapes), if anything can touch.
    #[cfg(feature = "collision")]
    pub collision: Option<crate::collision::CollisionModel>,
    /// Bilateral constraints (closed loops, welds, MJCF equalities).
    pub constraints: Vec<ConstraintModel>,
    /// How they are held.
    pub constraint_options: ConstraintOptions,
    /// The contact solver's settings (used when anything can touch).
    pub contact: ContactSettings,
}

impl Scenario {
    /// `model` at its home, at rest, no controller, the default options, nothing to touch.
    #[must_use]
    pub fn new(model: Model) -> Self {
        Self {
            model,
            home: None,
            q0: None,
            v0: None,
            controller: ControlKind::None,
            target: None,
            move_time: 1.0,
            profile: TimeScaling::Quintic,
            options: SimulationOptions::default(),
            #[cfg(feature = "collision")]
            collision: None,
            constraints: Vec::new(),
            constraint_options: ConstraintOptions::default(),
            contact: ContactSettings::default(),
        }
    }

    /// `model` in the world its file describes ([`crate::io::collision::file_world`]): the
    /// home the file places it at, the collision model, the bilateral constraints and their
    /// solver, the file's time step (else 1 ms); at rest, no controller.
    #[cfg(feature = "collision")]
    #[must_use]
    pub fn in_world(model: Model, world: crate::io::collision::FileWorld) -> Self {
        let mut s = Self::new(model);
        s.options.dt = world.time_step(None);
        s.home = world.home;
        s.collision = world.collision;
        s.constraints = world.constraints;
        s.constraint_options.settings = world.constraint_settings;
        s
    }

    /// Whether anything can touch: collision geometry or unilateral joint limits.
    #[must_use]
    pub fn touches(&self) -> bool {
        #[cfg(feature = "collision")]
        if self.collision.is_some() {
            return true;
        }
        self.options.limits == JointLimits::Unilateral
    }

    /// Whether there is a ground to stand on.
    fn ground(&self) -> bool {
        #[cfg(feature = "collision")]
        if let Some(cm) = &self.collision {
            return cm.ground.is_some();
        }
        false
    }

    /// The options the simulator runs with: `rk4` replaced by `semi-implicit` when anything can
    /// touch.
    #[must_use]
    pub fn effective_options(&self) -> SimulationOptions {
        let mut o = self.options;
        if self.touches() && o.integrator == Integrator::Rk4 {
            o.integrator = Integrator::SemiImplicitEuler;
        }
        o
    }

    /// The start and the target, after the rules of the [module](self) (set down on a ground).
    ///
    /// # Errors
    /// A vector of the wrong length ([`SimulationError::Length`]), a bad collision model.
    pub fn start(&self) -> Result<Start, SimulationError> {
        let m = &self.model;
        let (nq, nv) = (m.nq(), m.nv());
        let length = |what: &'static str, x: &[f64], n: usize| {
            if x.len() == n {
                Ok(())
            } else {
                Err(SimulationError::Length {
                    what,
                    got: x.len(),
                    expected: n,
                    joints: joint_list(m),
                })
            }
        };
        #[allow(unused_mut)] // set down on a ground (feature `collision`)
        let mut target = self.target.clone();
        if let Some(t) = &target {
            length("target", t, nq)?;
        }
        #[allow(unused_mut)]
        let mut q0 = match (&self.q0, &target) {
            (Some(q), _) => q.clone(),
            (None, Some(t)) if self.ground() => t.clone(),
            (None, _) => self.home.clone().unwrap_or_else(|| self.neutral()),
        };
        length("q0", &q0, nq)?;
        let v0 = self.v0.clone().unwrap_or_else(|| vec![0.0; nv]);
        length("v0", &v0, nv)?;
        #[cfg(feature = "collision")]
        if let Some(cm) = self.collision.as_ref().filter(|c| c.ground.is_some()) {
            use crate::collision::place_on_ground;
            if self.q0.is_none() && (self.home.is_none() || target.is_some()) {
                place_on_ground(m, cm, &mut q0)?;
            }
            if let Some(t) = target.as_mut() {
                place_on_ground(m, cm, t)?;
            }
        }
        Ok(Start { q0, v0, target })
    }

    /// The neutral configuration with each joint that a joint-coordinate constraint holds (an
    /// MJCF `<equality joint>`, a mimic joint) at its polynomial of the other joint's
    /// coordinate, `q_1 = Σ c_k q_2^k`, in the constraints' order, so that a coupling with an
    /// offset starts closed.
    fn neutral(&self) -> Vec<f64> {
        let m = &self.model;
        let mut q = neutral(m);
        for c in &self.constraints {
            if let (ConstraintKind::JointCoordinate { polycoef }, Some(j1)) = (c.kind, c.joint1) {
                let x = c.joint2.map_or(0.0, |j2| q[m.joint(j2).idx_q]);
                q[m.joint(j1).idx_q] = polynomial(&polycoef, x).0;
            }
        }
        q
    }

    /// The control law at the start `q0` towards `target` (see the [module](self)).
    ///
    /// # Errors
    /// A controller that needs a target and has none, a stance the contacts cannot hold.
    pub fn control_law(
        &self,
        q0: &[f64],
        target: Option<&[f64]>,
    ) -> Result<ControlLaw, SimulationError> {
        #[cfg(feature = "collision")]
        if let (Some(cm), ControlKind::Pd, Some(t)) = (&self.collision, self.controller, target) {
            if cm.ground.is_some() {
                return ControlLaw::standing(&self.model, t, cm);
            }
        }
        ControlLaw::builtin(
            &self.model,
            self.controller,
            q0,
            target,
            self.move_time,
            self.profile,
        )
    }

    /// The simulator of this scenario, with its built-in controller.
    ///
    /// # Errors
    /// As [`start`](Self::start), [`control_law`](Self::control_law) and
    /// [`build_with`](Self::build_with).
    pub fn build(&self) -> Result<Simulator<Controller>, SimulationError> {
        let Start { q0, v0, target } = self.start()?;
        let law = self.control_law(&q0, target.as_deref())?;
        let control = Controller::new(&self.model, law)?;
        self.assemble(&q0, &v0, control)
    }

    /// The simulator of this scenario with another control law (the built-in controller is not
    /// used).
    ///
    /// # Errors
    /// As [`start`](Self::start), [`Simulator::new`], [`Simulator::with_collision`] and
    /// [`Simulator::with_constraints`].
    pub fn build_with<C: super::Control>(
        &self,
        control: C,
    ) -> Result<Simulator<C>, SimulationError> {
        let start = self.start()?;
        self.assemble(&start.q0, &start.v0, control)
    }

    fn assemble<C: super::Control>(
        &self,
        q0: &[f64],
        v0: &[f64],
        control: C,
    ) -> Result<Simulator<C>, SimulationError> {
        let mut sim = Simulator::new(&self.model, q0, v0, self.effective_options(), control)?;
        #[cfg(feature = "collision")]
        if let Some(cm) = &self.collision {
            sim = sim.with_collision(cm.clone())?;
        }
        if !self.constraints.is_empty() {
            sim = sim.with_constraints(&self.constraints, self.constraint_options)?;
        }
        if self.contact != ContactSettings::default() {
            sim = sim.with_contact_settings(self.contact)?;
        }
        Ok(sim)
    }
}

/// Where a [`Scenario`] starts ([`Scenario::start`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Start {
    /// The initial configuration.
    pub q0: Vec<f64>,
    /// The initial velocity.
    pub v0: Vec<f64>,
    /// The target of `pd` and `track`, set down like the start.
    pub target: Option<Vec<f64>>,
}

/// `name (nq)` for every joint.
fn joint_list(model: &Model) -> String {
    model
        .joints()
        .iter()
        .map(|j| format!("{} ({})", j.name, j.nq))
        .collect::<Vec<_>>()
        .join(", ")
}
