//! The derivatives of one step of the time-stepping scheme with contacts
//! ([`contact_step`](super::contact_step)): `∂(q⁺, v⁺)/∂(q, v, τ)`, by the implicit function
//! theorem on the step's equations at their solution, each contact in the mode the solver left
//! it in (separated, sticking, sliding), `q` perturbed along `q ⊕ δ` and `q⁺` compared by
//! `⊖`.
//!
//! The step, from [`contact`](super::contact): `M̃ (v⁺ − v − T(v)) = h (τ − b(q, v)) + Jᵀ λ`
//! (`b` the bias forces with gravity and external wrenches, `T` the free-flyers' world-aligned
//! turn; a lone free body takes its free velocity from the midpoint rule instead), the contact
//! conditions on `σ = J v⁺`, the position correction `δq = h M̃⁻¹ Jᵀ μ`, and
//! `q⁺ = q ⊕ h (v⁺ + δq/h)` with the free-flyers stepped in world-aligned axes.
//!
//! 1. **The free velocity.** With `a⁺ = (v⁺ − v − T)/h`, one RNEA derivative at `(q, v, a⁺)`
//!    gives both `∂b/∂q` and `∂(M(q) u)/∂q` for `u = v⁺ − v_f` (RNEA is `M a + b`):
//!    `∂v⁺/∂q = M̃⁻¹ (−h ∂RNEA/∂q + ∂(Jᵀλ)/∂q + Jᵀ ∂λ/∂q)`, `∂v_f/∂v = I + ∂T/∂v − h M̃⁻¹ ∂b/∂v`
//!    (a lone body: the midpoint rule's own derivative,
//!    [`FreeBodies::velocity_jacobian`](super::free_body)), `∂v_f/∂τ = h M̃⁻¹`; the passive joint
//!    forces (damping, friction, limit springs) add their diagonal partials.
//! 2. **The impulses.** `δv⁺ = E δs + M̃⁻¹ Jᵀ δλ`, and per row of the problem:
//!    - a separated contact (`λ_n = 0`), a frictionless tangent, an idle limit: `δλ = 0`;
//!    - a pushing normal (or limit), a sticking tangent: `δσ = J δv⁺ + ∂(J v⁺)/∂q δq = δσ*`,
//!      `σ*_n = −φ/h` when the gap was open (`∂φ/∂q = J_n`), a rebound `−e J_n v` when found
//!      approaching, else constant;
//!    - a sliding contact, `λ_t = −μ λ_n σ_t/‖σ_t‖`:
//!      `δλ_t + μ û δλ_n + (μ λ_n/‖σ_t‖)(I − û ûᵀ) δσ_t = 0`, `û = σ_t/‖σ_t‖`.
//!
//!    The rows make one square system in `δλ`, solved in the least-squares sense (a box on its
//!    four corners has twelve rows for six freedoms: `δλ` is not unique, `δv⁺` is while the
//!    contacts stick; sliding on four coplanar points, the friction's moment depends on how the
//!    solver shared the weight, and the least-norm `δλ` need not be the solver's).
//!
//!    Bilateral rows (closed loops, welds: [`loops`](super::loops)) hold `J_B v⁺ = 0`, their
//!    `∂(J_B v⁺)/∂q` and `∂(J_Bᵀ λ_B)/∂q` the velocity-level partials of the constrained
//!    dynamics' derivatives ([`constraints`](crate::multibody::constraints)).
//! 3. **The position correction**, when something penetrated: the same on its normal rows,
//!    `(J M̃⁻¹ Jᵀ μ)_n = β (−φ)/h` for each pushing one, with `∂(M w)/∂q` from a second RNEA
//!    derivative (`w = M̃⁻¹ Jᵀ μ`); bilateral rows always (`−β e/h`, `∂e/∂q = J_B` at `e = 0`:
//!    an error within the projection's tolerance asks no correction, but any perturbation
//!    leaves that band).
//! 4. **The configuration update**: per joint the Jacobians of `⊕`
//!    ([`integrate_jacobians`](crate::multibody::integrate_jacobians)); a free-flyer, stepped
//!    in world-aligned axes with `R = exp(h ω)`: `δθ⁺ = Rᵀ δθ + h J_r(hω) δω`,
//!    `δp⁺ = Rᵀ (δp − h [v]× δθ + h δv)`, and its velocity turned to the new axes,
//!    `δ(Rᵀ u) = Rᵀ δu + [Rᵀ u]× J_r(hω) h δω`.
//! 5. **The projection onto the loops** ([`ConstraintOptions::project`](super::ConstraintOptions)),
//!    at its solution: the tangent projector in the metric of `M`,
//!    `I − M⁻¹ J_Bᵀ (J_B M⁻¹ J_Bᵀ)⁺ J_B` at `q⁺` (first order in the error it removed, `O(h²)`).
//!
//! Where the step is not differentiable (a contact exactly at a mode switch: touching without
//! pushing, pushing at `φ = 0`, sticking on the cone's edge), each column is the one-sided
//! derivative along `+δ`: a contact touching without pushing is a complementarity row of the
//! linearised problem (`δλ ≥ 0`, `δσ ≥ δσ*`), solved per column by a small active set; at
//! `φ = 0` the target takes the side the column moves the gap to (an opening closed in the
//! step, a penetration left to the correction); the correction's rows that meet their target
//! without pushing are complementarity rows too. [`StepDerivatives::at_switch`] names those
//! contacts. The control law's torque is an input: a law that is not open-loop
//! ([`Control::open_loop`]: [`OpenLoop`](super::OpenLoop), `ControlLaw::None`) is refused.

