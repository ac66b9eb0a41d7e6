//! The analytical derivatives of the constrained and impulse dynamics (Pinocchio's
//! `computeConstraintDynamicsDerivatives` and `computeImpulseDynamicsDerivatives`), by
//! differentiating the KKT system at its solution.
//!
//! Forward dynamics: `r_1 = RNEA(q, q̇, q̈) − J(q)ᵀ λ − τ = 0` and `r_2 = J(q) q̈ + γ(q, q̇) = 0`.
//! For any input x,
//!
//! `[M  Jᵀ; J  0] [∂q̈/∂x; −∂λ/∂x] = [∂τ/∂x − ∂RNEA/∂x + ∂(Jᵀλ)/∂x; −∂r_2/∂x]`
//!
//! with the partials at fixed `(q̈, λ)`: `∂RNEA/∂q`, `∂RNEA/∂q̇` ([`rnea_derivatives`]),
//! `∂(Jᵀλ)/∂q` and `∂r_2/∂q`, `∂r_2/∂q̇` ([`partials`](super::partials)). The same Schur
//! complement as the forward solve: `∂λ = K⁻¹ (∂r̃_2 − J M⁻¹ ∂r̃_1)`,
//! `∂q̈ = M⁻¹ (∂r̃_1 + Jᵀ ∂λ)`, reusing `M = LᵀL`, `Z = L⁻ᵀJᵀ` and the factor of `K + μ I`
//! (Carpentier & Mansard, RSS 2018, §IV; Carpentier, Budhiraja & Mansard, RSS 2021).
//!
//! Impulse dynamics: `r_1 = M(q) (q̇⁺ − q̇⁻) − J(q)ᵀ Λ` and `r_2 = J(q) (q̇⁺ + e q̇⁻)`, the same
//! way with `∂(M x)/∂q = ∂RNEA(q, 0, x)/∂q − ∂g/∂q`, `∂r_1/∂q̇⁻ = −M` and `∂r_2/∂q̇⁻ = e J`.
//!
//! With redundant constraints and `μ > 0`, `λ` is the least-norm multiplier of the proximal
//! iterations, and its derivatives are those of the least-norm solution, `∂λ = K⁺ (…)` by the
//! pivoted Cholesky pseudo-inverse (iterating the proximal steps on each column instead would
//! let the round-off of the right-hand side outside `K`'s range grow `∂λ` in `K`'s null space
//! by `b_⊥/μ` per iteration).

use super::dynamics::joint_coords;
use super::partials::{force_partials, residual_rows, BodyMotion, Level};
use super::solver::{pinv_solve, primal_rows, proximal_iterations, z_transpose_times};
use super::ProximalSettings;
use super::{constraint_dynamics, impulse_dynamics, ConstraintData, ConstraintError};
use crate::multibody::algorithms::ltl_solve_transposed;
use crate::multibody::{gravity_derivatives, rnea_derivatives, Data, Model, MultibodyError};
use nalgebra::DMatrix;

/// The derivatives of [`constraint_dynamics`]' `q̈` and `λ` (q along `q ⊕ δ`), filled by
/// [`constraint_dynamics_derivatives`]: Pinocchio's `ddq_dq`, `ddq_dv`, `ddq_dtau`,
/// `dlambda_dq`, `dlambda_dv`, `dlambda_dtau` (λ's rows in rigid's order: a wrench moment
/// first).
#[derive(Clone, Debug)]
pub struct ConstraintDynamicsDerivatives {
    /// `∂q̈/∂q` (nv x nv).
    pub ddq_dq: DMatrix<f64>,
    /// `∂q̈/∂q̇` (nv x nv).
    pub ddq_dv: DMatrix<f64>,
    /// `∂q̈/∂τ` (nv x nv).
    pub ddq_dtau: DMatrix<f64>,
    /// `∂λ/∂q` (m x nv).
    pub dlambda_dq: DMatrix<f64>,
    /// `∂λ/∂q̇` (m x nv).
    pub dlambda_dv: DMatrix<f64>,
    /// `∂λ/∂τ` (m x nv).
    pub dlambda_dtau: DMatrix<f64>,
    work: Work,
}

