//! The simulator of one body: a body, a state, a clock and an [`Integrator`], stepping without
//! allocation.
//!
//! A free body is a one-joint multibody model (a free-flyer whose body is the rigid body), and a
//! body on a pivot is a one-joint model too (a spherical joint at the pivot): the free-flyer's
//! configuration `(p, quaternion)` and body velocity `(ω_b, v_b)` are the state `(T_sb, V_b)`,
//! its generalised force is the body wrench. So `semi-implicit`, `rk4` and `variational` run the
//! multibody [`simulation::Simulator`] on that model (the same code as for a robot); only the
//! [`Lgvi`](Integrator::Lgvi), which has no multibody counterpart, is this module's own
//! ([`super::lgvi`]).

use super::lgvi::{lgvi_step, Momenta};
use super::rigid_body::{RigidBody, State, Support, WrenchFn};
use super::BodyError;
use crate::multibody::{JointType, Model, ModelBuilder, MultibodyError};
use crate::simulation::{self, Control, Integrator, SimulationError, SimulationOptions};
use crate::spatial::{quat_to_rot, so3, Transform, Twist, Vec3, Wrench};

/// Energy and momentum of the initial and current state, for reporting drift.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    /// Steps taken.
    pub steps: u64,
    /// Simulated time (s).
    pub time: f64,
    /// Energy `K + U` at the start (J).
    pub energy0: f64,
    /// Energy now (J).
    pub energy: f64,
    /// Kinetic energy at the start (J).
    pub kinetic0: f64,
    /// Angular momentum (world axes, about the CoM or the pivot) at the start.
    pub momentum0: Vec3,
    /// Angular momentum now.
    pub momentum: Vec3,
    /// The direction along which the momentum is conserved when gravity acts on a pivoted body
    /// (the unit vector of `g_s`); `None` when all of it is conserved.
    pub conserved_axis: Option<Vec3>,
}

impl Summary {
    /// `|E - E₀| / max(|E₀|, K₀)`: the energy error relative to the initial energy (or the
    /// initial kinetic energy when `E₀` is near zero).
    #[must_use]
    pub fn relative_energy_error(&self) -> f64 {
        let scale = self.energy0.abs().max(self.kinetic0.abs());
        if scale > 0.0 {
            (self.energy - self.energy0).abs() / scale
        } else {
            (self.energy - self.energy0).abs()
        }
    }

    /// `|L - L₀| / |L₀|` over the conserved part of the angular momentum (its component along
    /// gravity for a pivoted body under gravity); absolute when `L₀ = 0`.
    #[must_use]
    pub fn relative_momentum_error(&self) -> f64 {
        let d = self.momentum - self.momentum0;
        let (err, scale) = match self.conserved_axis {
            Some(k) => (d.dot(&k).abs(), self.momentum0.norm()),
            None => (d.norm(), self.momentum0.norm()),
        };
        if scale > 0.0 {
            err / scale
        } else {
            err
        }
    }
}

/// The body as the control law of its one-joint model: the applied wrench `W(t, state)` as the
/// joint's generalised force (the body wrench for a free-flyer, its moment about the pivot for a
/// spherical joint); gravity is the model's.
#[derive(Clone, Debug)]
struct OneJoint<W> {
    body: RigidBody<W>,
    /// The world position of the pivot (a pivoted body).
    pivot: Vec3,
}

impl<W: WrenchFn> OneJoint<W> {
    /// The state `(T_sb, V_b)` of the joint's `(q, v)`.
    fn state(&self, q: &[f64], v: &[f64]) -> State {
        match self.body.support() {
            Support::Free => State::new(
                Transform::new(
                    quat_to_rot(q[3], q[4], q[5], q[6]),
                    Vec3::new(q[0], q[1], q[2]),
                ),
                Twist::from_slice(v),
            ),
            Support::Pivot => State::new(
                Transform::new(quat_to_rot(q[0], q[1], q[2], q[3]), self.pivot),
                Twist::new(Vec3::new(v[0], v[1], v[2]), Vec3::zeros()),
            ),
        }
    }

