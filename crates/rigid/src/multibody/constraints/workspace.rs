//! The workspace of the constrained algorithms, made once per (model, constraint set).

use super::kinematics::ConstraintPlacement;
use super::{ConstraintError, ConstraintModel, SolverStats};
use crate::multibody::{JointType, Model};
use nalgebra::{DMatrix, DVector};

/// One constraint's columns of `J`: the dofs that move c1 or c2 (the chains of joint1 and
/// joint2 to the root), ascending, each with the chains it is on.
#[derive(Clone, Debug)]
pub(crate) struct Support {
    /// `(dof, on joint1's chain, on joint2's chain)`.
    pub cols: Vec<(usize, bool, bool)>,
}

/// The constraint set and every buffer of [`constraint_dynamics`](super::constraint_dynamics),
/// [`impulse_dynamics`](super::impulse_dynamics) and
/// [`contact_inverse_dynamics`](super::contact_inverse_dynamics): Pinocchio's
/// `initConstraintDynamics` and its vector of `RigidConstraintData`. Results are in the public
/// fields; `λ` and impulses hold 3, 6 or 1 numbers per constraint in the set's order (a wrench
/// moment first, as everywhere in rigid).
#[derive(Clone, Debug)]
pub struct ConstraintData {
    pub(crate) constraints: Vec<ConstraintModel>,
    /// First row of each constraint, and the total at the end (length `n + 1`).
    pub(crate) rows: Vec<usize>,
    pub(crate) support: Vec<Support>,
    nv: usize,
    njoints: usize,
    /// Each constraint's frames `oMc1`, `oMc2` and `c1Mc2` at the last `q`.
    pub placements: Vec<ConstraintPlacement>,
    /// The constraint Jacobian `J` (m x nv) at the last `q`.
    pub jacobian: DMatrix<f64>,
    /// The drift `γ` (m) of the last [`constraint_dynamics`](super::constraint_dynamics):
    /// `J q̈ + γ = 0`, `γ = J̇ q̇ + kp e + kd ė` (Pinocchio's `-primal_rhs_contact`).
    pub gamma: DVector<f64>,
    /// The constraint error `e` (m) at the `q` of the last forward or inverse dynamics (and
    /// of each simulator step): `−c1Mc2.translation`, `−log(c1Mc2)` or `q_1 − p(q_2)`, in the
    /// constraint's reference frame.
    pub error: DVector<f64>,
    /// The constraint velocity `J q̇` (m) at the last `(q, q̇)` (`J q̇⁻` after an impulse).
    pub velocity: DVector<f64>,
    /// `q̈` of [`constraint_dynamics`](super::constraint_dynamics).
    pub ddq: DVector<f64>,
    /// `λ` (m) of [`constraint_dynamics`](super::constraint_dynamics) and
    /// [`contact_inverse_dynamics`](super::contact_inverse_dynamics).
    pub lambda: DVector<f64>,
    /// `q̇⁺` of [`impulse_dynamics`](super::impulse_dynamics).
    pub dq_plus: DVector<f64>,
    /// The impulse `Λ` (m) of [`impulse_dynamics`](super::impulse_dynamics) (N·s, N·m·s).
    pub impulse: DVector<f64>,
    /// `τ` of [`contact_inverse_dynamics`](super::contact_inverse_dynamics).
    pub tau: DVector<f64>,
    /// What the last solve did.
    pub stats: SolverStats,
    /// The unactuated degrees of freedom of the inverse dynamics (`true`: no torque).
    pub(crate) unactuated: Vec<bool>,
    // --- buffers ---
    /// `Z = L⁻ᵀ Jᵀ` (nv x m), zero outside each constraint's support.
    pub(crate) z: DMatrix<f64>,
    /// The Delassus matrix `K = J M⁻¹ Jᵀ = Zᵀ Z` (m x m).
    pub(crate) delassus: DMatrix<f64>,
    /// The Cholesky factor of `K + μ I` (lower), or of the inverse dynamics' Gram matrix (nv x nv).
    pub(crate) chol: DMatrix<f64>,
    pub(crate) gram: DMatrix<f64>,
    /// `LᵀL` of the pivoted factor of the inverse dynamics (nv x nv) and its pivots.
    pub(crate) normal: DMatrix<f64>,
    pub(crate) perm: Vec<usize>,
    /// `w = L⁻ᵀ (τ − nle)` (nv).
    pub(crate) w: DVector<f64>,
    /// The right-hand side `b` of `K λ = b` (m).
    pub(crate) b: DVector<f64>,
    pub(crate) prev: DVector<f64>,
    pub(crate) y: DVector<f64>,
}