/// The derivatives of [`impulse_dynamics`]' `q̇⁺` and impulse `Λ`, filled by
/// [`impulse_dynamics_derivatives`]. (Pinocchio's `ddq_dv` after
/// `computeImpulseDynamicsDerivatives` is `∂(q̇⁺ − q̇⁻)/∂q̇⁻ = dvplus_dv − I`.)
#[derive(Clone, Debug)]
pub struct ImpulseDynamicsDerivatives {
    /// `∂q̇⁺/∂q` (nv x nv).
    pub dvplus_dq: DMatrix<f64>,
    /// `∂q̇⁺/∂q̇⁻` (nv x nv).
    pub dvplus_dv: DMatrix<f64>,
    /// `∂Λ/∂q` (m x nv).
    pub dimpulse_dq: DMatrix<f64>,
    /// `∂Λ/∂q̇⁻` (m x nv).
    pub dimpulse_dv: DMatrix<f64>,
    work: Work,
}

/// Scratch shared by both verbs.
#[derive(Clone, Debug)]
struct Work {
    bodies: [BodyMotion; 2],
    /// `∂r_2/∂q`, `∂r_2/∂q̇` (m x nv).
    dr_dq: DMatrix<f64>,
    dr_dv: DMatrix<f64>,
    /// `∂(Jᵀλ)/∂q` (nv x nv).
    dQ: DMatrix<f64>,
    /// The point of linearisation: `q̈` (or `q̇⁺ − q̇⁻`), and `q̇` (or `q̇⁺ + e q̇⁻`).
    a: Vec<f64>,
    v: Vec<f64>,
    /// Zero (nv): the acceleration of the velocity level.
    zero: Vec<f64>,
    /// One KKT column (nv, m), and scratch (m, m).
    x: Vec<f64>,
    y: Vec<f64>,
    b: Vec<f64>,
    prev: Vec<f64>,
    /// The pseudo-inverse's scratch (m x m, m x m, m): with `μ > 0`.
    pinv: (DMatrix<f64>, DMatrix<f64>, Vec<usize>),
}

impl Work {
    fn new(nv: usize, m: usize) -> Self {
        Self {
            bodies: [BodyMotion::new(nv), BodyMotion::new(nv)],
            dr_dq: DMatrix::zeros(m, nv),
            dr_dv: DMatrix::zeros(m, nv),
            dQ: DMatrix::zeros(nv, nv),
            a: vec![0.0; nv],
            v: vec![0.0; nv],
            zero: vec![0.0; nv],
            x: vec![0.0; nv],
            y: vec![0.0; m],
            b: vec![0.0; m],
            prev: vec![0.0; m],
            pinv: (DMatrix::zeros(m, m), DMatrix::zeros(m, m), vec![0; m]),
        }
    }

    fn check(&self, cdata: &ConstraintData) -> Result<(), ConstraintError> {
        if self.dr_dq.shape() != cdata.jacobian.shape() {
            return Err(ConstraintError::DataMismatch);
        }
        Ok(())
    }

    /// Every constraint's `∂r_2/∂q` (and `∂r_2/∂q̇` at the acceleration level) into `dr_dq`,
    /// `dr_dv`, and `∂(Jᵀλ)/∂q` into `dQ`, at `(q, self.v, self.a)`.
    fn partials(
        &mut self,
        model: &Model,
        data: &mut Data,
        cdata: &ConstraintData,
        q: &[f64],
        lambda: &[f64],
        level: Level,
    ) -> Result<(), MultibodyError> {
        self.dr_dq.fill(0.0);
        self.dr_dv.fill(0.0);
        self.dQ.fill(0.0);
        let a = if level == Level::Acceleration {
            &self.a
        } else {
            &self.zero
        };
        for (i, c) in cdata.constraints.iter().enumerate() {
            let [b1, b2] = &mut self.bodies;
            b1.load(model, data, (q, &self.v, a), c.joint1)?;
            b2.load(model, data, (q, &self.v, a), c.joint2)?;
            let joints = joint_coords(model, c, q, &self.v);
            let (pl, cols, rows) = (
                &cdata.placements[i],
                &cdata.support[i].cols,
                cdata.rows_of(i),
            );
            residual_rows(
                c,
                pl,
                (b1, b2),
                joints,
                (&self.a, level),
                cols,
                rows.start,
                (&mut self.dr_dq, &mut self.dr_dv),
            );
            force_partials(
                model,
                c,
                pl,
                (b1, b2),
                joints,
                &lambda[rows],
                cols,
                &mut self.dQ,
            );
        }
        Ok(())
    }

