//! The time-stepping scheme with contacts and unilateral joint limits (Moreau–Jean; Stewart &
//! Trinkle 1996; Anitescu & Potra 1997), the equations in
//! [`simulation::contact`](crate::simulation::contact):
//!
//! 1. `v_f = v_k + h M⁻¹ (τ(t_k, q_k, v_k) − c − g + Σ Jᵢᵀ Fᵢ)`: symplectic Euler's free velocity
//!    (the factor `M = LᵀL` kept for step 3). A controller's PD part (`K_p`, `K_d`,
//!    [`Control::pd_gains`]) is linearly implicit, as MuJoCo's implicit damping: `M` becomes
//!    `M̃ = M + h K_d + h² K_p` and the force `τ − c − g − h K_p v` (the backward-Euler
//!    linearisation of `K_p (q* ⊖ q⁺) − K_d v⁺`), so that stiff gains on light joints (an ankle
//!    that carries a humanoid, [`ControlLaw::stance`](super::ControlLaw::stance)) do not need a
//!    smaller step; the contact problem of step 3 is then posed on `M̃`;
//! 2. the bilateral constraints' rows at `q_k` (closed loops, welds: [`loops`](super::loops)),
//!    the contacts at `q_k` (collision geometry, parry) and the joints at or near a limit;
//! 3. the impulses `λ` of the one problem over their shared Delassus rows (bilateral rows
//!    `J_B v⁺ = 0`, the contacts' Signorini–Coulomb), `v_{k+1} = v_f + M⁻¹ Jᵀ λ`;
//! 4. `q_{k+1} = q_k ⊕ h v_{k+1} ⊕ δq`, with `δq` the position correction of any penetration
//!    and constraint error.
//!
//! First order in `h`, as MuJoCo's Euler and Pinocchio's simulators are; the smooth forces are
//! those of the other integrators (control, joint damping and friction, limit springs, external
//! wrenches).
//!
//! A lone free body (a free-flyer root with no child) takes its free velocity of step 1 from
//! [`free_body`](super::free_body) instead: the implicit midpoint on its gyroscopic term, which
//! keeps a passive body's energy.
//!
//! A free-flyer joint is stepped on SO(3) × R³ with its velocity in world-aligned axes over the
//! step (as MuJoCo's free joint), by the joint module
//! ([`JointType::integrate_world_aligned`](crate::multibody::JointType)).

use super::control::Control;
use super::free_body::FreeBodies;
use super::simulator::Dynamics;
use super::{JointLimits, SimulationError};
#[cfg(feature = "collision")]
use crate::collision::ContactPoint;
use crate::multibody::algorithms::{ltl_factor, ltl_solve_lower, ltl_solve_transposed};
use crate::multibody::configuration::{integrate_world_aligned, world_aligned_turn};
use crate::multibody::constraints::constraint_rows;
use crate::multibody::{
    compute_joint_jacobians, crba, nonlinear_effects, rnea_with_external, Model,
};
use crate::simulation::contact::{ContactSettings, ContactSolver, ContactStats};
use crate::spatial::Vec3;

/// How near a joint limit (rad or m) a joint enters the step's problem beyond what its speed
/// reaches in two steps: the position correction moves joints too (a foot pressed out of the
/// ground moves the leg), and a limit left out of the problem would be crossed.
const LIMIT_MARGIN: f64 = 1e-3;

/// How far above its surface (m) a contact point enters the step's problem beyond what its
/// approach speed closes in two steps: a body resting on one point of a rounded foot does not
/// carry the rim of its resting face (points 0.5 mm up, 5 mm away) as rows of the problem,
/// which no speed reached in a step would close; the position correction, which turns the
/// bodies, moves points by less.
#[cfg(feature = "collision")]
const CONTACT_SLACK: f64 = 1e-4;

/// The contact part of a simulator: the solver's workspace, the collision geometry and its
/// workspace, and the results of the last step.
#[derive(Clone, Debug)]
pub(crate) struct ContactStepper {
    pub(crate) solver: ContactSolver,
    pub(crate) settings: ContactSettings,
    #[cfg(feature = "collision")]
    pub(crate) collision: Option<(
        crate::collision::CollisionModel,
        crate::collision::CollisionData,
    )>,
    #[cfg(feature = "collision")]
    points: Vec<ContactPoint>,
    a: Vec<f64>,
    pub(crate) v_step: Vec<f64>,
    /// The velocity after the contact impulses, before the world-aligned update turns the
    /// free-flyers' part to their new axes.
    pub(crate) v_plus: Vec<f64>,
    pub(crate) dq: Vec<f64>,
    zeros: Vec<f64>,
    /// The lone free bodies, stepped by the implicit midpoint ([`free_body`](super::free_body)).
    pub(crate) free: FreeBodies,
    /// The energy the contact impulses took since the start (J): minus the sum of their work
    /// ([`ContactStats::work`]).
    pub(crate) dissipated: f64,
}

impl ContactStepper {
    pub(crate) fn new(model: &Model) -> Self {
        let nv = model.nv();
        Self {
            solver: ContactSolver::new(model),
            settings: ContactSettings::default(),
            #[cfg(feature = "collision")]
            collision: None,
            #[cfg(feature = "collision")]
            points: Vec::new(),
            a: vec![0.0; nv],
            v_step: vec![0.0; nv],
            v_plus: vec![0.0; nv],
            dq: vec![0.0; nv],
            zeros: vec![0.0; nv],
            free: FreeBodies::new(model),
            dissipated: 0.0,
        }
    }

