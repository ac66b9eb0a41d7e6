//! Forward dynamics under constraints given by their Jacobian (Pinocchio's `forwardDynamics`
//! with `J` and `γ`, the form before constraint models).

use super::solver::{cholesky, cholesky_solve};
use super::ConstraintError;
use crate::multibody::algorithms::{ltl_factor, ltl_solve_lower, ltl_solve_transposed};
use crate::multibody::{check_data, check_v, crba, nonlinear_effects, Data, Model};
use nalgebra::{DMatrix, DVector};

/// `q̈` and `λ` with `M q̈ + c + g = τ + Jᵀ λ` and `J q̈ + γ = 0` (`−damping λ` with a
/// damping) for a given constraint Jacobian `J` (m x nv) and drift `γ`: CRBA and RNEA at
/// `(q, v)`, then
/// [`jacobian_dynamics_from_terms`]. `q̈` in `data.ddq`; returns `λ`.
///
/// ```
/// use nalgebra::DMatrix;
/// use rigid::multibody::constraints::jacobian_dynamics;
/// use rigid::multibody::{double_pendulum, Data};
///
/// // the double pendulum with its first joint held (J = [1 0], γ = 0): the second swings alone
/// let model = double_pendulum();
/// let mut data = Data::new(&model);
/// let J = DMatrix::from_row_slice(1, 2, &[1.0, 0.0]);
/// let lambda =
///     jacobian_dynamics(&model, &mut data, &[0.3, 0.5], &[0.0; 2], &[0.0; 2], &J, &[0.0], 0.0)
///         .unwrap();
/// assert!(data.ddq[0].abs() < 1e-12);
/// // the second link alone: a rod of 1 kg, 1 m on a pin, q̈ = −(3 g / 2 l) sin(q1 + q2)
/// assert!((data.ddq[1] + 1.5 * 9.81 * (0.8f64).sin()).abs() < 1e-9);
/// assert!(lambda[0].abs() > 0.0); // the torque that holds joint 1
/// ```
///
/// # Errors
/// As [`jacobian_dynamics_from_terms`], and bad `q` or `v`.
#[allow(clippy::too_many_arguments)]
pub fn jacobian_dynamics(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    J: &DMatrix<f64>,
    gamma: &[f64],
    damping: f64,
) -> Result<DVector<f64>, ConstraintError> {
    nonlinear_effects(model, data, q, v)?;
    crba(model, data, q)?;
    jacobian_dynamics_from_terms(model, data, tau, J, gamma, damping)
}

/// [`jacobian_dynamics`] on the mass matrix and the bias of the last [`crba`] and
/// [`nonlinear_effects`] (`data.mass_matrix`, `data.nle`: Pinocchio's form after
/// `computeAllTerms`). Featherstone's range-space method (2008, §8.3), as Pinocchio's:
///
/// ```text
/// q̈_f = M⁻¹ (τ − c − g),   λ = (J M⁻¹ Jᵀ + damping I)⁻¹ (−γ − J q̈_f),   q̈ = q̈_f + M⁻¹ Jᵀ λ
/// ```
///
/// with `M = LᵀL` factored along the tree. `q̈` in `data.ddq`; returns `λ`. With `damping > 0`
/// (redundant constraints), `J q̈ + γ = −damping λ` instead of 0.
///
/// # Errors
/// [`ConstraintError::BadJacobian`] naming the fault: a `J` of another width than `nv`, a `γ`
/// of another length than its rows, a non-finite entry (its row and column) or a negative or
/// non-finite `damping`; [`ConstraintError::Singular`] when `J M⁻¹ Jᵀ + damping I` is not
/// positive definite (a pivot at most 1e-14 of its largest diagonal entry: redundant rows);
/// a `data` of another model, `M` not positive definite, or a `τ` of the wrong length.
pub fn jacobian_dynamics_from_terms(
    model: &Model,
    data: &mut Data,
    tau: &[f64],
    J: &DMatrix<f64>,
    gamma: &[f64],
    damping: f64,
) -> Result<DVector<f64>, ConstraintError> {
    check_data(model, data)?;
    check_v(model, "tau", tau)?;
    let (m, nv) = (J.nrows(), model.nv());
    let bad = |reason: String| Err(ConstraintError::BadJacobian(reason));
    if J.ncols() != nv {
        return bad(format!("J has {} columns, the model nv = {nv}", J.ncols()));
    }
    if gamma.len() != m {
        return bad(format!(
            "gamma has {} entries for the {m} rows of J",
            gamma.len()
        ));
    }
    if let Some(k) = J.iter().position(|x| !x.is_finite()) {
        // column-major: entry k is row k % m, column k / m
        return bad(format!("J[{}, {}] is not finite", k % m, k / m));
    }
    if let Some(r) = gamma.iter().position(|x| !x.is_finite()) {
        return bad(format!("gamma[{r}] is not finite"));
    }
    if !(damping >= 0.0 && damping.is_finite()) {
        return bad(format!("damping {damping} must be finite and >= 0"));
    }
    ltl_factor(model, data)?;
    let (L, parent) = (data.chol.as_slice(), &data.dof_parent);
    let minv = |x: &mut [f64]| {
        ltl_solve_transposed(L, parent, x);
        ltl_solve_lower(L, parent, x);
    };
    // q̈_f = M⁻¹ (τ − c − g); the columns of M⁻¹ Jᵀ
    let mut a: Vec<f64> = tau.iter().zip(&data.nle).map(|(t, b)| t - b).collect();
    minv(&mut a);
    let mut minv_jt = J.transpose();
    for mut c in minv_jt.column_iter_mut() {
        minv(c.as_mut_slice());
    }
    let mut K = J * &minv_jt;
    for r in 0..m {
        K[(r, r)] += damping;
    }
    let mut lambda = DVector::from_iterator(
        m,
        (0..m).map(|r| -gamma[r] - J.row(r).iter().zip(&a).map(|(j, x)| j * x).sum::<f64>()),
    );
    // a pivot at most 1e-14 of the largest diagonal entry is redundant rows
    cholesky(&mut K, m)?;
    cholesky_solve(&K, m, lambda.as_mut_slice());
    let ddq = &minv_jt * &lambda;
    for (d, (f, c)) in data.ddq.iter_mut().zip(a.iter().zip(ddq.iter())) {
        *d = f + c;
    }
    Ok(lambda)
}