use super::contact::Block;
use super::contact_step::{contact_step, ContactStepper};
use super::control::Control;
use super::linearised::{at_zero, classify, gap_target, solve_rows, target_of, Row, Target};
use super::{SimulationError, Simulator};
use crate::collision::Turn;
use crate::multibody::algorithms::{ltl_factor, ltl_solve_lower, ltl_solve_transposed};
use crate::multibody::configuration::world_aligned_turn;
use crate::multibody::constraints::velocity_level_partials;
use crate::multibody::{
    crba, rnea_derivatives, rnea_derivatives_with_external, se3_right_jacobian, Data, JointType,
};
use crate::spatial::{so3, Mat3, Mat6, Twist, Vec3};
use nalgebra::DMatrix;

/// What a contact (or joint limit) did in the differentiated step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContactMode {
    /// No impulse (`λ_n = 0`).
    Separated,
    /// Pushing, without slip (inside the friction cone, or frictionless, or a joint limit).
    Sticking,
    /// Pushing and slipping, the friction on the cone's edge.
    Sliding,
}

impl ContactMode {
    /// `separated`, `sticking` or `sliding` (the word of `rigid step` and Python).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Separated => "separated",
            Self::Sticking => "sticking",
            Self::Sliding => "sliding",
        }
    }
}