    /// One column of the KKT system `M x − Jᵀ y = r̃_1`, `J x = r̃_2`: on entry `self.x = r̃_1`
    /// (nv), `self.y = r̃_2` (m); on return `self.x = ∂q̈` and `self.y = ∂λ`.
    fn solve(&mut self, data: &Data, cd: &ConstraintData, settings: &ProximalSettings) {
        ltl_solve_transposed(data.chol.as_slice(), &data.dof_parent, &mut self.x);
        // K y = r̃_2 − Zᵀ L⁻ᵀ r̃_1, by the forward solve's iterations on its factor of K + μ I
        z_transpose_times(cd, &self.x, &mut self.b);
        for (b, y) in self.b.iter_mut().zip(&self.y) {
            *b = y - *b;
        }
        if settings.mu > 0.0 {
            // the derivative of the least-norm λ: y = K⁺ b (the proximal iterations would
            // converge to it too, but the round-off of b outside K's range would grow y in K's
            // null space by b_⊥/μ at each iteration)
            let (c, n2, perm) = &mut self.pinv;
            pinv_solve(&cd.delassus, c, n2, perm, &self.b, &mut self.y);
        } else {
            proximal_iterations(
                &cd.delassus,
                &cd.chol,
                &self.b,
                &mut self.y,
                &mut self.prev,
                settings,
            );
        }
        let n = cd.constraints.len();
        primal_rows(
            data,
            &cd.rows[..=n],
            &cd.support[..n],
            cd.z.as_slice(),
            &self.y,
            &mut self.x,
        );
    }
}

/// `∂(J(q) w)/∂q` (m x nv) and `∂(J(q)ᵀ λ)/∂q` (nv x nv) of the constraints of `cdata` (its
/// rows and placements made at `q`): the velocity-level partials of [the module](self), for the
/// derivatives of a simulation step whose bilateral rows hold `J v⁺ = 0`.
#[cfg(feature = "collision")]
pub(crate) fn velocity_level_partials(
    model: &Model,
    data: &mut Data,
    cdata: &ConstraintData,
    q: &[f64],
    w: &[f64],
    lambda: &[f64],
) -> Result<(DMatrix<f64>, DMatrix<f64>), MultibodyError> {
    let mut work = Work::new(model.nv(), cdata.dim());
    work.v.copy_from_slice(w);
    work.partials(model, data, cdata, q, lambda, Level::Velocity)?;
    Ok((work.dr_dq, work.dQ))
}

impl ConstraintDynamicsDerivatives {
    /// The buffers for `model` and the constraint set of `cdata`.
    #[must_use]
    pub fn new(model: &Model, cdata: &ConstraintData) -> Self {
        let (nv, m) = (model.nv(), cdata.dim());
        Self {
            ddq_dq: DMatrix::zeros(nv, nv),
            ddq_dv: DMatrix::zeros(nv, nv),
            ddq_dtau: DMatrix::zeros(nv, nv),
            dlambda_dq: DMatrix::zeros(m, nv),
            dlambda_dv: DMatrix::zeros(m, nv),
            dlambda_dtau: DMatrix::zeros(m, nv),
            work: Work::new(nv, m),
        }
    }
}

impl ImpulseDynamicsDerivatives {
    /// The buffers for `model` and the constraint set of `cdata`.
    #[must_use]
    pub fn new(model: &Model, cdata: &ConstraintData) -> Self {
        let (nv, m) = (model.nv(), cdata.dim());
        Self {
            dvplus_dq: DMatrix::zeros(nv, nv),
            dvplus_dv: DMatrix::zeros(nv, nv),
            dimpulse_dq: DMatrix::zeros(m, nv),
            dimpulse_dv: DMatrix::zeros(m, nv),
            work: Work::new(nv, m),
        }
    }
}

