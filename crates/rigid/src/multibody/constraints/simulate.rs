//! Simulation of constrained systems (closed loops, held contacts) with drift correction.

use super::dynamics::constraint_rows;
use super::solver::{delassus, primal, proximal};
use super::{
    constraint_dynamics, impulse_dynamics, ConstraintData, ConstraintError, ConstraintModel,
    ProximalSettings,
};
use crate::multibody::algorithms::ltl_factor;
use crate::multibody::configuration::dexp_inv;
use crate::multibody::{
    check_v, compute_joint_jacobians, crba, integrate, kinetic_energy, nonlinear_effects,
    potential_energy, Data, Model,
};

/// Options of [`ConstrainedSimulator`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstrainedStepOptions {
    /// Time step (s).
    pub dt: f64,
    /// The solver of each constrained acceleration, projection and velocity correction.
    pub settings: ProximalSettings,
    /// After each step, move `q` back onto the constraint manifold (`e(q) = 0`) and `q̇` onto its
    /// tangent space (`J q̇ = 0`), each the smallest change in the kinetic-energy metric `M`.
    pub project: bool,
    /// The position projection stops when `‖e‖∞` is at most this (m, rad).
    pub tolerance: f64,
    /// The most Newton iterations of the position projection.
    pub max_projection_iterations: usize,
}

impl Default for ConstrainedStepOptions {
    /// `dt = 1 ms`, exact solves, projection on, tolerance `1e-12`, at most 10 iterations.
    fn default() -> Self {
        Self {
            dt: 1e-3,
            settings: ProximalSettings::default(),
            project: true,
            tolerance: 1e-12,
            max_projection_iterations: 10,
        }
    }
}

/// The constraint violation at one time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Violation {
    /// Time (s).
    pub time: f64,
    /// `‖e(q)‖∞`: the largest constraint error (m, rad).
    pub position: f64,
    /// `‖J q̇‖∞`: the largest constraint velocity (m/s, rad/s).
    pub velocity: f64,
}

/// A fixed-step simulator of a model with constraints (closed loops, held contacts):
/// the RKMK4 Runge–Kutta scheme on the joint groups (Munthe-Kaas 1999, as the unconstrained
/// simulator's `Integrator::Rk4`) on the constrained accelerations of
/// [`constraint_dynamics`] (with each constraint's Baumgarte gains), then, when
/// [`project`](ConstrainedStepOptions::project) is on, a projection onto the constraint
/// manifold: Newton steps `δq = −M⁻¹ Jᵀ (J M⁻¹ Jᵀ)⁻¹ e`, `q ← q ⊕ δq` until
/// `‖e‖∞ ≤ tolerance`, and `q̇ ← q̇ − M⁻¹ Jᵀ (J M⁻¹ Jᵀ)⁻¹ J q̇` (a plastic impulse,
/// [`impulse_dynamics`] with `e = 0`). Both are the smallest corrections in the metric of `M`
/// (Ascher, Chin & Reich 1994, "Stabilization of DAEs and invariant manifolds"; Cline & Pai 2003,
/// "Post-stabilization for rigid body simulation with contact and constraints"). Allocates
/// nothing after [`new`](Self::new).
#[derive(Clone, Debug)]
pub struct ConstrainedSimulator<'m> {
    model: &'m Model,
    data: Data,
    cdata: ConstraintData,
    options: ConstrainedStepOptions,
    time: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    q_stage: Vec<f64>,
    v_stage: Vec<f64>,
    a: [Vec<f64>; 4],
    dtheta: [Vec<f64>; 4],
    theta: Vec<f64>,
}

impl<'m> ConstrainedSimulator<'m> {
    /// A simulator of `model` with `constraints`, starting at `(q0, v0)` (used as given; call
    /// [`project`](Self::project) to start on the constraint manifold).
    ///
    /// # Errors
    /// Bad constraints, states or options (`dt` not positive and finite).
    pub fn new(
        model: &'m Model,
        constraints: &[ConstraintModel],
        q0: &[f64],
        v0: &[f64],
        options: ConstrainedStepOptions,
    ) -> Result<Self, ConstraintError> {
        options.settings.check()?;
        if !(options.dt > 0.0 && options.dt.is_finite()) || options.tolerance.is_nan() {
            return Err(ConstraintError::BadSettings);
        }
        crate::multibody::check_q(model, q0)?;
        check_v(model, "v", v0)?;
        let nv = model.nv();
        let v = || vec![0.0; nv];
        Ok(Self {
            model,
            data: Data::new(model),
            cdata: ConstraintData::new(model, constraints)?,
            options,
            time: 0.0,
            q: q0.to_vec(),
            v: v0.to_vec(),
            q_stage: q0.to_vec(),
            v_stage: v(),
            a: [v(), v(), v(), v()],
            dtheta: [v(), v(), v(), v()],
            theta: v(),
        })
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
        self.time
    }
    /// The constraint workspace (its `lambda` holds the forces of the last acceleration).
    #[must_use]
    pub fn constraint_data(&self) -> &ConstraintData {
        &self.cdata
    }

    /// Kinetic plus potential energy (J).
    ///
    /// # Errors
    /// A state that is no longer valid.
    pub fn energy(&mut self) -> Result<f64, ConstraintError> {
        let k = kinetic_energy(self.model, &mut self.data, &self.q, &self.v)?;
        Ok(k + potential_energy(self.model, &mut self.data, &self.q)?)
    }

