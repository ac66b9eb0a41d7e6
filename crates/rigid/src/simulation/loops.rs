//! Bilateral constraints in the one simulator: closed loops, welds, MJCF equalities
//! ([`ConstraintModel`]s), held exactly.
//!
//! - With a smooth integrator (`rk4`, `semi-implicit` without contacts) the acceleration is
//!   [`constraint_dynamics`]'s: `M q̈ + c + g = τ + Jᵀ λ`, `J q̈ + γ = 0` (with each constraint's
//!   Baumgarte gains).
//! - With the time-stepping scheme (contacts, unilateral limits) the constraints are bilateral
//!   rows of the one contact problem (`J v⁺ = 0`, solved with the contacts over the shared
//!   Delassus rows), and their position error joins the contacts' position correction.
//! - After either, when [`ConstraintOptions::project`] is on, `q` is moved back onto the
//!   constraint manifold, Newton steps `δq = −M⁻¹ Jᵀ (J M⁻¹ Jᵀ)⁻¹ e`, `q ← q ⊕ δq` until
//!   `‖e‖∞ ≤ tolerance`, and (smooth integrators) `q̇ ← q̇ − M⁻¹ Jᵀ (J M⁻¹ Jᵀ)⁻¹ J q̇` (a plastic
//!   impulse, [`impulse_dynamics`] with `e = 0`): the smallest corrections in the metric of `M`
//!   (Ascher, Chin & Reich 1994; Cline & Pai 2003).

use super::SimulationError;
use crate::multibody::algorithms::ltl_factor;
use crate::multibody::constraints::solver::{delassus, primal, proximal};
use crate::multibody::constraints::{
    constraint_rows, impulse_dynamics, ConstraintData, ConstraintError, ConstraintModel,
    ProximalSettings,
};
use crate::multibody::{compute_joint_jacobians, crba, integrate, nonlinear_effects, Data, Model};

/// How a [`Simulator`](super::Simulator) holds its bilateral constraints
/// ([`with_constraints`](super::Simulator::with_constraints)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstraintOptions {
    /// The solver of each constrained acceleration, projection and velocity correction.
    pub settings: ProximalSettings,
    /// After each step, move `q` back onto the constraint manifold (`e(q) = 0`) and, with a
    /// smooth integrator, `q̇` onto its tangent space (`J q̇ = 0`), each the smallest change in
    /// the kinetic-energy metric `M`.
    pub project: bool,
    /// The position projection stops when `‖e‖∞` is at most this (m, rad).
    pub tolerance: f64,
    /// The most Newton iterations of the position projection.
    pub max_projection_iterations: usize,
}

impl Default for ConstraintOptions {
    /// Exact solves, projection on, tolerance `1e-12`, at most 10 iterations.
    fn default() -> Self {
        Self {
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

/// The largest constraint error (m) a simulation may start with: farther from closing, the loop
/// is refused ([`SimulationError::OpenLoop`]) rather than snapped shut by an impulse.
pub const MAX_INITIAL_VIOLATION: f64 = 1e-2;

/// The constraints of a simulator and their workspace.
#[derive(Clone, Debug)]
pub(crate) struct Loops {
    pub(crate) cdata: ConstraintData,
    pub(crate) options: ConstraintOptions,
    /// `τ + Σ Jᵢᵀ Fᵢ` for the constrained acceleration (external wrenches).
    pub(crate) tau: Vec<f64>,
    dq: Vec<f64>,
    q_next: Vec<f64>,
}

impl Loops {
    pub(crate) fn new(
        model: &Model,
        constraints: &[ConstraintModel],
        options: ConstraintOptions,
    ) -> Result<Self, SimulationError> {
        options.settings.check()?;
        let ok = options.tolerance.is_finite() && options.tolerance >= 0.0;
        if !ok {
            return Err(ConstraintError::BadSettings.into());
        }
        let nv = model.nv();
        Ok(Self {
            cdata: ConstraintData::new(model, constraints)?,
            options,
            tau: vec![0.0; nv],
            dq: vec![0.0; nv],
            q_next: vec![0.0; model.nq()],
        })
    }

    /// The violation at `(q, v)` (`cdata.error` and `cdata.velocity` filled).
    pub(crate) fn violation(
        &mut self,
        model: &Model,
        data: &mut Data,
        q: &[f64],
        v: &[f64],
        time: f64,
    ) -> Result<Violation, SimulationError> {
        let cd = &mut self.cdata;
        nonlinear_effects(model, data, q, v)?;
        compute_joint_jacobians(model, data, q)?;
        constraint_rows(model, data, cd, q, v, true);
        Ok(Violation {
            time,
            position: cd.error.amax(),
            velocity: cd.velocity.amax(),
        })
    }

    /// Moves `q` onto the constraint manifold and, when `velocity`, `v` onto its tangent space
    /// (see the [module](self) documentation); returns the Newton iterations done on `q`.
    pub(crate) fn project(
        &mut self,
        model: &Model,
        data: &mut Data,
        q: &mut [f64],
        v: &mut [f64],
        velocity: bool,
    ) -> Result<usize, SimulationError> {
        let settings = self.options.settings;
        let m = self.cdata.dim();
        let mut iterations = 0;
        loop {
            let cd = &mut self.cdata;
            nonlinear_effects(model, data, q, v)?;
            compute_joint_jacobians(model, data, q)?;
            constraint_rows(model, data, cd, q, v, true);
            if cd.error.amax() <= self.options.tolerance
                || iterations == self.options.max_projection_iterations
            {
                break;
            }
            // δq = −M⁻¹ Jᵀ K⁻¹ e = L⁻¹ Z λ with K λ = −e
            crba(model, data, q)?;
            ltl_factor(model, data)?;
            delassus(data, cd);
            for r in 0..m {
                cd.b[r] = -cd.error[r];
            }
            proximal(cd, &settings)?;
            self.dq.fill(0.0);
            primal(data, cd, &cd.lambda, &mut self.dq);
            integrate(model, q, &self.dq, 1.0, &mut self.q_next)?;
            q.copy_from_slice(&self.q_next);
            iterations += 1;
        }
        if velocity {
            let cd = &mut self.cdata;
            let v_plus = impulse_dynamics(model, data, cd, q, v, 0.0, &settings)?;
            v.copy_from_slice(v_plus.as_slice());
        }
        Ok(iterations)
    }
}