/// `∂(q⁺, v⁺)/∂(q, v, τ)` of one step ([`Simulator::step_derivatives`]), each `nv x nv`: `q`
/// and `q⁺` in the tangent space (`q ⊕ δ`, `q⁺ ⊖ q⁺₀`), `τ` the torque added to the control's.
#[derive(Clone, Debug, PartialEq)]
pub struct StepDerivatives {
    /// `∂q⁺/∂q`.
    pub dq_dq: DMatrix<f64>,
    /// `∂q⁺/∂v`.
    pub dq_dv: DMatrix<f64>,
    /// `∂q⁺/∂τ`.
    pub dq_dtau: DMatrix<f64>,
    /// `∂v⁺/∂q`.
    pub dv_dq: DMatrix<f64>,
    /// `∂v⁺/∂v`.
    pub dv_dv: DMatrix<f64>,
    /// `∂v⁺/∂τ`.
    pub dv_dtau: DMatrix<f64>,
    /// The step's new state `(q⁺, v⁺)` (the one [`Simulator::step`] would reach).
    pub q_next: Vec<f64>,
    /// See `q_next`.
    pub v_next: Vec<f64>,
    /// The mode of each contact (in the order of `contacts`), then of each joint limit of the
    /// step's problem.
    pub modes: Vec<ContactMode>,
    /// The indices (into `modes`) of those at a mode switch, where the step is not
    /// differentiable: touching without pushing, pushing exactly at `φ = 0` (within 1e-12),
    /// sticking on the cone's edge. Each column is then the one-sided derivative along `+δ`
    /// (`q ⊕ δ e_k`, `v + δ e_k`, `τ + δ e_k`, `δ → 0⁺`): a contact touching without pushing
    /// pushes (and sticks) in the columns that press it, one at `φ = 0` is closed in the step
    /// along the columns that open it and corrected along those that press it; a contact on
    /// the cone's edge is held sticking (one side only).
    pub at_switch: Vec<usize>,
    /// The contact points of the differentiated step (those of `modes`, in its order; the
    /// limits follow in `modes`).
    pub contacts: Vec<crate::collision::ContactPoint>,
    /// The indices (into `modes`) of the pushing contacts whose normal's turn and point's
    /// move are held fixed in these derivatives: between two geometries, those that are
    /// neither a flat face against a vertex, a ball or a rim nor two features' common
    /// perpendicular (vertices, ball centres, edges, capsule axes): edges crossing inside a
    /// face's outline, a cylinder against anything but a face, a non-convex mesh's triangle
    /// (see `contact/rows.rs`).
    pub held_normal: Vec<usize>,
    /// The energy safeguard scaled this step's impulse
    /// ([`ContactStats::scaled`](super::contact::ContactStats::scaled)): the scaled impulse no
    /// longer meets the targets the linearisation holds, so that step's derivatives are not
    /// reliable (nor is the velocity projection onto the loops that follows it differentiated).
    pub scaled: bool,
}

/// Whether every entry of these matrices is finite.
fn finite(ms: &[&DMatrix<f64>]) -> bool {
    ms.iter().all(|m| m.iter().all(|x| x.is_finite()))
}

/// `out ← M̃⁻¹ out` column by column, from the factor in `data`.
fn minv_columns(data: &Data, out: &mut DMatrix<f64>) {
    let L = data.chol.as_slice();
    for mut c in out.column_iter_mut() {
        let x = c.as_mut_slice();
        ltl_solve_transposed(L, &data.dof_parent, x);
        ltl_solve_lower(L, &data.dof_parent, x);
    }
}

