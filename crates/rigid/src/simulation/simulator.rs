//! The simulator: a model, a state `(q, v)` (and `p = M v` for the variational integrator), a
//! clock, a control law and the external wrenches, stepping without allocation.

use super::contact_step::{contact_step, ContactStepper};
use super::control::Control;
use super::integrators::{self, Workspace};
use super::loops::{ConstraintOptions, Loops, Violation, MAX_INITIAL_VIOLATION};
use super::{Integrator, JointLimits, SimulationError, SimulationOptions};
use crate::multibody::constraints::{
    constraint_dynamics, ConstraintData, ConstraintError, ConstraintModel,
};

use crate::multibody::{
    aba, aba_with_external, check_q, check_v, forward_kinematics_qv, gravity_torques,
    kinetic_energy, potential_energy, rnea_with_external, Data, JointId, Model, MultibodyError,
};
use crate::spatial::{Vec3, Wrench};

/// Everything the right-hand side `q̈ = f(t, q, v)` needs.
#[derive(Clone, Debug)]
pub(crate) struct Dynamics<C> {
    pub(crate) model: Model,
    /// The same model without gravity: `aba(free, q, 0, x) = M(q)⁻¹ x`.
    pub(crate) free: Model,
    pub(crate) data: Data,
    pub(crate) control: C,
    pub(crate) options: SimulationOptions,
    pub(crate) fext: Vec<Wrench>,
    pub(crate) has_fext: bool,
    /// `D_k` of each 1-dof joint at the initial state (limit springs).
    limit_inertia: Vec<f64>,
    /// The last control torques and passive torques.
    pub(crate) tau_control: Vec<f64>,
    pub(crate) tau: Vec<f64>,
    zeros: Vec<f64>,
    /// The bilateral constraints, if any ([`Simulator::with_constraints`]).
    pub(crate) loops: Option<Box<Loops>>,
}

impl<C: Control> Dynamics<C> {
    /// `τ = u(t, q, v) + τ_passive(q, v)` into `self.tau` (external wrenches excluded).
    pub(crate) fn torques(&mut self, t: f64, q: &[f64], v: &[f64]) -> Result<(), MultibodyError> {
        self.control
            .torque(&self.model, t, q, v, &mut self.tau_control)?;
        let m = &self.model;
        let opts = &self.options;
        for k in 0..m.nv {
            let mut tk = self.tau_control[k];
            if opts.joint_dynamics {
                tk -= m.damping[k] * v[k] + m.friction[k] * (v[k] / opts.friction_speed).tanh();
            }
            self.tau[k] = tk;
        }
        let tau = &mut self.tau;
        limit_springs(m, opts, &self.limit_inertia, q, v, |k, [f, _, _]| {
            tau[k] += f
        });
        Ok(())
    }

    /// The diagonal partials `∂τ_passive/∂q` and `∂τ_passive/∂v` of [`torques`](Self::torques)'s
    /// passive part (joint damping and friction, limit springs) into `dq`, `dv`.
    #[cfg(feature = "collision")]
    pub(crate) fn passive_partials(&self, q: &[f64], v: &[f64], dq: &mut [f64], dv: &mut [f64]) {
        let m = &self.model;
        let opts = &self.options;
        dq.fill(0.0);
        dv.fill(0.0);
        if opts.joint_dynamics {
            for k in 0..m.nv {
                let t = (v[k] / opts.friction_speed).tanh();
                dv[k] = -m.damping[k] - m.friction[k] * (1.0 - t * t) / opts.friction_speed;
            }
        }
        limit_springs(m, opts, &self.limit_inertia, q, v, |k, [_, fx, fv]| {
            dq[k] += fx;
            dv[k] += fv;
        });
    }