    /// The contacts of the last step (those given to the solver: a gap under the margin that
    /// the step may close).
    #[cfg(feature = "collision")]
    pub(crate) fn contacts(&self) -> &[ContactPoint] {
        &self.solver.points
    }

    /// Their impulses on body 1 (N·s, world axes).
    pub(crate) fn impulses(&self) -> &[Vec3] {
        &self.solver.impulses
    }

    /// The last solve's numbers.
    pub(crate) fn stats(&self) -> ContactStats {
        self.solver.stats
    }
}

/// One step of `h` from `(q, v)` at `t` into `q_new`, `v_new`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn contact_step<C: Control>(
    d: &mut Dynamics<C>,
    cs: &mut ContactStepper,
    t: f64,
    h: f64,
    q: &[f64],
    v: &[f64],
    q_new: &mut [f64],
    v_new: &mut [f64],
) -> Result<(), SimulationError> {
    let nv = v.len();
    d.torques(t, q, v)?;
    let model = &d.model;
    let data = &mut d.data;
    // a = τ − c − g + Σ Jᵀ F
    if d.has_fext {
        let b = rnea_with_external(model, data, q, v, &cs.zeros, &d.fext)?;
        for k in 0..nv {
            cs.a[k] = d.tau[k] - b[k];
        }
    } else {
        let b = nonlinear_effects(model, data, q, v)?;
        for k in 0..nv {
            cs.a[k] = d.tau[k] - b[k];
        }
    }
    crba(model, data, q)?;
    cs.free.prepare(model, &data.mass_matrix, v);
    if let Some((kp, kd)) = d.control.pd_gains() {
        for k in 0..nv {
            data.mass_matrix[(k, k)] += h * kd[k] + h * h * kp[k];
            cs.a[k] -= h * kp[k] * v[k];
        }
    }
    cs.free.forces(&cs.a);
    ltl_factor(model, data)?;
    ltl_solve_transposed(data.chol.as_slice(), &data.dof_parent, &mut cs.a);
    ltl_solve_lower(data.chol.as_slice(), &data.dof_parent, &mut cs.a);
    for k in 0..nv {
        v_new[k] = v[k] + h * cs.a[k];
    }
    // free-flyers in world-aligned axes over the step: the frame's turning `−ω × v_b`, which
    // `a` holds, is not a force
    world_aligned_turn(model, v, h, v_new);
    cs.free.free_velocity(&data.mass_matrix, v, h, v_new);
    compute_joint_jacobians(model, data, q)?;
    cs.solver.clear();
    if let Some(l) = &mut d.loops {
        // the bodies' velocities and drift accelerations of the RNEA above
        constraint_rows(model, data, &mut l.cdata, q, v, true);
        cs.solver.push_bilateral(&l.cdata, l.options.tolerance);
    }
    #[cfg(feature = "collision")]
    if let Some((cm, cd)) = &mut cs.collision {
        cd.contacts(cm, &data.placements, &mut cs.points);
        // a gap this step cannot close stays out of the problem: at the speed before the step
        // or the free one it closes by h·|σ_n| (a heuristic, not a bound: the impulses of the
        // others may turn the body onto it faster, which twice that and CONTACT_SLACK more
        // cover in most cases; a point missed is pressed in for a step and pushed out)
        let solver = &cs.solver;
        cd.retain(&mut cs.points, |c| {
            if c.gap <= CONTACT_SLACK {
                return true;
            }
            let approach = |x: &[f64]| -solver.normal_speed(data, c, x);
            let closing = approach(v).max(approach(v_new)).max(0.0);
            c.gap <= 2.0 * h * closing + CONTACT_SLACK
        });
        for c in &cs.points {
            cs.solver.push_contact(data, c);
        }
    }
    if d.options.limits == JointLimits::Unilateral {
        for (j, joint) in model.joints().iter().enumerate() {
            if joint.nq != 1 || joint.nv != 1 {
                continue;
            }
            let (x, k) = (q[joint.idx_q], joint.idx_v);
            let (lo, hi) = (model.lower[joint.idx_q], model.upper[joint.idx_q]);
            // near enough to reach the limit within two steps at this speed or the free
            // velocity's, or by the position correction (which moves joints through the
            // contacts and loops: a limit left out of the problem would be crossed)
            let reach = 2.0 * h * v[k].abs().max(v_new[k].abs()) + LIMIT_MARGIN;
            let id = crate::multibody::JointId(j);
            if lo.is_finite() && x - lo <= reach {
                cs.solver.push_limit(id, k, 1.0, x - lo);
            }
            if hi.is_finite() && hi - x <= reach {
                cs.solver.push_limit(id, k, -1.0, hi - x);
            }
        }
    }
    if cs.solver.is_empty() {
        cs.v_step.copy_from_slice(v_new);
        cs.dq.fill(0.0);
    } else {
        cs.solver.solve(data, v, v_new, h, &cs.settings);
        cs.dissipated -= cs.solver.stats.work;
        cs.solver.correction(data, h, &cs.settings, &mut cs.dq);
        for k in 0..nv {
            cs.v_step[k] = v_new[k] + cs.dq[k] / h;
        }
    }
    cs.v_plus.copy_from_slice(v_new);
    integrate_world_aligned(model, q, &cs.v_step, h, q_new, v_new);
    Ok(())
}