impl<C: Control> Simulator<C> {
    /// The derivatives of one [`step`](Self::step) from the current state, `∂(q⁺, v⁺)/∂(q, v, τ)`
    /// (see the module documentation of `simulation/step_derivatives.rs` for the equations), without stepping:
    /// the state, the time and the contacts' memory (warm starts, impacts) are left as they
    /// were. For a simulator with collision geometry or unilateral limits (the time-stepping
    /// scheme); the torque is the control law's, held as an input.
    ///
    /// ```
    /// use rigid::collision::{CollisionModel, Geometry, Ground, Shape};
    /// use rigid::mass::{RotationalInertia, SpatialInertia};
    /// use rigid::multibody::{JointId, JointType, ModelBuilder};
    /// use rigid::simulation::{ContactMode, Controller, Integrator, SimulationOptions, Simulator};
    /// use rigid::spatial::{Transform, Vec3};
    /// // a 1 kg box resting on the ground
    /// let g = SpatialInertia::from_com(1.0, Vec3::zeros(), RotationalInertia::diagonal(0.01, 0.01, 0.01));
    /// let mut b = ModelBuilder::new("box");
    /// b.add_joint(None, "box", JointType::FreeFlyer, Transform::identity(), g).unwrap();
    /// let model = b.build().unwrap();
    /// let mut cm = CollisionModel::new(Ground::horizontal(0.0, 0.8));
    /// let shape = Shape::Box { size: Vec3::new(0.2, 0.2, 0.2) };
    /// cm.geometries.push(Geometry::new("box", Some(JointId(0)), Transform::identity(), shape));
    /// let opts = SimulationOptions { integrator: Integrator::SemiImplicitEuler, ..Default::default() };
    /// let q0 = [0.0, 0.0, 0.1, 0.0, 0.0, 0.0, 1.0];
    /// let mut sim = Simulator::new(&model, &q0, &[0.0; 6], opts, Controller::none(&model))?
    ///     .with_collision(cm)?;
    /// let d = sim.step_derivatives()?;
    /// assert!(d.modes.iter().any(|m| *m == ContactMode::Sticking));
    /// // a small push along x is held by friction, a small push up only lightens the contact:
    /// // the box does not move; a small torque about z turns it neither
    /// assert!(d.dv_dtau[(3, 3)].abs() < 1e-9 && d.dv_dtau[(5, 5)].abs() < 1e-9);
    /// assert!(d.dv_dtau[(2, 2)].abs() < 1e-9);
    /// # Ok::<(), rigid::simulation::SimulationError>(())
    /// ```
    ///
    /// # Errors
    /// [`SimulationError::NotDifferentiable`] for a simulator without contacts or limits (not
    /// the time-stepping scheme) or with a control law that is not open-loop;
    /// [`SimulationError::Diverged`] for a non-finite result; an algorithm's error (a model
    /// whose joints the analytical derivatives do not cover).
    pub fn step_derivatives(&mut self) -> Result<StepDerivatives, SimulationError> {
        let Some(stepper) = &self.contact else {
            return Err(SimulationError::NotDifferentiable(
                "only the time-stepping scheme is differentiated: give the simulator collision \
                 geometry or unilateral limits",
            ));
        };
        if !self.dynamics.control.open_loop() {
            return Err(SimulationError::NotDifferentiable(
                "the control law's dependence on (q, v) is not differentiated: give the torque \
                 as an input (OpenLoop, or Controller with ControlLaw::None)",
            ));
        }
        let cs: &mut ContactStepper = self
            .derivative_stepper
            .get_or_insert_with(|| stepper.clone());
        cs.solver.copy_memory(&stepper.solver);
        cs.settings = stepper.settings;
        if let (Some((_, to)), Some((_, from))) = (&mut cs.collision, &stepper.collision) {
            to.copy_warm_from(from);
        }
        let (q, v) = (self.q.clone(), self.v.clone());
        let d = &mut self.dynamics;
        let (nq, nv) = (d.model.nq, d.model.nv);
        let h = d.options.dt;
        let (mut q1, mut v1) = (vec![0.0; nq], vec![0.0; nv]);
        contact_step(d, cs, self.t, h, &q, &v, &mut q1, &mut v1)?;
        let model = &d.model;
        let data = &d.data; // M̃'s factor, from the step
        let mut scratch = Data::new(model);
        let n3 = 3 * nv;

        // 1. the free velocity's partials, E = [E_q | E_v | E_τ] at δλ = 0
        let (mut tq, mut tv) = (vec![0.0; nv], vec![0.0; nv]);
        d.passive_partials(&q, &v, &mut tq, &mut tv);
        let mut turn = vec![0.0; nv];
        world_aligned_turn(model, &v, h, &mut turn);
        let vp = &cs.v_plus;
        let a_plus: Vec<f64> = (0..nv).map(|k| (vp[k] - v[k] - turn[k]) / h).collect();
        let (mut rq, mut rv) = {
            let r = if d.has_fext {
                rnea_derivatives_with_external(model, &mut scratch, &q, &v, &a_plus, &d.fext)?
            } else {
                rnea_derivatives(model, &mut scratch, &q, &v, &a_plus)?
            };
            (r.dtau_dq.clone(), r.dtau_dv.clone())
        };
        let lone: Vec<usize> = cs.free.first_dofs().collect();
        for &f in &lone {
            rv.rows_mut(f, 6).fill(0.0); // the midpoint rule's, below
        }
        for k in 0..nv {
            rq[(k, k)] -= tq[k];
            rv[(k, k)] -= tv[k];
        }
        let collision = cs.collision.as_ref();
        let radius = |g: usize| collision.map_or(0.0, |(_, cd)| cd.ball_radius(g));
        let solver = &cs.solver;
        let turns: Vec<Turn> = collision.map_or(Vec::new(), |(_, cd)| {
            let points = solver.points.iter().enumerate();
            points.map(|(k, c)| cd.turn(k, c)).collect()
        });
        let geometry = (&radius as &dyn Fn(usize) -> f64, turns.as_slice());
        let m = solver.m();
        let lambda = &solver.lambda[..m];
        // the contact bodies at (q, v⁺): their Jacobians serve every force partial below
        let at_vp = solver.rows_at(model, &mut scratch, &q, vp, geometry)?;
        let mut p = DMatrix::zeros(nv, nv);
        solver.force_dq(&at_vp, model, lambda, &mut p);
        // the bilateral rows lead, in the constraints' row order (at q: before the projection)
        let mb = solver.bilateral_rows;
        let bilateral = |x: &[f64], l: &[f64], scratch: &mut Data| match &d.loops {
            Some(lp) if mb > 0 => {
                velocity_level_partials(model, scratch, &lp.cdata, &q, x, &l[..mb]).map(Some)
            }
            _ => Ok(None),
        };
        let bilateral_v = bilateral(vp, lambda, &mut scratch)?;
        if let Some((_, pb)) = &bilateral_v {
            p += pb;
        }
        let mut e = DMatrix::zeros(nv, n3);
        {
            let mut eq = -rq * h + &p;
            minv_columns(data, &mut eq);
            e.columns_mut(0, nv).copy_from(&eq);
            let mut ev = -rv * h;
            minv_columns(data, &mut ev);
            let mut base = DMatrix::identity(nv, nv);
            for j in model.joints() {
                if j.kind == JointType::FreeFlyer && !lone.contains(&j.idx_v) {
                    // T = h ω × v_lin
                    let i = j.idx_v;
                    let w = Vec3::new(v[i], v[i + 1], v[i + 2]);
                    let l = Vec3::new(v[i + 3], v[i + 4], v[i + 5]);
                    let mut b = base.view_mut((i + 3, i), (3, 6));
                    b.columns_mut(0, 3).copy_from(&(-l.cross_matrix() * h));
                    let mut bl = b.columns_mut(3, 3);
                    bl += w.cross_matrix() * h;
                }
            }
            cs.free.velocity_jacobian(&v, h, &mut base);
            e.columns_mut(nv, nv).copy_from(&(base + ev));
            let mut et = DMatrix::identity(nv, nv) * h;
            minv_columns(data, &mut et);
            e.columns_mut(2 * nv, nv).copy_from(&et);
        }

        // 2. the impulses
        let mut jm = DMatrix::zeros(0, 0);
        solver.dense_jacobian(&mut jm);
        let mut w = jm.transpose();
        minv_columns(data, &mut w);
        let g = &jm * &w;
        let diverged = SimulationError::Diverged { time: self.t + h };
        if !finite(&[&e, &jm, &g]) {
            return Err(diverged);
        }
        let mut dv_plus = e.clone();
        let (mut modes, mut at_switch, mut held_normal) = (Vec::new(), Vec::new(), Vec::new());
        if m > 0 {
            let mut c = DMatrix::zeros(m, nv);
            solver.rows_dq(&at_vp, nv, &mut c);
            if let Some((cb, _)) = &bilateral_v {
                c.rows_mut(0, mb).copy_from(cb);
            }
            let rows = classify(solver, lambda, &mut modes, &mut at_switch);
            // the pushing contacts whose normal's turn is not followed (an edge across an
            // edge, a capsule's side, a cylinder's rim, a mesh's triangle)
            for (i, c) in solver.points.iter().enumerate() {
                let held =
                    c.geometries.1.is_some() && turns.get(i).is_none_or(|t| *t == Turn::Held);
                if held && modes[i] != ContactMode::Separated {
                    held_normal.push(i);
                }
            }
            let mut t = DMatrix::zeros(m, n3);
            let mut rebound = false;
            for (r, row) in rows.iter().enumerate() {
                match target_of(row) {
                    Some(Target::Gap { open, closed }) => {
                        gap_target(&mut t, r, &jm, h, open, closed)
                    }
                    Some(Target::Rebound(er)) => {
                        rebound = true;
                        let x = jm.row(r) * (-er);
                        t.view_mut((r, nv), (1, nv)).copy_from(&x);
                    }
                    _ => {}
                }
            }
            if rebound {
                let mut cv = DMatrix::zeros(m, nv);
                let at_v = solver.rows_at(model, &mut scratch, &q, &v, geometry)?;
                solver.rows_dq(&at_v, nv, &mut cv);
                for (r, row) in rows.iter().enumerate() {
                    if let Some(Target::Rebound(er)) = target_of(row) {
                        let x = cv.row(r) * (-er);
                        t.view_mut((r, 0), (1, nv)).copy_from(&x);
                    }
                }
            }
            let mut je = &jm * &e;
            let mut jq = je.columns_mut(0, nv);
            jq += &c;
            let dl = solve_rows(&rows, (&g, &je, &t), nv);
            dv_plus += &w * dl;
        }

        // 3. the position correction; with bilateral rows always (an error within the
        // projection's tolerance asks none, but any perturbation of q leaves that band)
        let mut dw = DMatrix::zeros(nv, nv);
        let beta = cs.settings.stabilization;
        // a pushing contact or limit touching (φ = 0, within round-off) is taken on the side
        // where the gap closed: the correction takes β of any penetration a perturbation makes
        let lscale = lambda.iter().fold(0.0_f64, |a, x| a.max(x.abs()));
        let pushing = |r: usize| lambda[r] > 1e-12 * lscale;
        let touching = |b: &Block| !b.bilateral && at_zero(b.gap) && pushing(b.row);
        let corrects =
            cs.dq.iter().any(|x| *x != 0.0) || mb > 0 || solver.blocks.iter().any(touching);
        if corrects && beta > 0.0 {
            let mu = &solver.mu[..m];
            let wc: Vec<f64> = cs.dq.iter().map(|x| x / h).collect();
            let zeros = vec![0.0; nv];
            let dmw = rnea_derivatives(&d.free, &mut scratch, &q, &zeros, &wc)?
                .dtau_dq
                .clone();
            let mut pm = DMatrix::zeros(nv, nv);
            solver.force_dq(&at_vp, model, mu, &mut pm);
            let bilateral_w = bilateral(&wc, mu, &mut scratch)?;
            if let Some((_, pb)) = &bilateral_w {
                pm += pb;
            }
            let mut ew = pm - dmw;
            minv_columns(data, &mut ew);
            let mut cw = DMatrix::zeros(m, nv);
            let at_w = solver.rows_at(model, &mut scratch, &q, &wc, geometry)?;
            solver.rows_dq(&at_w, nv, &mut cw);
            if let Some((cb, _)) = &bilateral_w {
                cw.rows_mut(0, mb).copy_from(cb);
            }
            let mut rows = vec![Row::Free; m];
            let mut t = DMatrix::zeros(m, nv);
            // the bilateral rows aim at −β e/h, `∂e/∂q = J` (at e = 0)
            for r in (0..mb).filter(|&r| !solver.bilateral_idle[r]) {
                rows[r] = Row::Equal(Target::gap(beta));
                gap_target(&mut t, r, &jm, h, beta, beta);
            }
            // a contact row pushes in the correction (μ > 0), or may as soon as a perturbation
            // moves the correction: one whose row meets its target (`J w = σ*`; every row
            // not penetrating when nothing was corrected) is a switch, pushing only if the
            // correction would press it in; touching at φ = 0, it takes β of the penetration
            // a perturbation makes and none of an opening
            let ran = cs.dq.iter().any(|x| *x != 0.0);
            let wscale = solver.sigma_mu[..m]
                .iter()
                .chain(&solver.target_mu[..m])
                .fold(1e-300_f64, |a, x| a.max(x.abs()));
            let tight = |r: usize| {
                !ran || (solver.sigma_mu[r] - solver.target_mu[r]).abs() <= 1e-9 * wscale
            };
            for b in solver.blocks.iter().filter(|b| !b.bilateral) {
                let (open, closed) = if at_zero(b.gap) {
                    (0.0, beta)
                } else if b.gap < 0.0 {
                    (beta, beta)
                } else {
                    (0.0, 0.0)
                };
                let target = Target::Gap { open, closed };
                if mu[b.row] > 0.0 {
                    rows[b.row] = Row::Equal(target);
                } else if tight(b.row) {
                    rows[b.row] = Row::Switch {
                        target,
                        tangents: 0,
                        slide: None,
                    };
                } else {
                    continue;
                }
                gap_target(&mut t, b.row, &jm, h, open, closed);
            }
            let je = &jm * &ew + cw;
            let dmu = solve_rows(&rows, (&g, &je, &t), nv);
            dw = ew + &w * dmu;
        }
        // δv_step = δv⁺ + δw (q columns)
        let mut dvs = dv_plus.clone();
        {
            let mut x = dvs.columns_mut(0, nv);
            x += &dw;
        }

        // 4. the configuration update
        let (mut dq_out, dv_out) = update_partials(model, &cs.v_step, vp, h, &dvs, &dv_plus);
        // 5. the projection onto the constraint manifold: at its solution, the tangent
        // projector in the metric of M, I − M⁻¹Jᵀ(J M⁻¹ Jᵀ)⁺ J (∂e/∂q = J at e = 0)
        if let Some(l) = d.loops.as_mut().filter(|l| l.options.project) {
            let velocity = cs.solver.stats.scaled;
            l.project(model, &mut d.data, &mut q1, &mut v1, velocity)?;
            let projector = loop_projector(model, &mut d.data, &l.cdata, &q1)?;
            dq_out = projector * dq_out;
        }
        if !finite(&[&dq_out, &dv_out]) || !q1.iter().chain(&v1).all(|x| x.is_finite()) {
            return Err(diverged);
        }
        Ok(StepDerivatives {
            dq_dq: dq_out.columns(0, nv).into_owned(),
            dq_dv: dq_out.columns(nv, nv).into_owned(),
            dq_dtau: dq_out.columns(2 * nv, nv).into_owned(),
            dv_dq: dv_out.columns(0, nv).into_owned(),
            dv_dv: dv_out.columns(nv, nv).into_owned(),
            dv_dtau: dv_out.columns(2 * nv, nv).into_owned(),
            q_next: q1,
            v_next: v1,
            modes,
            at_switch,
            held_normal,
            contacts: cs.solver.points.clone(),
            scaled: cs.solver.stats.scaled,
        })
    }
}