    /// `a = q̈(t, q, v)` by ABA with every force, or by the constrained dynamics when there are
    /// bilateral constraints.
    pub(crate) fn acceleration(
        &mut self,
        t: f64,
        q: &[f64],
        v: &[f64],
        a: &mut [f64],
    ) -> Result<(), SimulationError> {
        self.torques(t, q, v)?;
        if let Some(l) = &mut self.loops {
            // τ + Σ Jᵀ F: rnea without gravity, at rest, with F gives −Σ Jᵀ F
            l.tau.copy_from_slice(&self.tau);
            if self.has_fext {
                let z = &self.zeros;
                let r = rnea_with_external(&self.free, &mut self.data, q, z, z, &self.fext)?;
                for (t, rk) in l.tau.iter_mut().zip(r.iter()) {
                    *t -= rk;
                }
            }
            let (model, data) = (&self.model, &mut self.data);
            let settings = l.options.settings;
            let ddq = constraint_dynamics(model, data, &mut l.cdata, q, v, &l.tau, &settings)?;
            a.copy_from_slice(ddq.as_slice());
            return Ok(());
        }
        let ddq = if self.has_fext {
            aba_with_external(&self.model, &mut self.data, q, v, &self.tau, &self.fext)?
        } else {
            aba(&self.model, &mut self.data, q, v, &self.tau)?
        };
        a.copy_from_slice(ddq.as_slice());
        Ok(())
    }

    /// `out = M(q)⁻¹ x` (ABA without gravity at rest).
    pub(crate) fn minv(
        &mut self,
        q: &[f64],
        x: &[f64],
        out: &mut [f64],
    ) -> Result<(), MultibodyError> {
        let r = aba(&self.free, &mut self.data, q, &self.zeros, x)?;
        out.copy_from_slice(r.as_slice());
        Ok(())
    }

    /// `out = -g(q) + Σ Jᵢᵀ Fᵢ` (gravity and the external wrenches as generalised forces).
    pub(crate) fn field_forces(
        &mut self,
        q: &[f64],
        out: &mut [f64],
    ) -> Result<(), MultibodyError> {
        let g = gravity_torques(&self.model, &mut self.data, q)?;
        for (o, gk) in out.iter_mut().zip(g.iter()) {
            *o = -gk;
        }
        if self.has_fext {
            // rnea without gravity, at rest, with F: τ = -Σ Jᵀ F
            let r = rnea_with_external(
                &self.free,
                &mut self.data,
                q,
                &self.zeros,
                &self.zeros,
                &self.fext,
            )?;
            for (o, rk) in out.iter_mut().zip(r.iter()) {
                *o -= rk;
            }
        }
        Ok(())
    }
}

/// Each 1-dof joint's limit spring ([`JointLimits::Spring`]) at `(q, v)`, where it pushes:
/// `each(dof, [f, ∂f/∂x, ∂f/∂v])` with `f = −D ((x − l)/T² + 2ζ v/T)`, `l` the limit passed, `D`
/// the joint's articulated inertia at the start, `T` the time constant, `ζ` the damping ratio;
/// a spring that would pull the joint further out pushes nothing.
fn limit_springs(
    m: &Model,
    opts: &SimulationOptions,
    inertia: &[f64],
    q: &[f64],
    v: &[f64],
    mut each: impl FnMut(usize, [f64; 3]),
) {
    let JointLimits::Spring {
        time_constant: tc,
        damping_ratio: zeta,
    } = opts.limits
    else {
        return;
    };
    for j in m.joints() {
        if j.nq != 1 || j.nv != 1 {
            continue;
        }
        let (x, k) = (q[j.idx_q], j.idx_v);
        let (lo, hi) = (m.lower[j.idx_q], m.upper[j.idx_q]);
        let (past, sign) = if x > hi {
            (hi, -1.0)
        } else if x < lo {
            (lo, 1.0)
        } else {
            continue;
        };
        let d = inertia[k];
        let f = -d * ((x - past) / (tc * tc) + 2.0 * zeta * v[k] / tc);
        if sign * f > 0.0 {
            each(k, [f, -d / (tc * tc), -2.0 * d * zeta / tc]);
        }
    }
}

/// A multibody simulation: a model, its state, the time and an integrator with a fixed step, a
/// control law `C` ([`Controller`](super::Controller) or a closure) and constant external
/// wrenches per body. [`step`](Self::step) allocates nothing.
///
/// ```
/// use rigid::multibody::builtin;
/// use rigid::simulation::{ControlLaw, Controller, Integrator, SimulationOptions, Simulator};
/// let model = builtin("double_pendulum").unwrap();
/// let ctrl = Controller::new(&model, ControlLaw::GravityCompensation)?;
/// let opts = SimulationOptions { integrator: Integrator::SemiImplicitEuler, ..Default::default() };
/// let mut sim = Simulator::new(&model, &[0.5, -0.3], &[0.0, 0.0], opts, ctrl)?;
/// sim.run(500, |_| {})?;
/// assert!((sim.q()[0] - 0.5).abs() < 1e-12); // held still
/// # Ok::<(), rigid::simulation::SimulationError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Simulator<C = super::Controller> {
    pub(crate) dynamics: Dynamics<C>,
    pub(crate) ws: Workspace,
    pub(crate) t: f64,
    pub(crate) steps: u64,
    pub(crate) q: Vec<f64>,
    pub(crate) v: Vec<f64>,
    /// `p = M(q) v` (the variational integrator's state).
    pub(crate) p: Vec<f64>,
    /// Contacts and unilateral limits, when there are any ([`with_collision`](Self::with_collision),
    /// [`JointLimits::Unilateral`]).
    pub(crate) contact: Option<Box<ContactStepper>>,
    /// A copy of `contact` that [`step_derivatives`](Self::step_derivatives) steps, so that
    /// the simulator's own contacts and memory stay those of its last step (made on first use).
    pub(crate) derivative_stepper: Option<Box<ContactStepper>>,
}

