//! The derivatives of forward dynamics, `∂q̈/∂q`, `∂q̈/∂v`, `∂q̈/∂τ = M⁻¹`, from those of
//! inverse dynamics at `a = q̈` (Carpentier & Mansard 2018, §V).

use super::rnea::derivatives_unchecked;
use crate::multibody::algorithms::{aba, aba_with_external, check_fext, compute_minverse};
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
/// Steps: `q̈` by [`aba`]; the passes of [`rnea_derivatives`](super::rnea_derivatives) at
/// `(q, v, q̈)`; `M⁻¹` by [`compute_minverse`]; the two products with `-M⁻¹`, which skip the
/// zeros of `∂τ/∂q` and `∂τ/∂v` (column k is non-zero only on the dofs of k's ancestors and
/// subtree). `∂q` is along `q ⊕ δ` (see the [module docs](super)). Also leaves `q̈` in
/// `data.ddq`, `∂τ/∂q`, `∂τ/∂v` at `a = q̈` in `data.derivatives` and `M` in
/// `data.mass_matrix`. Nothing is allocated.
///
/// # Errors
/// As [`aba`] (wrong lengths, non-finite entries, a non-unit quaternion, a singular `M`).
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
    aba(model, data, q, v, tau)?;
    finish(model, data, q, v, None)
}

/// [`aba_derivatives`] with an external wrench `fext[i]` on each body, in body i's frame (as
/// [`aba_with_external`]).
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
    check_fext(model, fext)?;
    aba_with_external(model, data, q, v, tau, fext)?;
    finish(model, data, q, v, Some(fext))
}

/// After `q̈` is in `data.ddq` (inputs checked): the RNEA derivatives at `q̈`, `M⁻¹`, products.
fn finish<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    fext: Option<&[Wrench]>,
) -> Result<AbaDerivatives<'a>, MultibodyError> {
    // q̈ is an input of the passes that also write into `data`: lend it out (no allocation)
    let ddq = std::mem::take(&mut data.ddq);
    derivatives_unchecked(model, data, q, Some((v, ddq.as_slice())), fext);
    data.ddq = ddq;
    compute_minverse(model, data, q)?;
    let d = &mut data.derivatives;
    let (parent, end) = (&d.dof_parent, &d.dof_end);
    neg_minv_times(&data.minv, &d.dtau_dq, &mut d.dqdd_dq, parent, end);
    neg_minv_times(&data.minv, &d.dtau_dv, &mut d.dqdd_dv, parent, end);
    Ok(AbaDerivatives {
        dqdd_dq: &data.derivatives.dqdd_dq,
        dqdd_dv: &data.derivatives.dqdd_dv,
        dqdd_dtau: &data.minv,
    })
}

/// `out = -M⁻¹ X` for an `X` whose column `c` is non-zero only on the rows of `c`'s ancestor
/// dofs (the chain `λ(c), λ(λ(c)), …`) and of its subtree `c..end[c]`: column by column, a sum
/// of the columns of `M⁻¹` over those rows.
fn neg_minv_times(
    minv: &DMatrix<f64>,
    x: &DMatrix<f64>,
    out: &mut DMatrix<f64>,
    parent: &[usize],
    end: &[usize],
) {
    let nv = minv.nrows();
    let (minv, x) = (minv.as_slice(), x.as_slice());
    for (c, oc) in out.as_mut_slice().chunks_exact_mut(nv).enumerate() {
        let xc = &x[c * nv..(c + 1) * nv];
        oc.fill(0.0);
        let mut axpy = |r: usize| {
            let s = -xc[r];
            for (o, m) in oc.iter_mut().zip(&minv[r * nv..(r + 1) * nv]) {
                *o += s * m;
            }
        };
        for r in c..end[c] {
            axpy(r);
        }
        let mut r = parent[c];
        while r != usize::MAX {
            axpy(r);
            r = parent[r];
        }
    }
}
