//! The derivatives of inverse dynamics, `∂τ/∂q`, `∂τ/∂v`, `∂τ/∂a = M`, and of the generalised
//! gravity `∂g/∂q`, in one forward and one backward pass (Carpentier & Mansard, "Analytical
//! derivatives of rigid body dynamics algorithms", RSS 2018, Alg. 1), with every quantity in one
//! frame per tree (its root body's, as [`crba`](crate::multibody::crba)).

use super::passes::{backward, forward_acceleration, forward_velocity, Output};
use crate::multibody::algorithms::root_frame_bodies;
use crate::multibody::{check_data, check_q, check_v, Data, Model, MultibodyError};
use crate::spatial::Wrench;
use nalgebra::DMatrix;

/// The three partial derivatives of `τ = ID(q, v, a)`, borrowed from `data`.
#[derive(Clone, Copy, Debug)]
pub struct RneaDerivatives<'a> {
    /// `∂τ/∂q` (nv x nv, along `q ⊕ δ`): `data.derivatives.dtau_dq`.
    pub dtau_dq: &'a DMatrix<f64>,
    /// `∂τ/∂v` (nv x nv): `data.derivatives.dtau_dv`.
    pub dtau_dv: &'a DMatrix<f64>,
    /// `∂τ/∂a = M(q)`, armature on the diagonal, full symmetric: `data.mass_matrix`.
    pub dtau_da: &'a DMatrix<f64>,
}

/// The partial derivatives of inverse dynamics `τ = M(q) a + c(q, v) + g(q) - Σ J_iᵀ F_i^ext`:
/// `∂τ/∂q` (along `q ⊕ δ`, see the [module docs](super)), `∂τ/∂v` and `∂τ/∂a = M(q)`, in one
/// forward and one backward pass, O(n d) (d the depth); Carpentier & Mansard, "Analytical
/// derivatives of rigid body dynamics algorithms", RSS 2018, Alg. 1 (Pinocchio's
/// `computeRNEADerivatives`).
///
/// Every quantity is expressed in one inertial frame per tree, the frame {r} of its root body
/// frozen at `q` (any common frame gives the same `τ`; in this one the root's columns are its
/// constant `S`, as in [`crba`](crate::multibody::crba)): `J_k = [Ad_{rMi}] S_k`,
/// `G_i = [Ad_{rMi⁻¹}]ᵀ G_i^body [Ad_{rMi⁻¹}]`, gravity `a_g = (0, -R_rootᵀ g)`.
///
/// Forward (i = 1..n, λ the parent, `V_λ = 0`, `A_λ = a_g` at a root; `×` the twist cross
/// product `[ad_V]`, `×*` its dual `-[ad_V]ᵀ`):
/// - `V_i = V_λ + Σ_k J_k v_k`, `A_i = A_λ + Σ_k J_k a_k + V_i × Σ_k J_k v_k`
/// - `f_i = G_i A_i + V_i ×* G_i V_i - F_i^ext`, `h_i = G_i V_i`
/// - per dof k of joint i: `∂V/∂q_k = V_λ × J_k`, `∂A/∂q_k = A_λ × J_k + V_λ × ∂V/∂q_k`,
///   `∂A/∂v_k = (V_i + V_λ) × J_k`: the parts of the variations of the subtree's twists that are
///   not the rigid motion `J_k × (·)` of the subtree (which leaves `τ` unchanged).
/// - `B_i x = G_i (x × V_i) + x ×* h_i + V_i ×* G_i x`, the variation of `f_i` with the twist;
///   its lower-right block and upper-right block vanish and its angular block is
///   `[ω]I - I[ω] - [c][v] - [v][c] - [L]` (`G = (m, c = m·com, I)`, `h = (L, p)`, lower-left
///   `-2[p]`): a symmetric 3x3, `L` and `p`, all additive over a subtree.
///
/// Backward (i = n..1), with the subtree sums `Ic_i = Σ G_j`, `Bc_i = Σ B_j`, `F_i = Σ f_j`:
/// `τ_k = J_kᵀ F_i + armature_k a_k`, and for each dof k of joint i:
/// - `∂F/∂q_k = Ic_i ∂A/∂q_k + Bc_i ∂V/∂q_k (+ J_k ×* F_i)`, `∂F/∂v_k = Ic_i ∂A/∂v_k + Bc_i J_k`
/// - for every dof c of the subtree of i (own joint included): `∂τ_k/∂q_c = J_kᵀ ∂F/∂q_c`,
///   `∂τ_k/∂v_c = J_kᵀ ∂F/∂v_c`, `M_kc = J_kᵀ Ic_{j(c)} J_c` (the `J ×* F` term of the own joint is
///   added after this row is written: it cancels the turning of `J_k` itself)
/// - for every dof c of the strict subtree: `∂τ_c/∂q_k = (Ic_{j(c)} J_c)ᵀ ∂A/∂q_k + (Bc_{j(c)}ᵀ J_c)ᵀ ∂V/∂q_k`,
///   `∂τ_c/∂v_k = (Ic_{j(c)} J_c)ᵀ ∂A/∂v_k + (Bc_{j(c)}ᵀ J_c)ᵀ J_k`, `M_ck = M_kc`
///
/// Entries between different branches are zero. Returns the three matrices; `data.tau` holds
/// `τ` and `data.composite_inertias` the composite inertias (as after [`crba`](crate::multibody::crba)).
/// Nothing is allocated.
///
/// # Errors
/// Wrong lengths, non-finite entries, a non-unit quaternion, or a `data` made for another model.
///
/// ```
/// use rigid::multibody::{pendulum, rnea_derivatives, Data};
/// let model = pendulum(); // τ = q̈/3 + 4.905 sin q: ∂τ/∂q = 4.905 cos q, ∂τ/∂v = 0, M = 1/3
/// let mut data = Data::new(&model);
/// let d = rnea_derivatives(&model, &mut data, &[0.5], &[2.0], &[1.0])?;
/// assert!((d.dtau_dq[(0, 0)] - 4.905 * 0.5f64.cos()).abs() < 1e-12);
/// assert!(d.dtau_dv[(0, 0)].abs() < 1e-12 && (d.dtau_da[(0, 0)] - 1.0 / 3.0).abs() < 1e-12);
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn rnea_derivatives<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    a: &[f64],
) -> Result<RneaDerivatives<'a>, MultibodyError> {
    crate::multibody::algorithms::require_constant_subspaces(model, "the analytical derivatives")?;
    check_q(model, q)?;
    check_data(model, data)?;
    check_v(model, "v", v)?;
    check_v(model, "a", a)?;
    derivatives_unchecked(model, data, q, Some((v, a)), None);
    Ok(borrow(data))
}