impl<C: Control> Simulator<C> {
    /// Starts at `t = 0` in `(q0, v0)`.
    ///
    /// # Errors
    /// Bad options, wrong lengths, a non-finite entry, a non-unit quaternion, a singular mass
    /// matrix at `q0`.
    pub fn new(
        model: &Model,
        q0: &[f64],
        v0: &[f64],
        options: SimulationOptions,
        control: C,
    ) -> Result<Self, SimulationError> {
        options.check()?;
        check_q(model, q0)?;
        check_v(model, "v0", v0)?;
        if options.integrator == Integrator::Variational {
            // its ∇_q K (momentum.rs) assumes every S constant in body coordinates
            crate::multibody::algorithms::require_constant_subspaces(
                model,
                "the variational integrator",
            )?;
        }
        let (nq, nv) = (model.nq, model.nv);
        let mut data = Data::new(model);
        // articulated inertia of each 1-dof joint at q0, for the limit springs
        let zeros = vec![0.0; nv];
        aba(model, &mut data, q0, &zeros, &zeros)?;
        let limit_inertia = (0..nv)
            .map(|k| {
                let j = &model.joints()[model.plan().dof_joint[k]];
                if j.nv == 1 {
                    1.0 / data.d_inv_1[k]
                } else {
                    0.0
                }
            })
            .collect();
        let mut sim = Self {
            dynamics: Dynamics {
                model: model.clone(),
                free: model.clone().with_gravity(Vec3::zeros()),
                data,
                control,
                options,
                fext: vec![Wrench::zero(); model.njoints()],
                has_fext: false,
                limit_inertia,
                tau_control: vec![0.0; nv],
                tau: vec![0.0; nv],
                zeros,
                loops: None,
            },
            ws: Workspace::new(nq, nv),
            t: 0.0,
            steps: 0,
            q: q0.to_vec(),
            v: v0.to_vec(),
            p: vec![0.0; nv],
            contact: None,
            derivative_stepper: None,
        };
        if options.limits == JointLimits::Unilateral {
            sim.contact_stepper()?;
        }
        sim.sync_momentum();
        Ok(sim)
    }

    /// The contact stepper, made on first use; refuses an integrator other than semi-implicit.
    fn contact_stepper(&mut self) -> Result<&mut ContactStepper, SimulationError> {
        let integrator = self.dynamics.options.integrator;
        if integrator != Integrator::SemiImplicitEuler {
            return Err(SimulationError::ContactIntegrator { integrator });
        }
        let model = &self.dynamics.model;
        self.derivative_stepper = None;
        Ok(self
            .contact
            .get_or_insert_with(|| Box::new(ContactStepper::new(model))))
    }

