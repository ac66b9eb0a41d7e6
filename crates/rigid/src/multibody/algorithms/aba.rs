//! The articulated-body algorithm for forward dynamics (Featherstone 2008, Table 7.1), in body
//! coordinates, and forward dynamics by Cholesky factorisation of `M` as a cross-check.
//!
//! Read [`reference::aba`](crate::multibody::reference::aba) first (spatial_v2's `FDab.m`): this
//! is the same three loops, with `IA{λ(i)} += Xup' * Ia * Xup` as the written-out
//! [`congruence`](crate::spatial) (its plane-rotation variant when `X_T` has no rotation and the
//! joint turns about a coordinate axis), and a one-dof joint's `U`, `d`, `u` as scalars and
//! columns (`S = ±e_c` picks a column of `I^A` and a component of `p^A`).

use super::{joint_bias, joint_motion, parent_placement, update_subspaces};
use crate::error::DimensionError;
use crate::multibody::plan::PlacementKind;
use crate::multibody::{check_data, check_q, check_v, Data, Model, MultibodyError};
use crate::spatial::{
    congruence, congruence_about_axis, mat6_twist, sub_outer, Mat6, Twist, Vec3, Vec6, Wrench,
};
use nalgebra::DVector;

fn aba_impl(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    fext: Option<&[Wrench]>,
) -> Result<(), MultibodyError> {
    let n = model.njoints();
    update_subspaces(model, q, &mut data.S);
    // pass 1: kinematics, bias forces
    for i in 0..n {
        let liMi = parent_placement(model, i, q);
        data.parent_placements[i] = liMi;
        let Vp = match model.joints()[i].parent {
            Some(p) => data.velocities[p.0],
            None => Twist::zero(),
        };
        let vJ = joint_motion(model, &data.S, i, v);
        let V = liMi.inv_act_twist(&Vp) + vJ;
        data.velocities[i] = V;
        data.c_bias[i] = V.cross(&vJ);
        if let Some(cJ) = joint_bias(model, i, q, v) {
            data.c_bias[i] += cJ;
        }
        let G = &model.inertias()[i];
        data.ia[i] = G.matrix();
        let mut pA = -V.ad_transpose(&G.momentum(&V));
        if let Some(f) = fext {
            pA -= f[i];
        }
        data.pa[i] = pA;
    }
    // pass 2: articulated inertias
    for i in (0..n).rev() {
        let j = &model.joints()[i];
        let (iv, nv) = (j.idx_v, j.nv);
        let pA = data.pa[i];
        if nv == 1 {
            // one degree of freedom: D and u are scalars
            let IA = &data.ia[i];
            let S = &data.S[iv];
            // U = I^A S, Sᵀ U, Sᵀ p^A: for S = s e_c a column and two components
            let (U, SU, Sp) = match model.plan().dof_axis[iv] {
                Some((c, s)) => {
                    let x = IA.column(c);
                    let U = Wrench::new(Vec3::new(x[0], x[1], x[2]), Vec3::new(x[3], x[4], x[5]));
                    (U * s, x[c], s * pA.to_vector()[c])
                }
                None => {
                    let U = mat6_twist(IA, S);
                    (U, S.dot(&U), S.dot(&pA))
                }
            };
            let D = SU + model.armature[iv];
            // a massless subtree moved by this joint (or a NaN): M is singular, not a NaN result
            if D.is_nan() || D <= 0.0 {
                return Err(MultibodyError::NotPositiveDefinite);
            }
            let Dinv = 1.0 / D;
            let u = tau[iv] - Sp;
            data.u_cols[iv] = U;
            data.d_inv_1[iv] = Dinv;
            data.u[iv] = u;
            if let Some(p) = j.parent {
                // I^a = I^A - U D⁻¹ Uᵀ, p^a = p^A + I^a c + U D⁻¹ u (I^a in place of I^A)
                let (head, tail) = data.ia.split_at_mut(i);
                let Ia = &mut tail[0];
                sub_outer(Ia, &U, Dinv);
                let pa = pA + mat6_twist(Ia, &data.c_bias[i]) + U * (Dinv * u);
                let X = &data.parent_placements[i];
                head[p.0] += match model.plan().dof_axis[iv] {
                    Some((k, _))
                        if k < 3 && model.plan().placement[i] == PlacementKind::Identity =>
                    {
                        congruence_about_axis(Ia, X, k)
                    }
                    _ => congruence(Ia, X),
                };
                data.pa[p.0] += X.act_wrench(&pa);
            }
            continue;
        }
        let IA = data.ia[i];
        for a in 0..nv {
            data.u_cols[iv + a] = mat6_twist(&IA, &data.S[iv + a]);
        }
        let mut D = Mat6::identity();
        for a in 0..nv {
            for b in 0..nv {
                D[(a, b)] = data.S[iv + a].dot(&data.u_cols[iv + b]);
            }
            D[(a, a)] += model.armature[iv + a];
            data.u[iv + a] = tau[iv + a] - data.S[iv + a].dot(&pA);
        }
        let Dinv = D.try_inverse().ok_or(MultibodyError::NotPositiveDefinite)?;
        data.d_inv[i] = Dinv;
        if let Some(p) = j.parent {
            let mut Ia = IA;
            let mut corr = Vec6::zeros();
            for a in 0..nv {
                let Ua = data.u_cols[iv + a].to_vector();
                let mut w = Vec6::zeros(); // Σ_b Dinv_ab U_b
                let mut s = 0.0; // Σ_b Dinv_ab u_b
                for b in 0..nv {
                    w += data.u_cols[iv + b].to_vector() * Dinv[(a, b)];
                    s += Dinv[(a, b)] * data.u[iv + b];
                }
                Ia -= Ua * w.transpose();
                corr += Ua * s;
            }
            // p^a = p^A + I^a c + U D⁻¹ u
            let pa = pA + mat6_twist(&Ia, &data.c_bias[i]) + Wrench::from_vector(&corr);
            data.ia[p.0] += congruence(&Ia, &data.parent_placements[i]);
            data.pa[p.0] += data.parent_placements[i].act_wrench(&pa);
        }
    }
    // pass 3: accelerations
    let a_world = Twist::new(Vec3::zeros(), -model.gravity);
    for i in 0..n {
        let j = &model.joints()[i];
        let (iv, nv) = (j.idx_v, j.nv);
        let Ap = match j.parent {
            Some(p) => data.accelerations_gravity[p.0],
            None => a_world,
        };
        let mut A = data.parent_placements[i].inv_act_twist(&Ap) + data.c_bias[i];
        if nv == 1 {
            let x = data.d_inv_1[iv] * (data.u[iv] - A.dot(&data.u_cols[iv]));
            data.ddq[iv] = x;
            A += data.S[iv] * x;
            data.accelerations_gravity[i] = A;
            continue;
        }
        let Dinv = data.d_inv[i];
        let mut rhs = [0.0; 6];
        for (a, r) in rhs.iter_mut().enumerate().take(nv) {
            *r = data.u[iv + a] - A.dot(&data.u_cols[iv + a]);
        }
        for a in 0..nv {
            let mut x = 0.0;
            for b in 0..nv {
                x += Dinv[(a, b)] * rhs[b];
            }
            data.ddq[iv + a] = x;
            A += data.S[iv + a] * x;
        }
        data.accelerations_gravity[i] = A;
    }
    Ok(())
}