impl ConstraintData {
    /// The workspace of `constraints` on `model`: checks every constraint (joints in range,
    /// rigid placements, gains, one-dof joints for joint coordinates) and allocates every buffer.
    /// The free-flyer joints' dofs are unactuated for [`contact_inverse_dynamics`](super::contact_inverse_dynamics)
    /// ([`set_unactuated`](Self::set_unactuated) changes it).
    ///
    /// # Errors
    /// The first bad constraint, named by its position.
    pub fn new(model: &Model, constraints: &[ConstraintModel]) -> Result<Self, ConstraintError> {
        let mut rows = vec![0];
        for (i, c) in constraints.iter().enumerate() {
            c.check(model, i)?;
            rows.push(rows[i] + c.dim());
        }
        let m = rows[constraints.len()];
        let nv = model.nv();
        let support = constraints
            .iter()
            .map(|c| support(model, c.joint1, c.joint2))
            .collect();
        let unactuated = (0..nv)
            .map(|k| model.joint(model.dof_joint(k)).kind == JointType::FreeFlyer)
            .collect();
        Ok(Self {
            constraints: constraints.to_vec(),
            rows,
            support,
            nv,
            njoints: model.njoints(),
            placements: vec![ConstraintPlacement::default(); constraints.len()],
            jacobian: DMatrix::zeros(m, nv),
            gamma: DVector::zeros(m),
            error: DVector::zeros(m),
            velocity: DVector::zeros(m),
            ddq: DVector::zeros(nv),
            lambda: DVector::zeros(m),
            dq_plus: DVector::zeros(nv),
            impulse: DVector::zeros(m),
            tau: DVector::zeros(nv),
            stats: SolverStats::default(),
            unactuated,
            z: DMatrix::zeros(nv, m),
            delassus: DMatrix::zeros(m, m),
            chol: DMatrix::zeros(m.max(nv), m.max(nv)),
            gram: DMatrix::zeros(nv, nv),
            normal: DMatrix::zeros(nv, nv),
            perm: vec![0; nv],
            w: DVector::zeros(nv),
            b: DVector::zeros(m.max(nv)),
            prev: DVector::zeros(m.max(nv)),
            y: DVector::zeros(nv),
        })
    }

    /// The constraints, in order.
    #[must_use]
    pub fn constraints(&self) -> &[ConstraintModel] {
        &self.constraints
    }

    /// The total number of rows `m` (3, 6 or 1 per constraint).
    #[must_use]
    pub fn dim(&self) -> usize {
        self.rows[self.constraints.len()]
    }

    /// The rows of constraint `i` in `λ`, `J`, `γ` and the impulse.
    #[must_use]
    pub fn rows_of(&self, i: usize) -> std::ops::Range<usize> {
        self.rows[i]..self.rows[i + 1]
    }

    /// Per-constraint numbers (`λ`, an impulse, `γ`; `dim()` of them) in Pinocchio's order: each
    /// frame constraint's `(m, f)` written `(f, m)`, linear first; the others as they are
    /// (`out[r] = x[source_row(r, true)]`).
    ///
    /// # Panics
    /// If `x` or `out` is shorter than [`dim`](Self::dim).
    pub fn force_first(&self, x: &[f64], out: &mut [f64]) {
        for (r, o) in out[..self.dim()].iter_mut().enumerate() {
            *o = x[self.source_row(r, true)];
        }
    }

    /// The row of rigid's order (a wrench moment first) that row `r` of the output takes: `r`
    /// itself, or with `force_first` (Pinocchio's order) the other half of a frame constraint's
    /// six rows. The one home of that order for vectors ([`force_first`](Self::force_first))
    /// and for matrices of constraint rows (`J`, `∂λ/∂q`, …).
    ///
    /// # Panics
    /// If `r >= dim()`.
    #[must_use]
    pub fn source_row(&self, r: usize, force_first: bool) -> usize {
        let c = self.rows.partition_point(|&start| start <= r) - 1;
        match self.constraints[c].kind {
            super::ConstraintKind::Frame if force_first => {
                let start = self.rows[c];
                start + (r - start + 3) % 6
            }
            _ => r,
        }
    }

    /// The largest constraint error `‖e‖∞` ([`error`](Self::error)), m or rad.
    #[must_use]
    pub fn violation(&self) -> f64 {
        self.error.amax()
    }

    /// Marks which degrees of freedom have no actuator for
    /// [`contact_inverse_dynamics`](super::contact_inverse_dynamics) (`true`: no torque; default:
    /// the free-flyer joints' six).
    ///
    /// # Errors
    /// [`ConstraintError::BadActuation`] when `unactuated.len() != nv`.
    pub fn set_unactuated(&mut self, unactuated: &[bool]) -> Result<(), ConstraintError> {
        if unactuated.len() != self.nv {
            return Err(ConstraintError::BadActuation {
                got: unactuated.len(),
                nv: self.nv,
            });
        }
        self.unactuated.copy_from_slice(unactuated);
        Ok(())
    }

    /// The unactuated degrees of freedom.
    #[must_use]
    pub fn unactuated(&self) -> &[bool] {
        &self.unactuated
    }

    pub(crate) fn check_model(&self, model: &Model) -> Result<(), ConstraintError> {
        if self.nv != model.nv() || self.njoints != model.njoints() {
            return Err(ConstraintError::DataMismatch);
        }
        Ok(())
    }
}

/// The dofs on the chains from joint1 and joint2 to their roots, ascending, with which chain
/// each is on (both: a common ancestor).
fn support(
    model: &Model,
    j1: Option<crate::multibody::JointId>,
    j2: Option<crate::multibody::JointId>,
) -> Support {
    let chain = |j: Option<crate::multibody::JointId>| {
        let mut on = vec![false; model.nv()];
        let mut j = j;
        while let Some(i) = j {
            let joint = model.joint(i);
            on[joint.dofs()].iter_mut().for_each(|x| *x = true);
            j = joint.parent;
        }
        on
    };
    let (on1, on2) = (chain(j1), chain(j2));
    Support {
        cols: (0..model.nv())
            .filter(|&k| on1[k] || on2[k])
            .map(|k| (k, on1[k], on2[k]))
            .collect(),
    }
}