    /// The same simulator with collision geometry: contacts with the ground and between bodies,
    /// with Coulomb friction and restitution, solved at every step
    /// ([`contact`](crate::simulation::contact)). The integrator must be `semi-implicit` (the
    /// time-stepping scheme).
    ///
    /// ```
    /// use rigid::collision::{CollisionModel, Geometry, Ground, Shape};
    /// use rigid::mass::{RotationalInertia, SpatialInertia};
    /// use rigid::simulation::{Controller, Integrator, SimulationOptions, Simulator};
    /// use rigid::multibody::{JointId, JointType, ModelBuilder};
    /// use rigid::spatial::{Transform, Vec3};
    /// // a 1 kg ball of radius 0.1 m dropped from 0.5 m onto the ground
    /// let g = SpatialInertia::from_com(1.0, Vec3::zeros(), RotationalInertia::diagonal(0.004, 0.004, 0.004));
    /// let mut b = ModelBuilder::new("ball");
    /// b.add_joint(None, "ball", JointType::FreeFlyer, Transform::identity(), g).unwrap();
    /// let model = b.build().unwrap();
    /// let mut cm = CollisionModel::new(Ground::horizontal(0.0, 0.8));
    /// cm.geometries.push(Geometry::new("ball", Some(JointId(0)), Transform::identity(), Shape::Sphere { radius: 0.1 }));
    /// let opts = SimulationOptions { integrator: Integrator::SemiImplicitEuler, ..Default::default() };
    /// let q0 = [0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 1.0];
    /// let mut sim = Simulator::new(&model, &q0, &[0.0; 6], opts, Controller::none(&model))?.with_collision(cm)?;
    /// sim.run(1000, |_| {})?;
    /// assert!((sim.q()[2] - 0.1).abs() < 1e-6); // resting on the ground
    /// # Ok::<(), rigid::simulation::SimulationError>(())
    /// ```
    ///
    /// # Errors
    /// [`SimulationError::ContactIntegrator`], or a bad collision model
    /// ([`SimulationError::Collision`]).
    #[cfg(feature = "collision")]
    pub fn with_collision(
        mut self,
        collision: crate::collision::CollisionModel,
    ) -> Result<Self, SimulationError> {
        let data = crate::collision::CollisionData::new(&self.dynamics.model, &collision)?;
        self.contact_stepper()?.collision = Some((collision, data));
        Ok(self)
    }

    /// The same simulator with bilateral constraints (closed loops, welds, MJCF equalities),
    /// held exactly at every step whatever else acts (contacts, limits, control): by the
    /// constrained dynamics under a smooth integrator, as bilateral rows of the contact problem
    /// under the time-stepping scheme, then projected onto the constraint manifold
    /// ([`ConstraintOptions::project`]); see [`loops`](super::loops). With the projection on, the
    /// start state is projected too. Call it before or after
    /// [`with_collision`](Self::with_collision).
    ///
    /// ```
    /// use rigid::multibody::constraints::ConstraintModel;
    /// use rigid::simulation::{ConstraintOptions, Controller, SimulationOptions, Simulator};
    /// use rigid::multibody::{builtin, forward_kinematics_q, Data, JointId};
    /// use rigid::spatial::{Transform, Vec3};
    /// // the double pendulum's tip pinned where it is at q0: a loop without freedom
    /// let model = builtin("double_pendulum").unwrap();
    /// let q0 = [0.5, -1.0];
    /// let mut data = Data::new(&model);
    /// forward_kinematics_q(&model, &mut data, &q0)?;
    /// let tip = Transform::from_translation(Vec3::new(0.0, 0.0, -1.0));
    /// let c = ConstraintModel::point(Some(JointId(1)), tip, None, data.placements[1] * tip);
    /// let mut opts = ConstraintOptions::default();
    /// opts.settings.mu = 1e-6; // the y row is redundant (planar motion)
    /// let none = Controller::none(&model);
    /// let sim = Simulator::new(&model, &q0, &[1.0, -2.0], SimulationOptions::default(), none)?;
    /// let mut sim = sim.with_constraints(&[c], opts)?; // the start's velocity projected: zero
    /// sim.run(1000, |_| {})?;
    /// assert!(sim.violation()?.position < 1e-12);
    /// assert!((sim.q()[0] - 0.5).abs() < 1e-9 && (sim.q()[1] + 1.0).abs() < 1e-9);
    /// # Ok::<(), rigid::simulation::SimulationError>(())
    /// ```
    ///
    /// # Errors
    /// A bad constraint or option ([`SimulationError::Constraint`]), the variational integrator
    /// ([`SimulationError::ConstrainedIntegrator`]), a start farther than
    /// [`MAX_INITIAL_VIOLATION`] from closing ([`SimulationError::OpenLoop`]).
    pub fn with_constraints(
        mut self,
        constraints: &[ConstraintModel],
        options: ConstraintOptions,
    ) -> Result<Self, SimulationError> {
        let integrator = self.dynamics.options.integrator;
        if integrator == Integrator::Variational {
            return Err(SimulationError::ConstrainedIntegrator { integrator });
        }
        let d = &mut self.dynamics;
        let mut loops = Box::new(Loops::new(&d.model, constraints, options)?);
        loops.violation(&d.model, &mut d.data, &self.q, &self.v, self.t)?;
        let e = &loops.cdata.error;
        if let Some(r) = (0..e.len()).find(|&r| e[r].abs() > MAX_INITIAL_VIOLATION) {
            let index = (0..constraints.len())
                .find(|&i| loops.cdata.rows_of(i).contains(&r))
                .unwrap_or(0);
            return Err(SimulationError::OpenLoop {
                index,
                violation: e[r].abs(),
            });
        }
        d.loops = Some(loops);
        if options.project {
            self.project_constraints()?;
        }
        Ok(self)
    }