    /// The one-joint model of the body and the joint's `(q, v)` at `x`.
    fn model(&self, x: &State) -> Result<(Model, Vec<f64>, Vec<f64>), BodyError> {
        let quaternion = so3::to_quaternion(&x.pose.rotation);
        let (kind, placement, q, v) = match self.body.support() {
            Support::Free => {
                let p = x.pose.translation;
                let mut q = vec![p.x, p.y, p.z];
                q.extend_from_slice(&quaternion);
                let v = x.twist.to_vector().as_slice().to_vec();
                (JointType::FreeFlyer, Transform::identity(), q, v)
            }
            Support::Pivot => (
                JointType::Spherical,
                Transform::from_translation(self.pivot),
                quaternion.to_vec(),
                x.twist.w.as_slice().to_vec(),
            ),
        };
        let mut b = ModelBuilder::new("body");
        b.add_joint(None, "body", kind, placement, *self.body.inertia())?;
        Ok((b.build()?.with_gravity(self.body.gravity()), q, v))
    }
}

impl<W: WrenchFn> Control for OneJoint<W> {
    fn torque(
        &mut self,
        _model: &Model,
        t: f64,
        q: &[f64],
        v: &[f64],
        tau: &mut [f64],
    ) -> Result<(), MultibodyError> {
        let f: Wrench = self.body.applied_wrench(t, &self.state(q, v));
        match self.body.support() {
            Support::Free => tau.copy_from_slice(f.to_vector().as_slice()),
            Support::Pivot => tau.copy_from_slice(f.m.as_slice()),
        }
        Ok(())
    }
}

/// How the steps are taken: the one-joint multibody simulator, or the LGVI and its momenta.
#[derive(Clone, Debug)]
enum Stepper<W> {
    Joint(Box<simulation::Simulator<OneJoint<W>>>),
    Lgvi {
        body: Box<RigidBody<W>>,
        /// The variational integrator's momenta of the state, carried between steps.
        momenta: Momenta,
    },
}

/// A body, its state, the time and an integrator with a fixed step.
///
/// ```
/// use rigid::body::{Integrator, RigidBody, Simulator, State};
/// use rigid::mass::{RotationalInertia, SpatialInertia};
/// use rigid::spatial::{Transform, Twist, Vec3};
/// let g = SpatialInertia::from_com(1.0, Vec3::zeros(), RotationalInertia::diagonal(1.0, 2.0, 3.0));
/// let body = RigidBody::free(g).unwrap();
/// let x0 = State::new(Transform::identity(), Twist::new(Vec3::new(0.1, 2.0, 0.1), Vec3::zeros()));
/// let mut sim = Simulator::new(body, x0, Integrator::Lgvi, 1e-3).unwrap();
/// sim.run(1000, |_, _| {}).unwrap();
/// assert!(sim.summary().relative_momentum_error() < 1e-13);
/// ```
#[derive(Clone, Debug)]
pub struct Simulator<W = fn(f64, &State) -> crate::spatial::Wrench> {
    stepper: Stepper<W>,
    integrator: Integrator,
    dt: f64,
    t: f64,
    steps: u64,
    state: State,
    energy0: f64,
    kinetic0: f64,
    momentum0: Vec3,
}

/// A simulation error of the one-joint model as a body's.
fn body_error(e: SimulationError) -> BodyError {
    match e {
        SimulationError::Diverged { .. }
        | SimulationError::Multibody(MultibodyError::NonFinite { .. }) => {
            BodyError::NonFinite { what: "state" }
        }
        SimulationError::NoConvergence {
            iterations,
            residual,
        } => BodyError::NoConvergence {
            iterations,
            residual,
        },
        SimulationError::TimeStep { dt } => BodyError::TimeStep { dt },
        e => BodyError::Simulation(e),
    }
}

impl<W: WrenchFn> Simulator<W> {
    /// Starts at `t = 0` in state `x0` with step `dt`.
    ///
    /// # Errors
    /// [`BodyError::TimeStep`] unless `dt` is positive and finite; [`BodyError::NonFinite`] for a
    /// non-finite state; [`BodyError::PivotMoves`] for a pivoted body with `v_b ≠ 0`.
    pub fn new(
        body: RigidBody<W>,
        x0: State,
        integrator: Integrator,
        dt: f64,
    ) -> Result<Self, BodyError> {
        if !(dt > 0.0 && dt.is_finite()) {
            return Err(BodyError::TimeStep { dt });
        }
        if !x0.is_finite() {
            return Err(BodyError::NonFinite {
                what: "initial state",
            });
        }
        if body.support() == Support::Pivot && x0.twist.v.norm() > 0.0 {
            return Err(BodyError::PivotMoves {
                speed: x0.twist.v.norm(),
            });
        }
        let (energy0, kinetic0, momentum0) = (
            body.energy(&x0),
            body.kinetic_energy(&x0),
            body.angular_momentum(&x0),
        );
        let stepper = if integrator == Integrator::Lgvi {
            Stepper::Lgvi {
                momenta: Momenta::of(&body, &x0),
                body: Box::new(body),
            }
        } else {
            let joint = OneJoint {
                body,
                pivot: x0.pose.translation,
            };
            let (model, q0, v0) = joint.model(&x0)?;
            let opts = SimulationOptions::conservative(dt, integrator);
            let sim = simulation::Simulator::new(&model, &q0, &v0, opts, joint);
            Stepper::Joint(Box::new(sim.map_err(body_error)?))
        };
        Ok(Self {
            stepper,
            integrator,
            dt,
            t: 0.0,
            steps: 0,
            state: x0,
            energy0,
            kinetic0,
            momentum0,
        })
    }

