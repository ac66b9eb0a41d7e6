//! The articulated-body algorithm for forward dynamics (Featherstone 2008, Table 7.1), in body
//! coordinates, and forward dynamics by Cholesky factorisation of `M` as a cross-check.

use super::{joint_motion, parent_placement};
use crate::error::DimensionError;
use crate::multibody::{check_data, check_q, check_v, Data, Model, MultibodyError};
use crate::spatial::{skew, Mat3, Mat6, Transform, Twist, Vec3, Vec6, Wrench};
use nalgebra::DVector;

/// `I V` for a 6x6 (articulated) inertia acting on a twist, giving a wrench (column-major loop
/// over a fixed-size array: unrolled, no bounds checks).
#[inline]
pub(crate) fn mat6_twist(m: &Mat6, t: &Twist) -> Wrench {
    let x = [t.w.x, t.w.y, t.w.z, t.v.x, t.v.y, t.v.z];
    let a: &[f64; 36] = m.as_slice().try_into().expect("6x6");
    let mut y = [0.0; 6];
    for c in 0..6 {
        for r in 0..6 {
            y[r] += a[c * 6 + r] * x[c];
        }
    }
    Wrench::new(Vec3::new(y[0], y[1], y[2]), Vec3::new(y[3], y[4], y[5]))
}

/// `I -= s u uᵀ` (symmetric rank-one update), in place.
#[inline]
fn sub_outer(m: &mut Mat6, u: &Wrench, s: f64) {
    let u = [u.m.x, u.m.y, u.m.z, u.f.x, u.f.y, u.f.z];
    let a: &mut [f64; 36] = m.as_mut_slice().try_into().expect("6x6");
    for c in 0..6 {
        let uc = u[c] * s;
        for r in 0..6 {
            a[c * 6 + r] -= u[r] * uc;
        }
    }
}

/// `Xᵀ I X` with `X = [Ad_{T⁻¹}]`, `T = liMi = (R, p)`: an inertia of the child expressed in the
/// parent frame, by 3x3 blocks `I = [[A, B], [Bᵀ, C]]`: first rotate
/// (`A' = R A Rᵀ`, `B' = R B Rᵀ`, `C' = R C Rᵀ`), then shift the origin by `p`:
/// `A'' = A' - B'[p] + [p]B'ᵀ - [p]C'[p]`, `B'' = B' + [p]C'`, `C'' = C'`.
#[inline]
pub(crate) fn congruence(I: &Mat6, T: &Transform) -> Mat6 {
    let R = &T.rotation;
    let A: Mat3 = I.fixed_view::<3, 3>(0, 0).into();
    let B: Mat3 = I.fixed_view::<3, 3>(0, 3).into();
    let C: Mat3 = I.fixed_view::<3, 3>(3, 3).into();
    let A1 = R * A * R.transpose();
    let B1 = R * B * R.transpose();
    let C1 = R * C * R.transpose();
    let P = skew(&T.translation);
    let B1P = B1 * P;
    let PC = P * C1;
    let A2 = A1 - B1P - B1P.transpose() - PC * P;
    let B2 = B1 + PC;
    let mut out = Mat6::zeros();
    out.fixed_view_mut::<3, 3>(0, 0).copy_from(&A2);
    out.fixed_view_mut::<3, 3>(0, 3).copy_from(&B2);
    out.fixed_view_mut::<3, 3>(3, 0).copy_from(&B2.transpose());
    out.fixed_view_mut::<3, 3>(3, 3).copy_from(&C1);
    out
}

/// [`congruence`] for `T = (R, p)` with `R` a rotation about the coordinate axis `k` (an
/// unrotated `X_T` times a revolute `X_J` about `±e_k`): `diag(R, R)` mixes only the rows and
/// columns of the two other axes (a plane rotation, read from `R`), and the shift by `p` is
/// `I ↦ Pᵀ I P` with `P = [[1, 0], [-[p], 1]]`: columns `0..3` gain `I[:, 3..6] (-[p])`, then rows
/// `0..3` gain `[p] I[3..6, :]`. ≈ 170 multiplications against ≈ 240 for the general path.
#[inline]
pub(crate) fn congruence_about_axis(I: &Mat6, T: &Transform, k: usize) -> Mat6 {
    match k {
        0 => congruence_plane::<1, 2>(I, T),
        1 => congruence_plane::<2, 0>(I, T),
        _ => congruence_plane::<0, 1>(I, T),
    }
}