    /// Moves the state onto the constraint manifold and its tangent space (the projection of
    /// [`ConstraintOptions::project`]); returns the Newton iterations done (0 without
    /// constraints).
    ///
    /// # Errors
    /// A singular constraint set (use `μ > 0` for redundant constraints).
    pub fn project_constraints(&mut self) -> Result<usize, SimulationError> {
        let d = &mut self.dynamics;
        let Some(l) = &mut d.loops else {
            return Ok(0);
        };
        let n = l.project(&d.model, &mut d.data, &mut self.q, &mut self.v, true)?;
        self.sync_momentum();
        Ok(n)
    }

    /// The constraint violation of the current state (zero without constraints).
    ///
    /// # Errors
    /// A state that is no longer valid.
    pub fn violation(&mut self) -> Result<Violation, SimulationError> {
        let d = &mut self.dynamics;
        match &mut d.loops {
            Some(l) => l.violation(&d.model, &mut d.data, &self.q, &self.v, self.t),
            None => Ok(Violation {
                time: self.t,
                ..Violation::default()
            }),
        }
    }

    /// The constraints' workspace (`None` without constraints): after a step with a smooth
    /// integrator, its `lambda` holds the constraint forces of the last acceleration.
    #[must_use]
    pub fn constraint_data(&self) -> Option<&ConstraintData> {
        self.dynamics.loops.as_ref().map(|l| &l.cdata)
    }

    /// The same simulator with these contact solver settings.
    ///
    /// # Errors
    /// [`SimulationError::ContactSettings`] for settings out of range,
    /// [`SimulationError::ContactIntegrator`].
    pub fn with_contact_settings(
        mut self,
        settings: crate::simulation::contact::ContactSettings,
    ) -> Result<Self, SimulationError> {
        if !settings.is_valid() {
            return Err(SimulationError::ContactSettings);
        }
        self.contact_stepper()?.settings = settings;
        Ok(self)
    }

    /// The contacts of the last step: every contact point given to the solver (a gap under the
    /// margin that the step may close: at most `2 h |σ_n| + 0.1 mm`, `σ_n` its approach speed),
    /// whether it pushed or not; empty without collision geometry.
    #[cfg(feature = "collision")]
    #[must_use]
    pub fn contacts(&self) -> &[crate::collision::ContactPoint] {
        self.contact.as_ref().map_or(&[], |c| c.contacts())
    }

    /// The impulse of each of [`contacts`](Self::contacts) on its body 1 over the last step
    /// (N·s, world axes; divide by `dt` for the mean force).
    #[must_use]
    pub fn contact_impulses(&self) -> &[Vec3] {
        self.contact.as_ref().map_or(&[], |c| c.impulses())
    }

    /// What the last step's contact solve did (all zero without contacts).
    #[must_use]
    pub fn contact_stats(&self) -> crate::simulation::contact::ContactStats {
        self.contact.as_ref().map(|c| c.stats()).unwrap_or_default()
    }

    /// The energy the contact impulses have taken since the start (J): minus the sum of their
    /// work over each step, `λᵀ J (v + v⁺)/2` ([`ContactStats::work`](crate::simulation::contact::ContactStats::work));
    /// `K + U` plus this is the energy the system would have without them (to first order in
    /// `h`). Zero for a body at rest on the ground; `½ m u² (1 − e²)` for an impact at the speed `u`.
    #[must_use]
    pub fn contact_dissipation(&self) -> f64 {
        self.contact.as_ref().map_or(0.0, |c| c.dissipated)
    }

    /// `p = M(q) v` from the current `(q, v)`.
    fn sync_momentum(&mut self) {
        let d = &mut self.dynamics;
        super::momentum::momentum(&d.model, &mut d.data, &self.q, &self.v, &mut self.p, None);
    }