    /// The constraint violation of the current state.
    ///
    /// # Errors
    /// A state that is no longer valid.
    pub fn violation(&mut self) -> Result<Violation, ConstraintError> {
        let (model, data, cd) = (self.model, &mut self.data, &mut self.cdata);
        nonlinear_effects(model, data, &self.q, &self.v)?;
        compute_joint_jacobians(model, data, &self.q)?;
        constraint_rows(model, data, cd, &self.q, &self.v, true);
        Ok(Violation {
            time: self.time,
            position: cd.error.amax(),
            velocity: cd.velocity.amax(),
        })
    }

    /// One step of `dt` under the joint torques `tau`; returns the violation after it.
    ///
    /// # Errors
    /// Bad `tau`, a singular constraint set, or a state that is no longer finite.
    pub fn step(&mut self, tau: &[f64]) -> Result<Violation, ConstraintError> {
        self.rk4(tau)?;
        self.time += self.options.dt;
        if self.options.project {
            self.project()?;
        }
        for (what, x) in [("q", &self.q), ("v", &self.v)] {
            if let Some(index) = x.iter().position(|x| !x.is_finite()) {
                return Err(crate::multibody::MultibodyError::NonFinite { what, index }.into());
            }
        }
        self.violation()
    }

    /// RKMK4: stages at `q₀ ⊕ Θᵢ`, `Θ̇ᵢ = dexp⁻¹_{−Θᵢ}(vᵢ)`, as `simulation`'s `rk4`.
    fn rk4(&mut self, tau: &[f64]) -> Result<(), ConstraintError> {
        let (model, h) = (self.model, self.options.dt);
        let settings = self.options.settings;
        let nv = model.nv();
        let acc =
            |data: &mut Data, cd: &mut ConstraintData, q: &[f64], v: &[f64], out: &mut [f64]| {
                let ddq = constraint_dynamics(model, data, cd, q, v, tau, &settings)?;
                out.copy_from_slice(ddq.as_slice());
                Ok::<(), ConstraintError>(())
            };
        acc(
            &mut self.data,
            &mut self.cdata,
            &self.q,
            &self.v,
            &mut self.a[0],
        )?;
        self.dtheta[0].copy_from_slice(&self.v);
        let c = [0.5, 0.5, 1.0];
        for s in 1..4 {
            let hs = c[s - 1] * h;
            for k in 0..nv {
                self.theta[k] = -hs * self.dtheta[s - 1][k];
                self.v_stage[k] = self.v[k] + hs * self.a[s - 1][k];
            }
            integrate(model, &self.q, &self.dtheta[s - 1], hs, &mut self.q_stage)?;
            let (done, rest) = self.a.split_at_mut(s);
            let _ = done;
            acc(
                &mut self.data,
                &mut self.cdata,
                &self.q_stage,
                &self.v_stage,
                &mut rest[0],
            )?;
            let (_, rest) = self.dtheta.split_at_mut(s);
            dexp_inv(model, &self.theta, &self.v_stage, false, &mut rest[0]);
        }
        let (dt, a) = (&self.dtheta, &self.a);
        for k in 0..nv {
            self.theta[k] = (dt[0][k] + 2.0 * (dt[1][k] + dt[2][k]) + dt[3][k]) / 6.0;
            self.v[k] += h / 6.0 * (a[0][k] + 2.0 * (a[1][k] + a[2][k]) + a[3][k]);
        }
        integrate(model, &self.q, &self.theta, h, &mut self.q_stage)?;
        self.q.copy_from_slice(&self.q_stage);
        Ok(())
    }

    /// Moves `q` onto the constraint manifold and `q̇` onto its tangent space (see the type's
    /// documentation); returns the number of Newton iterations done on `q`.
    ///
    /// # Errors
    /// A singular constraint set (use `μ > 0` for redundant constraints).
    pub fn project(&mut self) -> Result<usize, ConstraintError> {
        let (model, settings) = (self.model, self.options.settings);
        let (data, cd) = (&mut self.data, &mut self.cdata);
        let m = cd.dim();
        let mut iterations = 0;
        loop {
            nonlinear_effects(model, data, &self.q, &self.v)?;
            compute_joint_jacobians(model, data, &self.q)?;
            constraint_rows(model, data, cd, &self.q, &self.v, true);
            if cd.error.amax() <= self.options.tolerance
                || iterations == self.options.max_projection_iterations
            {
                break;
            }
            // δq = −M⁻¹ Jᵀ K⁻¹ e = L⁻¹ Z λ with K λ = −e
            crba(model, data, &self.q)?;
            ltl_factor(model, data)?;
            delassus(data, cd);
            for r in 0..m {
                cd.b[r] = -cd.error[r];
            }
            proximal(cd, &settings)?;
            self.theta.fill(0.0);
            primal(data, cd, &cd.lambda, &mut self.theta);
            integrate(model, &self.q, &self.theta, 1.0, &mut self.q_stage)?;
            self.q.copy_from_slice(&self.q_stage);
            iterations += 1;
        }
        let v = impulse_dynamics(model, data, cd, &self.q, &self.v, 0.0, &settings)?;
        self.v.copy_from_slice(v.as_slice());
        Ok(iterations)
    }
}