/// The rotation mixes axes `A` and `B` (`(A, B, k)` cyclic): `R_AA = R_BB = c`, `R_BA = s`.
#[inline(always)]
fn congruence_plane<const A: usize, const B: usize>(I: &Mat6, T: &Transform) -> Mat6 {
    let r = T.rotation.as_slice(); // column-major
    let (c, s) = (r[3 * A + A], r[3 * A + B]);
    let mut m = [0.0; 36];
    m.copy_from_slice(I.as_slice()); // column-major: m[6 col + row]
                                     // diag(R, R) I: rows A, B (and A + 3, B + 3) of every column
    for col in 0..6 {
        for o in [0, 3] {
            let (x, y) = (m[6 * col + o + A], m[6 * col + o + B]);
            m[6 * col + o + A] = c * x - s * y;
            m[6 * col + o + B] = s * x + c * y;
        }
    }
    // (·) diag(R, R)ᵀ: columns A, B (and A + 3, B + 3)
    for o in [0, 3] {
        for row in 0..6 {
            let (x, y) = (m[6 * (o + A) + row], m[6 * (o + B) + row]);
            m[6 * (o + A) + row] = c * x - s * y;
            m[6 * (o + B) + row] = s * x + c * y;
        }
    }
    let p = [T.translation.x, T.translation.y, T.translation.z];
    // I P: column j < 3 += Σ_l I[:, 3 + l] (-[p])_lj, i.e. row-wise vᵀ (-[p]) = (p × v)ᵀ
    for row in 0..6 {
        let v = [m[18 + row], m[24 + row], m[30 + row]];
        m[row] += p[1] * v[2] - p[2] * v[1];
        m[6 + row] += p[2] * v[0] - p[0] * v[2];
        m[12 + row] += p[0] * v[1] - p[1] * v[0];
    }
    // Pᵀ (·): row i < 3 += ([p] I[3..6, :])_i, column-wise p × v
    for col in 0..6 {
        let v = [m[6 * col + 3], m[6 * col + 4], m[6 * col + 5]];
        m[6 * col] += p[1] * v[2] - p[2] * v[1];
        m[6 * col + 1] += p[2] * v[0] - p[0] * v[2];
        m[6 * col + 2] += p[0] * v[1] - p[1] * v[0];
    }
    Mat6::from_column_slice(&m)
}