    /// One step of `dt`. On error the state is left unchanged.
    ///
    /// # Errors
    /// An algorithm's error, [`SimulationError::NoConvergence`] (variational), or
    /// [`SimulationError::Diverged`] when the new state is not finite.
    pub fn step(&mut self) -> Result<(), SimulationError> {
        let h = self.dynamics.options.dt;
        let ok = if let Some(cs) = &mut self.contact {
            let ws = &mut self.ws;
            contact_step(
                &mut self.dynamics,
                cs,
                self.t,
                h,
                &self.q,
                &self.v,
                &mut ws.q_new,
                &mut ws.v_new,
            )
        } else {
            match self.dynamics.options.integrator {
                super::Integrator::SemiImplicitEuler => integrators::semi_implicit_euler(
                    &mut self.dynamics,
                    &mut self.ws,
                    self.t,
                    h,
                    &self.q,
                    &self.v,
                ),
                super::Integrator::Rk4 => integrators::rk4(
                    &mut self.dynamics,
                    &mut self.ws,
                    self.t,
                    h,
                    &self.q,
                    &self.v,
                ),
                super::Integrator::Variational => integrators::variational(
                    &mut self.dynamics,
                    &mut self.ws,
                    self.t,
                    h,
                    &self.q,
                    &self.p,
                ),
                // refused by `new`, and options cannot change after it
                integrator @ super::Integrator::Lgvi => {
                    Err(SimulationError::UnsupportedIntegrator { integrator })
                }
            }
        };
        let time = self.t + h;
        let ok = ok.and_then(|()| {
            let d = &mut self.dynamics;
            match &mut d.loops {
                Some(l) if l.options.project => {
                    let ws = &mut self.ws;
                    // the time-stepping scheme solved J v⁺ = 0 with the contacts, unless its
                    // energy safeguard scaled the impulse (the bilateral part with it)
                    let velocity = self.contact.as_ref().is_none_or(|c| c.stats().scaled);
                    l.project(
                        &d.model,
                        &mut d.data,
                        &mut ws.q_new,
                        &mut ws.v_new,
                        velocity,
                    )
                    .map(|_| ())
                }
                _ => Ok(()),
            }
        });
        match ok {
            Ok(()) => {}
            Err(
                SimulationError::Multibody(MultibodyError::NonFinite { .. })
                | SimulationError::Constraint(ConstraintError::Multibody(
                    MultibodyError::NonFinite { .. },
                )),
            ) => return Err(SimulationError::Diverged { time }),
            Err(e) => return Err(e),
        }
        let ws = &self.ws;
        if !ws.q_new.iter().chain(&ws.v_new).all(|x| x.is_finite()) {
            return Err(SimulationError::Diverged { time });
        }
        self.q.copy_from_slice(&ws.q_new);
        self.v.copy_from_slice(&ws.v_new);
        if self.dynamics.options.integrator == super::Integrator::Variational {
            self.p.copy_from_slice(&ws.p_new);
        }
        self.steps += 1;
        self.t = self.steps as f64 * h;
        Ok(())
    }

    /// `n` steps, calling `observe(self)` after each.
    ///
    /// # Errors
    /// The first step that fails.
    pub fn run(&mut self, n: u64, mut observe: impl FnMut(&Self)) -> Result<(), SimulationError> {
        for _ in 0..n {
            self.step()?;
            observe(self);
        }
        Ok(())
    }

    /// The configuration.
    #[must_use]
    pub fn q(&self) -> &[f64] {
        &self.q
    }
    /// The velocity.
    #[must_use]
    pub fn v(&self) -> &[f64] {
        &self.v
    }
    /// The time (s).
    #[must_use]
    pub fn time(&self) -> f64 {
        self.t
    }
    /// Steps taken.
    #[must_use]
    pub fn steps(&self) -> u64 {
        self.steps
    }
    /// The model.
    #[must_use]
    pub fn model(&self) -> &Model {
        &self.dynamics.model
    }
    /// The options.
    #[must_use]
    pub fn options(&self) -> &SimulationOptions {
        &self.dynamics.options
    }
    /// The control law.
    #[must_use]
    pub fn control(&self) -> &C {
        &self.dynamics.control
    }
    /// The control law.
    pub fn control_mut(&mut self) -> &mut C {
        &mut self.dynamics.control
    }