/// [`rnea_derivatives`] with an external wrench `fext[i]` on each body, in body i's frame (as
/// [`rnea_with_external`](crate::multibody::rnea_with_external)): the wrenches are fixed in the
/// bodies, so they turn with them and enter `∂τ/∂q`.
///
/// # Errors
/// As [`rnea_derivatives`], and `fext.len() != njoints` or a non-finite wrench.
///
/// ```
/// use rigid::multibody::{double_pendulum, rnea_derivatives_with_external, Data};
/// use rigid::spatial::{Vec3, Wrench};
/// let model = double_pendulum();
/// let mut data = Data::new(&model);
/// let fext = [Wrench::zero(), Wrench::new(Vec3::zeros(), Vec3::new(1.0, 0.0, 0.0))];
/// let d = rnea_derivatives_with_external(&model, &mut data, &[0.1, 0.2], &[0.0; 2], &[0.0; 2], &fext)?;
/// assert_eq!(d.dtau_dq.shape(), (2, 2));
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn rnea_derivatives_with_external<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    fext: &[Wrench],
) -> Result<RneaDerivatives<'a>, MultibodyError> {
    crate::multibody::algorithms::require_constant_subspaces(model, "the analytical derivatives")?;
    check_q(model, q)?;
    check_data(model, data)?;
    check_v(model, "v", v)?;
    check_v(model, "a", a)?;
    crate::multibody::algorithms::check_fext(model, fext)?;
    derivatives_unchecked(model, data, q, Some((v, a)), Some(fext));
    Ok(borrow(data))
}

fn borrow(data: &Data) -> RneaDerivatives<'_> {
    RneaDerivatives {
        dtau_dq: &data.derivatives.dtau_dq,
        dtau_dv: &data.derivatives.dtau_dv,
        dtau_da: &data.mass_matrix,
    }
}

/// `∂g/∂q`, the derivative of the generalised gravity `g(q) = τ(q, 0, 0)` along `q ⊕ δ`
/// (Pinocchio's `computeGeneralizedGravityDerivatives`): the passes of [`rnea_derivatives`]
/// without velocity terms. Returns `data.derivatives.dg_dq`; `data.g` holds `g(q)`.
///
/// # Errors
/// As [`rnea_derivatives`].
///
/// ```
/// use rigid::multibody::{gravity_derivatives, pendulum, Data};
/// let model = pendulum(); // g(q) = 4.905 sin q
/// let mut data = Data::new(&model);
/// let dg = gravity_derivatives(&model, &mut data, &[0.3])?;
/// assert!((dg[(0, 0)] - 4.905 * 0.3f64.cos()).abs() < 1e-12);
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn gravity_derivatives<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
) -> Result<&'a DMatrix<f64>, MultibodyError> {
    crate::multibody::algorithms::require_constant_subspaces(model, "the analytical derivatives")?;
    check_q(model, q)?;
    check_data(model, data)?;
    derivatives_unchecked(model, data, q, None, None);
    Ok(&data.derivatives.dg_dq)
}

/// Both passes on checked inputs: `va = None` is the gravity pass.
fn derivatives_unchecked(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    va: Option<(&[f64], &[f64])>,
    fext: Option<&[Wrench]>,
) {
    root_frame_bodies(
        model,
        q,
        &mut data.root_placements,
        &mut data.dof_J,
        &mut data.root_frame_inertias,
        &mut data.sin_cos,
    );
    let (v, a) = (va.map(|x| x.0), va.map(|x| x.1));
    forward_velocity(model, data, q, v, fext);
    forward_acceleration(model, data, a);
    let out = if va.is_some() {
        Output::Full
    } else {
        Output::Gravity
    };
    backward(model, data, a, out);
}
