//! Analytical derivatives of the dynamics and the kinematics (Carpentier & Mansard, "Analytical
//! derivatives of rigid body dynamics algorithms", RSS 2018): the partial derivatives of inverse
//! dynamics (RNEA), forward dynamics (ABA) and gravity with respect to `(q, v, a)` or `(q, v, τ)`,
//! of a frame's placement, velocity and acceleration, and the Jacobians of
//! [`integrate`](crate::multibody::integrate) and [`difference`](crate::multibody::difference).
//!
//! # Convention: derivatives with respect to `q`
//!
//! `q` lives on a manifold (quaternions, SE(3)), so a derivative with respect to `q` is taken
//! along the tangent perturbation `q ⊕ δ = integrate(q, δ)`, `δ ∈ ℝ^nv`, with the velocity
//! coordinates of each joint: column `k` of `∂f/∂q` is `d/dε f(q ⊕ ε e_k)` at `ε = 0`, and
//! `∂f/∂q` is `nv x nv` (not `nv x nq`). Joint by joint:
//!
//! | joint | `q ⊕ δ` | column order |
//! | --- | --- | --- |
//! | revolute, continuous, prismatic | `q + δ` | one column |
//! | spherical | `R · exp([δ])`: the rotation turned by `δ` about the body axes | `(δx, δy, δz)` body frame |
//! | free-flyer | `T · exp(δ)`, the SE(3) exponential of the body twist `δ = (ω, v)` | **angular first**: `(ωx, ωy, ωz, vx, vy, vz)` |
//! | planar | `T · exp(δ)` in SE(2), `δ = (vx, vy, ω)` body frame | `(vx, vy, ω)` |
//!
//! This is Pinocchio's convention (its `integrate` is `q · exp(δ)` too), with one difference: a
//! Pinocchio free-flyer's tangent is linear first, `(v, ω)`, so its rows and columns of a
//! Pinocchio derivative are rigid's with the two halves swapped. A continuous joint's Pinocchio
//! configuration is `(cos θ, sin θ)` but its tangent is the angle, so the columns coincide.
//! Derivatives with respect to `v`, `a` and `τ` are ordinary ones, in the velocity coordinates
//! (body twists, angular first).
//!
//! | notes | code | source |
//! | --- | --- | --- |
//! | `∂τ/∂q`, `∂τ/∂v`, `∂τ/∂a = M` | [`rnea_derivatives`], [`rnea_derivatives_with_external`] | Carpentier & Mansard 2018, §IV (Alg. 1); Pinocchio `computeRNEADerivatives` |
//! | `∂g/∂q` | [`gravity_derivatives`] | the same at `v = a = 0`; Pinocchio `computeGeneralizedGravityDerivatives` |
//! | `∂q̈/∂q = -M⁻¹ ∂τ/∂q`, `∂q̈/∂v = -M⁻¹ ∂τ/∂v`, `∂q̈/∂τ = M⁻¹` | [`aba_derivatives`], [`aba_derivatives_with_external`] | Carpentier & Mansard 2018, §V; Pinocchio `computeABADerivatives` |
//! | `∂V/∂q`, `∂V/∂v`, `∂A/∂(q, v, a)` of a frame; placement: `J` | [`frame_kinematics_derivatives`], [`joint_kinematics_derivatives`] | Carpentier & Mansard 2018, §III; Pinocchio `getFrameAccelerationDerivatives` |
//! | `∂(q ⊕ v)/∂q`, `∂(q ⊕ v)/∂v`, `∂(q₁ ⊖ q₀)/∂q₀`, `∂(q₁ ⊖ q₀)/∂q₁` | [`integrate_jacobians`](crate::multibody::integrate_jacobians), [`difference_jacobians`](crate::multibody::difference_jacobians) | right Jacobians of SO(3), SE(3), SE(2) (Barfoot 2017, §7.1; Solà et al. 2018) |
//! | many states at once | [`batch`](crate::multibody::batch) (`rnea_derivatives_batch`, `aba_derivatives_batch`) | rayon |
//!
//! The buffers live in [`Data::derivatives`](crate::multibody::Data::derivatives) (a
//! [`Derivatives`]), made once by [`Data::new`](crate::multibody::Data::new): nothing is
//! allocated per call.

mod aba;
mod kinematics;
mod passes;
mod product;
mod rnea;

pub use aba::{aba_derivatives, aba_derivatives_with_external, AbaDerivatives};
pub use kinematics::{
    frame_kinematics_derivatives, joint_kinematics_derivatives, KinematicsDerivatives,
};
pub use rnea::{
    gravity_derivatives, rnea_derivatives, rnea_derivatives_with_external, RneaDerivatives,
};

use crate::multibody::Model;
use crate::spatial::{Twist, Vec3, Wrench};
use nalgebra::DMatrix;