/// Forward dynamics `q̈ = M(q)⁻¹ (τ - c(q, v) - g(q))` by the articulated-body algorithm
/// (Featherstone 2008, Table 7.1), body coordinates, gravity as base acceleration `A_0 = -g`:
///
/// - pass 1 (i = 1..n): `V_i = [Ad_{liMi⁻¹}] V_{λ(i)} + S_i q̇_i`, `c_i = [ad_{V_i}] S_i q̇_i`,
///   `I^A_i = G_i`, `p^A_i = -[ad_{V_i}]ᵀ G_i V_i - F_i^ext`
/// - pass 2 (i = n..1): `U_i = I^A_i S_i`, `D_i = S_iᵀ U_i + armature_i`,
///   `u_i = τ_i - S_iᵀ p^A_i`; `I^a = I^A_i - U_i D_i⁻¹ U_iᵀ`, `p^a = p^A_i + I^a c_i + U_i D_i⁻¹ u_i`;
///   `I^A_{λ(i)} += Xᵀ I^a X`, `p^A_{λ(i)} += Xᵀ p^a` with `X = [Ad_{liMi⁻¹}]`
/// - pass 3 (i = 1..n): `A' = X A_{λ(i)} + c_i`, `q̈_i = D_i⁻¹ (u_i - U_iᵀ A')`, `A_i = A' + S_i q̈_i`
///
/// Returns `data.ddq`. O(n). Should the recursion meet a joint inertia `D_i ≤ 0` while `M` is
/// positive definite (digits lost to a light body carrying a heavy subtree), the answer comes from
/// the sparse Cholesky factorisation of `M` instead ([`forward_dynamics_cholesky`](crate::multibody::forward_dynamics_cholesky)).
///
/// # Errors
/// Wrong lengths, non-finite entries, a non-unit quaternion, or a singular `M` (a massless
/// subtree moved by a joint).
///
/// ```
/// use rigid::multibody::{aba, puma560, rnea, Data, Puma560Options};
/// let model = puma560(Puma560Options::default());
/// let mut data = Data::new(&model);
/// let (q, v, a) = ([0.1; 6], [0.2; 6], [0.3; 6]);
/// let tau = rnea(&model, &mut data, &q, &v, &a)?.clone();
/// let ddq = aba(&model, &mut data, &q, &v, tau.as_slice())?;
/// assert!(ddq.iter().zip(&a).all(|(x, y)| (x - y).abs() < 1e-9));
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn aba<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
) -> Result<&'a DVector<f64>, MultibodyError> {
    check_inputs(model, data, q, v, tau)?;
    match aba_impl(model, data, q, v, tau, None) {
        Err(MultibodyError::NotPositiveDefinite) => cholesky_fallback(model, data, q, v, tau, None),
        r => r.map(|()| &data.ddq),
    }
}