    /// The current state.
    #[must_use]
    pub fn state(&self) -> &State {
        &self.state
    }

    /// The current time (s).
    #[must_use]
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The body.
    #[must_use]
    pub fn body(&self) -> &RigidBody<W> {
        match &self.stepper {
            Stepper::Joint(sim) => &sim.control().body,
            Stepper::Lgvi { body, .. } => body,
        }
    }

    /// The integrator.
    #[must_use]
    pub fn integrator(&self) -> Integrator {
        self.integrator
    }

    /// The step size (s).
    #[must_use]
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// One step; returns the new state. On error the state is left unchanged.
    ///
    /// # Errors
    /// [`BodyError::NoConvergence`] if the implicit solve of a variational integrator fails,
    /// [`BodyError::NonFinite`] if the new state is not finite (a wrench that blew up).
    pub fn step(&mut self) -> Result<&State, BodyError> {
        let next = match &mut self.stepper {
            Stepper::Joint(sim) => {
                sim.step().map_err(body_error)?;
                sim.control().state(sim.q(), sim.v())
            }
            Stepper::Lgvi { body, momenta } => {
                let (next, m) = lgvi_step(body, self.t, &self.state, momenta, self.dt)?;
                if next.is_finite() {
                    *momenta = m;
                }
                next
            }
        };
        if !next.is_finite() {
            return Err(BodyError::NonFinite { what: "state" });
        }
        self.state = next;
        self.steps += 1;
        self.t = self.steps as f64 * self.dt;
        Ok(&self.state)
    }

    /// `n` steps, calling `observe(t, state)` after each.
    ///
    /// # Errors
    /// The first step that fails.
    pub fn run(&mut self, n: u64, mut observe: impl FnMut(f64, &State)) -> Result<(), BodyError> {
        for _ in 0..n {
            self.step()?;
            observe(self.t, &self.state);
        }
        Ok(())
    }

    /// Steps, time, and energy and momentum at the start and now.
    #[must_use]
    pub fn summary(&self) -> Summary {
        let body = self.body();
        let g = body.gravity();
        let conserved_axis =
            (body.support() == Support::Pivot && g.norm() > 0.0).then(|| g.normalize());
        Summary {
            steps: self.steps,
            time: self.t,
            energy0: self.energy0,
            energy: body.energy(&self.state),
            kinetic0: self.kinetic0,
            momentum0: self.momentum0,
            momentum: body.angular_momentum(&self.state),
            conserved_axis,
        }
    }