fn aba_impl(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    fext: Option<&[Wrench]>,
) -> Result<(), MultibodyError> {
    let n = model.joints.len();
    // pass 1: kinematics, bias forces
    for i in 0..n {
        let liMi = parent_placement(model, i, q);
        data.parent_placements[i] = liMi;
        let Vp = match model.joints[i].parent {
            Some(p) => data.velocities[p.0],
            None => Twist::zero(),
        };
        let vJ = joint_motion(model, i, v);
        let V = liMi.inv_act_twist(&Vp) + vJ;
        data.velocities[i] = V;
        data.c_bias[i] = V.cross(&vJ);
        let G = &model.inertias[i];
        data.ia[i] = G.matrix();
        let mut pA = -V.ad_transpose(&G.momentum(&V));
        if let Some(f) = fext {
            pA -= f[i];
        }
        data.pa[i] = pA;
    }
    // pass 2: articulated inertias
    for i in (0..n).rev() {
        let j = &model.joints[i];
        let (iv, nv) = (j.idx_v, j.nv);
        let pA = data.pa[i];
        if nv == 1 {
            // one degree of freedom: D and u are scalars
            let IA = &data.ia[i];
            let S = &model.dof_S[iv];
            // U = I^A S, Sᵀ U, Sᵀ p^A: for S = s e_c a column and two components
            let (U, SU, Sp) = match model.dof_axis[iv] {
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
                head[p.0] += match model.dof_axis[iv] {
                    Some((k, _)) if k < 3 && model.unrotated[i] => congruence_about_axis(Ia, X, k),
                    _ => congruence(Ia, X),
                };
                data.pa[p.0] += X.act_wrench(&pa);
            }
            continue;
        }
        let IA = data.ia[i];
        for a in 0..nv {
            data.u_cols[iv + a] = mat6_twist(&IA, &model.dof_S[iv + a]);
        }
        let mut D = Mat6::identity();
        for a in 0..nv {
            for b in 0..nv {
                D[(a, b)] = model.dof_S[iv + a].dot(&data.u_cols[iv + b]);
            }
            D[(a, a)] += model.armature[iv + a];
            data.u[iv + a] = tau[iv + a] - model.dof_S[iv + a].dot(&pA);
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
        let j = &model.joints[i];
        let (iv, nv) = (j.idx_v, j.nv);
        let Ap = match j.parent {
            Some(p) => data.accelerations_gravity[p.0],
            None => a_world,
        };
        let mut A = data.parent_placements[i].inv_act_twist(&Ap) + data.c_bias[i];
        if nv == 1 {
            let x = data.d_inv_1[iv] * (data.u[iv] - A.dot(&data.u_cols[iv]));
            data.ddq[iv] = x;
            A += model.dof_S[iv] * x;
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
            A += model.dof_S[iv + a] * x;
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
/// the sparse Cholesky factorisation of `M` instead ([`forward_dynamics_cholesky`]).
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
/// instead ([`forward_dynamics_cholesky`]); a massless subtree makes `M` singular and stays an
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

#[cfg(test)]
mod tests {
    use super::{congruence, congruence_about_axis};
    use crate::mass::{RotationalInertia, SpatialInertia};
    use crate::spatial::{so3, Mat6, Transform, Vec3};

    /// The written-out congruence equals `[Ad_{T⁻¹}]ᵀ I [Ad_{T⁻¹}]` with the dense adjoint, on a
    /// general symmetric 6x6 (an articulated inertia has no spatial-inertia structure).
    #[test]
    fn congruence_equals_the_dense_product() {
        let T = Transform::new(
            so3::exp(&Vec3::new(0.3, -1.1, 0.7)),
            Vec3::new(0.4, -0.2, 0.9),
        );
        let G = SpatialInertia::from_com(
            2.0,
            Vec3::new(0.1, 0.2, -0.3),
            RotationalInertia::diagonal(0.5, 0.7, 0.9),
        )
        .matrix();
        let mut I = G + Mat6::from_fn(|r, c| ((r * 7 + c * 3) % 5) as f64 * 0.01);
        I = (I + I.transpose()) * 0.5;
        let X = T.inverse().adjoint();
        let dense = X.transpose() * I * X;
        let fast = congruence(&I, &T);
        assert!(
            (dense - fast).amax() < 1e-12 * dense.amax(),
            "{}",
            dense - fast
        );
    }

    /// The plane-rotation path equals the general one for rotations about each axis (±angle).
    #[test]
    fn congruence_about_an_axis_equals_the_general_one() {
        let G = SpatialInertia::from_com(
            1.5,
            Vec3::new(-0.2, 0.1, 0.3),
            RotationalInertia::diagonal(0.4, 0.6, 0.8),
        )
        .matrix();
        let mut I = G + Mat6::from_fn(|r, c| ((r * 5 + c * 2) % 7) as f64 * 0.01);
        I = (I + I.transpose()) * 0.5;
        for k in 0..3 {
            for angle in [0.7, -2.3] {
                let T = Transform::new(
                    so3::exp(&(Vec3::ith(k, 1.0) * angle)),
                    Vec3::new(0.3, -0.5, 0.2),
                );
                let (a, b) = (congruence(&I, &T), congruence_about_axis(&I, &T, k));
                assert!((a - b).amax() < 1e-12 * a.amax(), "axis {k}: {}", a - b);
            }
        }
    }
}
