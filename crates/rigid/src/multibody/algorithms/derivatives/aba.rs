//! The derivatives of forward dynamics, `∂q̈/∂q`, `∂q̈/∂v`, `∂q̈/∂τ = M⁻¹`, from those of
//! inverse dynamics at `a = q̈` (Carpentier & Mansard 2018, §V).

use super::passes::{backward, bias_torques, forward_acceleration, forward_velocity, Output};
use super::product::{neg_minv_times, Pattern};
use crate::multibody::algorithms::{check_aba_inputs, check_fext, minverse_unchecked};
use crate::multibody::{Data, Model, MultibodyError};
use crate::spatial::Wrench;
use nalgebra::DMatrix;

/// The three partial derivatives of `q̈ = FD(q, v, τ)`, borrowed from `data`.
#[derive(Clone, Copy, Debug)]
pub struct AbaDerivatives<'a> {
    /// `∂q̈/∂q` (nv x nv, along `q ⊕ δ`): `data.derivatives.dqdd_dq`.
    pub dqdd_dq: &'a DMatrix<f64>,
    /// `∂q̈/∂v` (nv x nv): `data.derivatives.dqdd_dv`.
    pub dqdd_dv: &'a DMatrix<f64>,
    /// `∂q̈/∂τ = M(q)⁻¹`, full symmetric: `data.minv`.
    pub dqdd_dtau: &'a DMatrix<f64>,
}

/// The partial derivatives of forward dynamics `q̈ = M(q)⁻¹ (τ - c(q, v) - g(q))`: since
/// `ID(q, v, FD(q, v, τ)) = τ` for all `(q, v, τ)`, differentiating gives
/// `∂q̈/∂q = -M⁻¹ ∂τ/∂q`, `∂q̈/∂v = -M⁻¹ ∂τ/∂v` (the RNEA derivatives at `a = q̈`) and
/// `∂q̈/∂τ = M⁻¹` (Carpentier & Mansard, "Analytical derivatives of rigid body dynamics
/// algorithms", RSS 2018, §V; Pinocchio's `computeABADerivatives`).
///
/// Steps, sharing one first pass (every body in its tree's root frame, as
/// [`crba`](crate::multibody::crba)): `M⁻¹` by the passes of
/// [`compute_minverse`](crate::multibody::compute_minverse); the velocity
/// terms of the [`rnea_derivatives`](super::rnea_derivatives) forward pass and their bias
/// torques `b = c + g - Jᵀ F^ext`; `q̈ = M⁻¹ (τ - b)`; the acceleration terms at `q̈` and the
/// backward pass, giving `∂τ/∂q` and `∂τ/∂v` at `(q, v, q̈)`; the two products with `-M⁻¹`,
/// which skip the zeros of `∂τ/∂q` and `∂τ/∂v` (column k is non-zero only on the dofs of k's
/// ancestors and subtree). `∂q` is along `q ⊕ δ` (see the [module docs](super)). Also leaves
/// `q̈` in `data.ddq` and `∂τ/∂q`, `∂τ/∂v` at `a = q̈` in `data.derivatives`. Nothing is
/// allocated.
///
/// # Errors
/// As [`aba`](crate::multibody::aba): wrong lengths, non-finite entries, a non-unit quaternion,
/// or [`MultibodyError::NotPositiveDefinite`] for a singular `M`.
///
/// ```
/// use rigid::multibody::{aba_derivatives, pendulum, Data};
/// let model = pendulum(); // q̈ = 3 (τ - 4.905 sin q)
/// let mut data = Data::new(&model);
/// let d = aba_derivatives(&model, &mut data, &[0.5], &[0.0], &[1.0])?;
/// assert!((d.dqdd_dq[(0, 0)] + 3.0 * 4.905 * 0.5f64.cos()).abs() < 1e-12);
/// assert!((d.dqdd_dtau[(0, 0)] - 3.0).abs() < 1e-12);
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn aba_derivatives<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
) -> Result<AbaDerivatives<'a>, MultibodyError> {
    crate::multibody::algorithms::require_constant_subspaces(model, "the analytical derivatives")?;
    check_aba_inputs(model, data, q, v, tau)?;
    aba_derivatives_unchecked(model, data, q, v, tau, None)
}

/// [`aba_derivatives`] with an external wrench `fext[i]` on each body, in body i's frame (as
/// [`aba_with_external`](crate::multibody::aba_with_external)).
///
/// # Errors
/// As [`aba_derivatives`], and `fext.len() != njoints` or a non-finite wrench.
///
/// ```
/// use rigid::multibody::{aba_derivatives_with_external, double_pendulum, Data};
/// use rigid::spatial::{Vec3, Wrench};
/// let model = double_pendulum();
/// let mut data = Data::new(&model);
/// let fext = [Wrench::zero(), Wrench::new(Vec3::zeros(), Vec3::new(0.0, 0.0, 2.0))];
/// let d = aba_derivatives_with_external(&model, &mut data, &[0.1, 0.2], &[0.3, 0.0], &[0.0; 2], &fext)?;
/// assert_eq!(d.dqdd_dv.shape(), (2, 2));
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn aba_derivatives_with_external<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    fext: &[Wrench],
) -> Result<AbaDerivatives<'a>, MultibodyError> {
    crate::multibody::algorithms::require_constant_subspaces(model, "the analytical derivatives")?;
    check_aba_inputs(model, data, q, v, tau)?;
    check_fext(model, fext)?;
    aba_derivatives_unchecked(model, data, q, v, tau, Some(fext))
}

fn aba_derivatives_unchecked<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    fext: Option<&[Wrench]>,
) -> Result<AbaDerivatives<'a>, MultibodyError> {
    minverse_unchecked(model, data, q)?;
    forward_velocity(model, data, q, Some(v), fext);
    bias_torques(model, data);
    // q̈ = M⁻¹ (τ - b)
    let nv = model.nv;
    let d = &mut data.derivatives;
    for ((r, t), b) in d.rhs.iter_mut().zip(tau).zip(&d.tau_bias) {
        *r = t - b;
    }
    for (x, col) in data
        .ddq
        .iter_mut()
        .zip(data.minv.as_slice().chunks_exact(nv.max(1)))
    {
        *x = col.iter().zip(&d.rhs).map(|(m, r)| m * r).sum();
    }
    // q̈ is an input of the passes that also write into `data`: lend it out (no allocation)
    let ddq = std::mem::take(&mut data.ddq);
    forward_acceleration(model, data, Some(ddq.as_slice()));
    backward(model, data, Some(ddq.as_slice()), Output::Aba);
    data.ddq = ddq;
    let d = &mut data.derivatives;
    let pattern = Pattern {
        parent: &d.dof_parent,
        end: &d.dof_end,
    };
    neg_minv_times(
        &data.minv,
        (&d.dtau_dq, &d.dtau_dv),
        (&mut d.dqdd_dq, &mut d.dqdd_dv),
        &pattern,
        &mut d.minv_padded,
        &mut d.column,
    );
    Ok(AbaDerivatives {
        dqdd_dq: &data.derivatives.dqdd_dq,
        dqdd_dv: &data.derivatives.dqdd_dv,
        dqdd_dtau: &data.minv,
    })
}