    /// `|E - E₀| / max(|E₀|, K₀)` now.
    #[must_use]
    pub fn relative_energy_error(&self) -> f64 {
        self.summary().relative_energy_error()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mass::{RotationalInertia, SpatialInertia};
    use crate::simulation::Controller;

    const G: Vec3 = Vec3::new(0.0, 0.0, -9.81);

    /// A tumbling body (its frame {b} away from the CoM, axes off the principal ones).
    fn asymmetric() -> SpatialInertia {
        let r = so3::exp(&Vec3::new(-0.3, 0.1, 0.2));
        let i = RotationalInertia::diagonal(0.4, 0.7, 0.9).rotated_by(&r);
        SpatialInertia::from_com(1.5, Vec3::new(-0.1, 0.25, 0.05), i)
    }

    /// A pose and a twist with every component non-zero.
    fn start() -> State {
        let pose = Transform::new(
            so3::exp(&Vec3::new(0.4, 0.2, -0.6)),
            Vec3::new(0.5, -0.2, 1.0),
        );
        State::new(
            pose,
            Twist::new(Vec3::new(-0.8, 1.2, 0.6), Vec3::new(0.1, 0.4, -0.3)),
        )
    }

    /// A free body's `rk4` is the multibody simulator on the one-joint free-flyer model with the
    /// body's inertia, step for step.
    #[test]
    fn a_free_body_is_the_one_joint_free_flyer_model() {
        let body = RigidBody::free(asymmetric())
            .unwrap()
            .with_gravity(G)
            .unwrap();
        let x0 = start();
        let mut b = ModelBuilder::new("free");
        let flyer = JointType::FreeFlyer;
        b.add_joint(None, "f", flyer, Transform::identity(), asymmetric())
            .unwrap();
        let model = b.build().unwrap().with_gravity(G);
        let mut q0 = x0.pose.translation.as_slice().to_vec();
        q0.extend_from_slice(&so3::to_quaternion(&x0.pose.rotation));
        let v0 = x0.twist.to_vector().as_slice().to_vec();
        let opts = SimulationOptions::conservative(1e-3, Integrator::Rk4);
        let mut robot =
            simulation::Simulator::new(&model, &q0, &v0, opts, Controller::none(&model)).unwrap();
        let mut sim = Simulator::new(body, x0, Integrator::Rk4, 1e-3).unwrap();
        for _ in 0..500 {
            robot.step().unwrap();
            let x = *sim.step().unwrap();
            assert_eq!(&x.pose.translation.as_slice(), &&robot.q()[..3]);
            assert_eq!(x.twist.to_vector().as_slice(), robot.v());
        }
    }

    /// `variational` (the multibody one, 4th order) keeps the momentum of a torque-free free
    /// body and the vertical momentum of a heavy body on a pivot to round-off; `semi-implicit`
    /// steps a body too; the energy error of both stays small.
    #[test]
    fn every_multibody_integrator_steps_a_body() {
        let free = RigidBody::free(asymmetric()).unwrap();
        let pivot = RigidBody::pivot(asymmetric())
            .unwrap()
            .with_gravity(G)
            .unwrap();
        let still = State::new(start().pose, Twist::new(start().twist.w, Vec3::zeros()));
        for (body, x0) in [(free, start()), (pivot, still)] {
            for (integrator, energy) in [
                (Integrator::Variational, 1e-9),
                (Integrator::SemiImplicitEuler, 1e-2),
            ] {
                let mut sim = Simulator::new(body.clone(), x0, integrator, 1e-3).unwrap();
                sim.run(2000, |_, _| {}).unwrap();
                let s = sim.summary();
                let (de, dl) = (s.relative_energy_error(), s.relative_momentum_error());
                assert!(
                    de < energy,
                    "{integrator} {:?}: energy {de:e}",
                    body.support()
                );
                if integrator == Integrator::Variational {
                    assert!(dl < 1e-12, "{:?}: momentum {dl:e}", body.support());
                }
            }
        }
    }

    /// An applied wrench that depends on the state (a constant world force at the CoM, `Rᵀ f`
    /// in {b}) moves the CoM as `½ (f / m) t²` with every integrator (to its order).
    #[test]
    fn an_applied_wrench_acts_through_every_integrator() {
        let g = SpatialInertia::from_com(
            2.0,
            Vec3::zeros(),
            RotationalInertia::diagonal(1.0, 2.0, 3.0),
        );
        let f = Vec3::new(1.0, -2.0, 0.5);
        let body = RigidBody::free(g)
            .unwrap()
            .with_wrench(move |_: f64, x: &State| {
                Wrench::new(Vec3::zeros(), x.pose.rotation.transpose() * f)
            });
        let x0 = State::new(
            Transform::identity(),
            Twist::new(Vec3::new(0.3, 2.0, -1.0), Vec3::zeros()),
        );
        for integrator in Integrator::ALL {
            let mut sim = Simulator::new(body.clone(), x0, integrator, 1e-3).unwrap();
            sim.run(1000, |_, _| {}).unwrap();
            let expected = f * (0.5 / 2.0);
            let err = (sim.state().pose.translation - expected).norm();
            // symplectic Euler is first order: ½ |a| h t
            let tol = match integrator {
                Integrator::SemiImplicitEuler => 2e-3,
                _ => 1e-9,
            };
            assert!(err < tol, "{integrator}: {err:e}");
        }
    }
}
