//! The simulator: a body, a state, a clock and an integrator, stepping without allocation.

use super::integrators::{rkmk4_step, variational_step, Integrator, Momenta};
use super::rigid_body::{RigidBody, State, Support, WrenchFn};
use super::BodyError;
use crate::spatial::Vec3;

impl<W: WrenchFn> RigidBody<W> {
    /// One step of size `h` from `(t, x)` with the chosen integrator.
    ///
    /// # Errors
    /// [`BodyError::NoConvergence`] if the implicit solve of the variational integrator fails,
    /// [`BodyError::NonFinite`] if the new state is not finite (a wrench that blew up).
    pub fn step(
        &self,
        integrator: Integrator,
        t: f64,
        x: &State,
        h: f64,
    ) -> Result<State, BodyError> {
        let next = match integrator {
            Integrator::Rk4 => rkmk4_step(self, t, x, h),
            Integrator::Variational => variational_step(self, t, x, &Momenta::of(self, x), h)?.0,
        };
        if next.is_finite() {
            Ok(next)
        } else {
            Err(BodyError::NonFinite { what: "state" })
        }
    }
}

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

/// A body, its state, the time and an integrator with a fixed step.
///
/// ```
/// use rigid::body::{Integrator, RigidBody, Simulator, State};
/// use rigid::mass::{RotationalInertia, SpatialInertia};
/// use rigid::spatial::{Transform, Twist, Vec3};
/// let g = SpatialInertia::from_com(1.0, Vec3::zeros(), RotationalInertia::diagonal(1.0, 2.0, 3.0));
/// let body = RigidBody::free(g).unwrap();
/// let x0 = State::new(Transform::identity(), Twist::new(Vec3::new(0.1, 2.0, 0.1), Vec3::zeros()));
/// let mut sim = Simulator::new(body, x0, Integrator::Variational, 1e-3).unwrap();
/// sim.run(1000, |_, _| {}).unwrap();
/// assert!(sim.summary().relative_momentum_error() < 1e-13);
/// ```
#[derive(Clone, Debug)]
pub struct Simulator<W = fn(f64, &State) -> crate::spatial::Wrench> {
    body: RigidBody<W>,
    integrator: Integrator,
    dt: f64,
    t: f64,
    steps: u64,
    state: State,
    energy0: f64,
    kinetic0: f64,
    momentum0: Vec3,
    /// The variational integrator's momenta of `state`, carried between steps.
    momenta: Momenta,
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
        Ok(Self {
            energy0: body.energy(&x0),
            kinetic0: body.kinetic_energy(&x0),
            momentum0: body.angular_momentum(&x0),
            momenta: Momenta::of(&body, &x0),
            body,
            integrator,
            dt,
            t: 0.0,
            steps: 0,
            state: x0,
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
        &self.body
    }

    /// The step size (s).
    #[must_use]
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// One step; returns the new state. On error the state is left unchanged.
    ///
    /// # Errors
    /// As [`RigidBody::step`].
    pub fn step(&mut self) -> Result<&State, BodyError> {
        let (t, x, h) = (self.t, &self.state, self.dt);
        let (next, momenta) = match self.integrator {
            Integrator::Rk4 => (rkmk4_step(&self.body, t, x, h), self.momenta),
            Integrator::Variational => variational_step(&self.body, t, x, &self.momenta, h)?,
        };
        if !next.is_finite() {
            return Err(BodyError::NonFinite { what: "state" });
        }
        self.state = next;
        self.momenta = momenta;
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
        let g = self.body.gravity();
        let conserved_axis =
            (self.body.support() == Support::Pivot && g.norm() > 0.0).then(|| g.normalize());
        Summary {
            steps: self.steps,
            time: self.t,
            energy0: self.energy0,
            energy: self.body.energy(&self.state),
            kinetic0: self.kinetic0,
            momentum0: self.momentum0,
            momentum: self.body.angular_momentum(&self.state),
            conserved_axis,
        }
    }

    /// `|E - E₀| / max(|E₀|, K₀)` now.
    #[must_use]
    pub fn relative_energy_error(&self) -> f64 {
        self.summary().relative_energy_error()
    }
}