/// The outputs and buffers of the derivative algorithms, a part of [`Data`](crate::multibody::Data)
/// (`data.derivatives`). Matrices are `nv x nv` (kinematics: `6 x nv`), column `k` the derivative
/// with respect to coordinate `k` (along `q ⊕ δ` for `q`, see the [module docs](self)).
#[derive(Clone, Debug)]
pub struct Derivatives {
    /// `∂τ/∂q` ([`rnea_derivatives`]; at `a = q̈` after [`aba_derivatives`]).
    pub dtau_dq: DMatrix<f64>,
    /// `∂τ/∂v` ([`rnea_derivatives`]; at `a = q̈` after [`aba_derivatives`]).
    pub dtau_dv: DMatrix<f64>,
    /// `∂g/∂q`, the derivative of the generalised gravity ([`gravity_derivatives`]).
    pub dg_dq: DMatrix<f64>,
    /// `∂q̈/∂q` ([`aba_derivatives`]).
    pub dqdd_dq: DMatrix<f64>,
    /// `∂q̈/∂v` ([`aba_derivatives`]).
    pub dqdd_dv: DMatrix<f64>,
    /// `∂V/∂q` of a frame's twist `V` (6 x nv, [`frame_kinematics_derivatives`]).
    pub velocity_dq: DMatrix<f64>,
    /// `∂V/∂v = J`, the frame's Jacobian, which is also the derivative of its placement
    /// (6 x nv, [`frame_kinematics_derivatives`]).
    pub velocity_dv: DMatrix<f64>,
    /// `∂A/∂q` of a frame's acceleration `A = dV/dt` (6 x nv).
    pub acceleration_dq: DMatrix<f64>,
    /// `∂A/∂v` (6 x nv).
    pub acceleration_dv: DMatrix<f64>,
    /// `∂A/∂a = J` (6 x nv).
    pub acceleration_da: DMatrix<f64>,
    // --- per joint, in the frame {r} of its tree's root body (see `rnea.rs`) ---
    /// `V_i`, `A_i` (gravity included), its bias part `A⁰_i` (at `a = 0`) and the rest `A_i - A⁰_i`,
    /// the force `f_i` (then the composite `F_i` of each subtree), the bias forces' composites.
    pub(crate) vel: Vec<Twist>,
    pub(crate) acc: Vec<Twist>,
    pub(crate) acc0: Vec<Twist>,
    pub(crate) acc_a: Vec<Twist>,
    pub(crate) force: Vec<Wrench>,
    pub(crate) bias: Vec<Wrench>,
    /// At a root: `g' = -Rᵀ g`, gravity as the world's acceleration `(0, g')` in its tree's frame.
    pub(crate) gravity: Vec<Vec3>,
    /// Composite momentum `Σ G_j V_j` of each subtree.
    pub(crate) momentum: Vec<Wrench>,
    /// Composite symmetric part of the angular block of `B` (6 numbers, `xx yy zz xy xz yz`).
    pub(crate) sym: Vec<[f64; 6]>,
    // --- per degree of freedom ---
    pub(crate) dv_dq: Vec<Twist>,
    pub(crate) da_dq: Vec<Twist>,
    pub(crate) da_dv: Vec<Twist>,
    /// `Ic J_k`, `Bcᵀ J_k` (its angular part: the linear part is zero), `∂F/∂q_k`, `∂F/∂v_k`.
    pub(crate) yj: Vec<Wrench>,
    pub(crate) bj: Vec<Vec3>,
    pub(crate) df_dq: Vec<Wrench>,
    pub(crate) df_dv: Vec<Wrench>,
    /// `J_kᵀ` of the bias forces (`c + g - Jᵀ F^ext`), and `τ` minus it.
    pub(crate) tau_bias: Vec<f64>,
    pub(crate) rhs: Vec<f64>,
    /// `M⁻¹` in blocks of 8 rows, its columns padded with zeros (`product.rs`).
    pub(crate) minv_padded: Vec<[f64; 8]>,
    /// The non-zero rows of one column of `∂τ/∂q`, `∂τ/∂v` (`product.rs`).
    pub(crate) column: Vec<product::Entry>,
    /// The ancestor dof `λ(k)` of each dof (`usize::MAX` at a root) and one past the last dof of
    /// its subtree: column `k` of `∂τ/∂q` is non-zero only on `k`'s ancestors and its subtree.
    pub(crate) dof_parent: Vec<usize>,
    pub(crate) dof_end: Vec<usize>,
}

impl Derivatives {
    /// Buffers for `model`.
    #[must_use]
    pub fn new(model: &Model) -> Self {
        let (n, nv) = (model.njoints(), model.nv());
        let mut dof_parent = vec![usize::MAX; nv];
        let mut dof_end = vec![0; nv];
        for (j, &end) in model.joints().iter().zip(&model.plan().subtree_end_v) {
            for k in j.idx_v..j.idx_v + j.nv {
                dof_end[k] = end;
                dof_parent[k] = if k > j.idx_v {
                    k - 1
                } else {
                    j.parent.map_or(usize::MAX, |p| {
                        let pj = &model.joints()[p.0];
                        pj.idx_v + pj.nv - 1
                    })
                };
            }
        }
        let square = || DMatrix::zeros(nv, nv);
        let six = || DMatrix::zeros(6, nv);
        Self {
            dtau_dq: square(),
            dtau_dv: square(),
            dg_dq: square(),
            dqdd_dq: square(),
            dqdd_dv: square(),
            velocity_dq: six(),
            velocity_dv: six(),
            acceleration_dq: six(),
            acceleration_dv: six(),
            acceleration_da: six(),
            vel: vec![Twist::zero(); n],
            acc: vec![Twist::zero(); n],
            acc0: vec![Twist::zero(); n],
            acc_a: vec![Twist::zero(); n],
            force: vec![Wrench::zero(); n],
            bias: vec![Wrench::zero(); n],
            gravity: vec![Vec3::zeros(); n],
            momentum: vec![Wrench::zero(); n],
            sym: vec![[0.0; 6]; n],
            dv_dq: vec![Twist::zero(); nv],
            da_dq: vec![Twist::zero(); nv],
            da_dv: vec![Twist::zero(); nv],
            yj: vec![Wrench::zero(); nv],
            bj: vec![Vec3::zeros(); nv],
            df_dq: vec![Wrench::zero(); nv],
            df_dv: vec![Wrench::zero(); nv],
            tau_bias: vec![0.0; nv],
            rhs: vec![0.0; nv],
            minv_padded: vec![[0.0; 8]; product::blocks(nv) * nv],
            column: vec![product::Entry::default(); nv],
            dof_parent,
            dof_end,
        }
    }
}