/// [`aba`] with an external wrench `fext[i]` on each body, in body i's frame.
///
/// # Errors
/// As [`aba`], and `fext.len() != njoints`.
pub fn aba_with_external<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    fext: &[Wrench],
) -> Result<&'a DVector<f64>, MultibodyError> {
    check_inputs(model, data, q, v, tau)?;
    DimensionError::check("fext", model.njoints(), fext.len())?;
    match aba_impl(model, data, q, v, tau, Some(fext)) {
        Err(MultibodyError::NotPositiveDefinite) => {
            cholesky_fallback(model, data, q, v, tau, Some(fext))
        }
        r => r.map(|()| &data.ddq),
    }
}

/// When ABA meets a joint inertia `D ≤ 0`, `M` may still be positive definite: the recursion's
/// subtraction `I^A - U D⁻¹ Uᵀ` loses every digit when a light body carries a heavy subtree (mass
/// ratios of 1e10 and more). Solve `M q̈ = τ - b` by the sparse Cholesky factorisation of `M`
/// instead ([`forward_dynamics_cholesky`](crate::multibody::forward_dynamics_cholesky)); a massless subtree makes `M` singular and stays an
/// error. No allocation (`data.nle` lends its storage for the zero acceleration).
fn cholesky_fallback<'a>(
    model: &Model,
    data: &'a mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    fext: Option<&[Wrench]>,
) -> Result<&'a DVector<f64>, MultibodyError> {
    // b = rnea(q, v, 0) with the external wrenches: c + g - Jᵀ f
    let mut zero = std::mem::take(&mut data.nle);
    zero.fill(0.0);
    let bias = match fext {
        Some(f) => super::rnea_with_external(model, data, q, v, zero.as_slice(), f).map(|_| ()),
        None => super::rnea(model, data, q, v, zero.as_slice()).map(|_| ()),
    };
    data.nle = zero;
    bias?;
    data.nle.copy_from(&data.tau);
    super::crba(model, data, q)?;
    super::cholesky::ltl_solve(model, data, tau)
}

/// The argument checks shared by [`aba`], [`aba_with_external`] and the ABA derivatives.
pub(crate) fn check_inputs(
    model: &Model,
    data: &Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
) -> Result<(), MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    check_v(model, "v", v)?;
    check_v(model, "tau", tau)
}