/// Step 4's partials: `∂q⁺` (tangent at `q⁺`) and the velocity carried to the new axes, from
/// `δv_step` (`dvs`) and `δv⁺` (`dv_plus`), each `nv x 3nv`, `vs` and `vp` the step's `v_step`
/// and `v⁺` (see the [module](self)'s step 4).
fn update_partials(
    model: &crate::multibody::Model,
    vs: &[f64],
    vp: &[f64],
    h: f64,
    dvs: &DMatrix<f64>,
    dv_plus: &DMatrix<f64>,
) -> (DMatrix<f64>, DMatrix<f64>) {
    let (nv, n3) = (model.nv, dvs.ncols());
    let mut dq_out = DMatrix::zeros(nv, n3);
    let mut dv_out = dv_plus.clone();
    let (mut bq, mut bv) = (Mat6::zeros(), Mat6::zeros());
    for j in model.joints() {
        let (i, n) = (j.idx_v, j.nv);
        if j.kind == JointType::FreeFlyer {
            let wv = Vec3::new(vs[i], vs[i + 1], vs[i + 2]);
            let lin = Vec3::new(vs[i + 3], vs[i + 4], vs[i + 5]);
            let rt: Mat3 = so3::exp(&(wv * h)).transpose();
            let jr: Mat3 = se3_right_jacobian(&Twist::new(wv * h, Vec3::zeros()))
                .fixed_view::<3, 3>(0, 0)
                .into_owned();
            let hjr = jr * h;
            let up = [
                Vec3::new(vp[i], vp[i + 1], vp[i + 2]),
                Vec3::new(vp[i + 3], vp[i + 4], vp[i + 5]),
            ];
            let at = |m: &DMatrix<f64>, o: usize, col: usize| {
                Vec3::new(m[(o, col)], m[(o + 1, col)], m[(o + 2, col)])
            };
            for col in 0..n3 {
                // the q-column's own δθ, δp (zero off this joint and for v, τ)
                let mut e6 = [0.0; 6];
                if (i..i + 6).contains(&col) {
                    e6[col - i] = 1.0;
                }
                let (dth, dp) = (
                    Vec3::new(e6[0], e6[1], e6[2]),
                    Vec3::new(e6[3], e6[4], e6[5]),
                );
                let (dws, dls) = (at(dvs, i, col), at(dvs, i + 3, col));
                let th1 = rt * dth + hjr * dws;
                let p1 = rt * (dp - lin.cross(&dth) * h + dls * h);
                for k in 0..3 {
                    dq_out[(i + k, col)] = th1[k];
                    dq_out[(i + 3 + k, col)] = p1[k];
                }
                for (half, u) in up.iter().enumerate() {
                    let o = i + 3 * half;
                    let x = rt * at(dv_plus, o, col) + (rt * u).cross(&(hjr * dws));
                    for k in 0..3 {
                        dv_out[(o + k, col)] = x[k];
                    }
                }
            }
        } else {
            j.kind
                .integrate_jacobians(&vs[i..i + n], h, &mut bq, &mut bv);
            let x = bv.view((0, 0), (n, n)) * dvs.rows(i, n);
            dq_out.rows_mut(i, n).copy_from(&x);
            let mut diag = dq_out.view_mut((i, i), (n, n));
            diag += bq.view((0, 0), (n, n));
        }
    }
    (dq_out, dv_out)
}

/// Step 5's projector onto the loops at `q` (`cd` their rows there): the tangent projector in
/// the metric of `M`, `I − M⁻¹ J_Bᵀ (J_B M⁻¹ J_Bᵀ)⁺ J_B`.
fn loop_projector(
    model: &crate::multibody::Model,
    data: &mut Data,
    cd: &crate::multibody::constraints::ConstraintData,
    q: &[f64],
) -> Result<DMatrix<f64>, SimulationError> {
    let nv = model.nv;
    crba(model, data, q)?;
    ltl_factor(model, data)?;
    let mut jb = DMatrix::zeros(cd.dim(), nv);
    for i in 0..cd.constraints.len() {
        for r in cd.rows_of(i) {
            for &(k, _, _) in &cd.support[i].cols {
                jb[(r, k)] = cd.jacobian[(r, k)];
            }
        }
    }
    let mut wb = jb.transpose();
    minv_columns(data, &mut wb);
    let gb = &jb * &wb;
    let tol = 1e-10 * gb.amax().max(1e-300);
    let gp = gb
        .pseudo_inverse(tol)
        .unwrap_or_else(|_| DMatrix::zeros(cd.dim(), cd.dim()));
    Ok(DMatrix::identity(nv, nv) - wb * gp * jb)
}