/// [`constraint_dynamics`] at `(q, q̇, τ)` and the derivatives of its `q̈` and `λ` with respect
/// to `q` (along `q ⊕ δ`, as every derivative in rigid), `q̇` and `τ`, into `out` (see [the
/// module](self) for the equations). The derivatives are exact where the dynamics are smooth:
/// everywhere for full-rank constraints with `μ = 0`.
///
/// # Errors
/// As [`constraint_dynamics`]; a joint whose motion subspace is not constant (as the other
/// analytical derivatives); `out` made for another constraint set.
///
/// ```
/// use rigid::multibody::constraints::{constraint_dynamics_derivatives, ConstraintData,
///     ConstraintDynamicsDerivatives, ConstraintModel, ProximalSettings};
/// use rigid::multibody::{builtin, Data, JointId};
/// use rigid::spatial::{Transform, Vec3};
/// // the double pendulum's elbow held on a vertical rail through the shoulder (x = 0)
/// let model = builtin("double_pendulum").unwrap();
/// let mut data = Data::new(&model);
/// let c = ConstraintModel::point(Some(JointId(1)), Transform::identity(), None, Transform::identity());
/// let mut cdata = ConstraintData::new(&model, &[c])?;
/// let mut d = ConstraintDynamicsDerivatives::new(&model, &cdata);
/// let settings = ProximalSettings::new(1e-12, 1e-12, 100);
/// constraint_dynamics_derivatives(&model, &mut data, &mut cdata, &[0.3, -0.2], &[0.1, 0.4],
///                                 &[0.0, 0.0], &settings, &mut d)?;
/// assert_eq!(d.ddq_dq.shape(), (2, 2));
/// assert_eq!(d.dlambda_dtau.shape(), (3, 2));
/// # Ok::<(), rigid::multibody::constraints::ConstraintError>(())
/// ```
#[allow(clippy::too_many_arguments)]
pub fn constraint_dynamics_derivatives(
    model: &Model,
    data: &mut Data,
    cdata: &mut ConstraintData,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    settings: &ProximalSettings,
    out: &mut ConstraintDynamicsDerivatives,
) -> Result<(), ConstraintError> {
    out.work.check(cdata)?;
    constraint_dynamics(model, data, cdata, q, v, tau, settings)?;
    let w = &mut out.work;
    w.a.copy_from_slice(cdata.ddq.as_slice());
    w.v.copy_from_slice(v);
    let lambda = &cdata.lambda.as_slice()[..cdata.dim()];
    w.partials(model, data, cdata, q, lambda, Level::Acceleration)?;
    rnea_derivatives(model, data, q, v, &w.a)?;
    let data = &*data;
    let (dtau_dq, dtau_dv) = (&data.derivatives.dtau_dq, &data.derivatives.dtau_dv);
    let nv = model.nv();
    for k in 0..nv {
        // q
        for i in 0..nv {
            w.x[i] = w.dQ[(i, k)] - dtau_dq[(i, k)];
        }
        for r in 0..cdata.dim() {
            w.y[r] = -w.dr_dq[(r, k)];
        }
        w.solve(data, cdata, settings);
        out.ddq_dq.column_mut(k).copy_from_slice(&w.x);
        out.dlambda_dq.column_mut(k).copy_from_slice(&w.y);
        // q̇
        for i in 0..nv {
            w.x[i] = -dtau_dv[(i, k)];
        }
        for r in 0..cdata.dim() {
            w.y[r] = -w.dr_dv[(r, k)];
        }
        w.solve(data, cdata, settings);
        out.ddq_dv.column_mut(k).copy_from_slice(&w.x);
        out.dlambda_dv.column_mut(k).copy_from_slice(&w.y);
        // τ
        w.x.fill(0.0);
        w.x[k] = 1.0;
        w.y.fill(0.0);
        w.solve(data, cdata, settings);
        out.ddq_dtau.column_mut(k).copy_from_slice(&w.x);
        out.dlambda_dtau.column_mut(k).copy_from_slice(&w.y);
    }
    Ok(())
}