    /// Replace the state (and restart nothing else: the time goes on).
    ///
    /// # Errors
    /// Wrong lengths, non-finite entries, a non-unit quaternion.
    pub fn set_state(&mut self, q: &[f64], v: &[f64]) -> Result<(), SimulationError> {
        check_q(&self.dynamics.model, q)?;
        check_v(&self.dynamics.model, "v", v)?;
        self.q.copy_from_slice(q);
        self.v.copy_from_slice(v);
        self.sync_momentum();
        Ok(())
    }

    /// Forgets the contacts of past steps (their impulses, the warm start of the next solve,
    /// an impact of the last step, whose rebound the next step would give, and the collision
    /// search's warm starts): for a step from a state that does not continue the last one.
    pub fn forget_contacts(&mut self) {
        if let Some(c) = &mut self.contact {
            c.solver.forget();
            #[cfg(feature = "collision")]
            if let Some((_, cd)) = &mut c.collision {
                cd.forget();
            }
        }
    }

    /// Set the external wrench on the body moved by `joint`, in that body's frame, held until
    /// changed (for a wrench that varies, set it between steps).
    ///
    /// # Errors
    /// An unknown joint or a non-finite wrench.
    pub fn set_external_wrench(
        &mut self,
        joint: JointId,
        w: Wrench,
    ) -> Result<(), SimulationError> {
        let d = &mut self.dynamics;
        if joint.0 >= d.fext.len() {
            return Err(MultibodyError::OutOfRange {
                what: "joint",
                index: joint.0,
            }
            .into());
        }
        if !w.to_vector().iter().all(|x| x.is_finite()) {
            return Err(SimulationError::Invalid(format!(
                "external wrench on '{}' is not finite",
                d.model.joints()[joint.0].name
            )));
        }
        d.fext[joint.0] = w;
        d.has_fext = d.fext.iter().any(|f| *f != Wrench::zero());
        Ok(())
    }

    /// The torques applied at the current state: the control law's, and the total with the
    /// passive joint forces (damping, friction, limits), each of length `nv`.
    ///
    /// # Errors
    /// The control law's error.
    pub fn torques(&mut self) -> Result<(&[f64], &[f64]), SimulationError> {
        let d = &mut self.dynamics;
        d.torques(self.t, &self.q, &self.v)?;
        Ok((&d.tau_control, &d.tau))
    }

    /// Total energy `K + U` (J) of the current state.
    ///
    /// # Errors
    /// Only if the state is bad (it is checked at every step).
    pub fn energy(&mut self) -> Result<f64, SimulationError> {
        let (k, u) = self.energies()?;
        Ok(k + u)
    }

    /// Kinetic and potential energy `(K, U)` (J).
    ///
    /// # Errors
    /// As [`energy`](Self::energy).
    pub fn energies(&mut self) -> Result<(f64, f64), SimulationError> {
        let d = &mut self.dynamics;
        let k = kinetic_energy(&d.model, &mut d.data, &self.q, &self.v)?;
        let u = potential_energy(&d.model, &mut d.data, &self.q)?;
        Ok((k, u))
    }

    /// The spatial momentum of the whole system in the world frame, about the world origin:
    /// `Σᵢ [Ad_{oMi⁻¹}]ᵀ Gᵢ Vᵢ` (conserved for a free-flying robot without gravity, external
    /// wrenches or control).
    ///
    /// # Errors
    /// As [`energy`](Self::energy).
    pub fn momentum(&mut self) -> Result<Wrench, SimulationError> {
        let d = &mut self.dynamics;
        forward_kinematics_qv(&d.model, &mut d.data, &self.q, &self.v)?;
        let mut h = Wrench::zero();
        for i in 0..d.model.njoints() {
            h += d.data.placements[i]
                .act_wrench(&d.model.inertias()[i].momentum(&d.data.velocities[i]));
        }
        Ok(h)
    }

    /// The workspace `Data` (placements etc. of the last evaluation; use after
    /// [`momentum`](Self::momentum) for the current placements).
    #[must_use]
    pub fn data(&self) -> &Data {
        &self.dynamics.data
    }
}

/// Lengths of a row-major block of states.
#[cfg(feature = "parallel")]
pub(crate) fn check_rows(
    what: &'static str,
    per: usize,
    n: usize,
    len: usize,
) -> Result<(), SimulationError> {
    crate::error::DimensionError::check(what, n * per, len)
        .map_err(|e| MultibodyError::from(e).into())
}