/// [`impulse_dynamics`] at `(q, q̇⁻)` and the derivatives of `q̇⁺` and the impulse `Λ` with
/// respect to `q` (along `q ⊕ δ`) and `q̇⁻`, into `out` (see [the module](self)).
///
/// # Errors
/// As [`impulse_dynamics`] and [`constraint_dynamics_derivatives`].
///
/// ```
/// use rigid::multibody::constraints::{impulse_dynamics_derivatives, ConstraintData,
///     ImpulseDynamicsDerivatives, ConstraintModel, ProximalSettings};
/// use rigid::multibody::{builtin, Data, JointId};
/// use rigid::spatial::Transform;
/// let model = builtin("double_pendulum").unwrap();
/// let mut data = Data::new(&model);
/// let c = ConstraintModel::point(Some(JointId(1)), Transform::identity(), None, Transform::identity());
/// let mut cdata = ConstraintData::new(&model, &[c])?;
/// let mut d = ImpulseDynamicsDerivatives::new(&model, &cdata);
/// let settings = ProximalSettings::new(1e-12, 1e-12, 100);
/// impulse_dynamics_derivatives(&model, &mut data, &mut cdata, &[0.3, -0.2], &[0.1, 0.4], 0.0,
///                              &settings, &mut d)?;
/// // the elbow is pinned after the impact, whatever it did before: q̇⁺ depends on q̇⁻ only
/// // through the free swing of the outer link
/// assert_eq!(d.dvplus_dv.shape(), (2, 2));
/// # Ok::<(), rigid::multibody::constraints::ConstraintError>(())
/// ```
#[allow(clippy::too_many_arguments)]
pub fn impulse_dynamics_derivatives(
    model: &Model,
    data: &mut Data,
    cdata: &mut ConstraintData,
    q: &[f64],
    v_before: &[f64],
    restitution: f64,
    settings: &ProximalSettings,
    out: &mut ImpulseDynamicsDerivatives,
) -> Result<(), ConstraintError> {
    out.work.check(cdata)?;
    impulse_dynamics(model, data, cdata, q, v_before, restitution, settings)?;
    let w = &mut out.work;
    let nv = model.nv();
    for k in 0..nv {
        w.a[k] = cdata.dq_plus[k] - v_before[k];
        w.v[k] = cdata.dq_plus[k] + restitution * v_before[k];
    }
    let impulse = &cdata.impulse.as_slice()[..cdata.dim()];
    w.partials(model, data, cdata, q, impulse, Level::Velocity)?;
    // ∂(M x)/∂q = ∂RNEA(q, 0, x)/∂q − ∂g/∂q, x = q̇⁺ − q̇⁻ (RNEA's pass leaves `dg_dq` as it is)
    gravity_derivatives(model, data, q)?;
    rnea_derivatives(model, data, q, &w.zero, &w.a)?;
    let data = &*data;
    let (drnea, dg, M) = (
        &data.derivatives.dtau_dq,
        &data.derivatives.dg_dq,
        &data.mass_matrix,
    );
    for k in 0..nv {
        for i in 0..nv {
            w.x[i] = w.dQ[(i, k)] - (drnea[(i, k)] - dg[(i, k)]);
        }
        for r in 0..cdata.dim() {
            w.y[r] = -w.dr_dq[(r, k)];
        }
        w.solve(data, cdata, settings);
        out.dvplus_dq.column_mut(k).copy_from_slice(&w.x);
        out.dimpulse_dq.column_mut(k).copy_from_slice(&w.y);
        for i in 0..nv {
            w.x[i] = M[(i, k)];
        }
        for r in 0..cdata.dim() {
            w.y[r] = -restitution * cdata.jacobian[(r, k)];
        }
        w.solve(data, cdata, settings);
        out.dvplus_dv.column_mut(k).copy_from_slice(&w.x);
        out.dimpulse_dv.column_mut(k).copy_from_slice(&w.y);
    }
    Ok(())
}
