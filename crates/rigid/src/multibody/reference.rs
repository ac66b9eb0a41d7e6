//! **Read this first.** Inverse dynamics, the mass matrix and forward dynamics as the textbook
//! writes them: Featherstone's spatial_v2 (`ID.m`, `HandC.m`, `FDab.m`; *Rigid Body Dynamics
//! Algorithms*, 2008, Tables 5.1, 6.2 and 7.1) in rigid's notation, one screen each, for every
//! joint type, with 6x6 matrices and no shortcut.
//!
//! | book | here | meaning |
//! | --- | --- | --- |
//! | `Xup{i}` | `X[i]` = `[Ad_{liMi⁻¹}]` | parent coordinates to body i's, `liMi = X_T X_J(q_i)` |
//! | `S{i}`, `c_J` | [`JointType::subspace`], [`JointType::bias`] | motion subspace and joint bias acceleration, child frame |
//! | `crm(v)`, `crf(v)` | `[ad_V]`, `-[ad_V]ᵀ` ([`Twist::ad`](crate::spatial::Twist::ad)) | spatial cross products |
//! | `I{i}` | `G[i]` ([`SpatialInertia::matrix`](crate::mass::SpatialInertia::matrix)) | body inertia in its frame |
//! | `a_grav` | `-A_0 = g` | gravity as a fictitious base acceleration `A_0 = (0, -g)` |
//!
//! Twists and wrenches are angular first. The joint armature `J_a` (on the diagonal of `M`) enters
//! as in the fast algorithms: `τ_k += J_a,k q̈_k`, `M_kk += J_a,k`, `D_i += diag(J_a)`.
//!
//! The fast algorithms ([`rnea`](super::rnea), [`crba`](super::crba), [`aba`](super::aba))
//! compute the same numbers with the allocations, the 6x6 products and the joint dispatch taken
//! out; the test suite checks them against these on random trees of every joint type and on real
//! robots. These functions allocate: they are for reading, testing and checking.
//!
//! ```
//! use rigid::multibody::{builtin, reference, rnea, Data};
//! let model = builtin("puma560").unwrap();
//! let (q, v, a) = ([0.1, -0.4, 0.9, 0.2, -0.3, 1.1], [0.5; 6], [-1.0; 6]);
//! let tau = reference::rnea(&model, &q, &v, &a)?;
//! let mut data = Data::new(&model);
//! assert!((rnea(&model, &mut data, &q, &v, &a)? - &tau).amax() < 1e-12);
//! let ddq = reference::aba(&model, &q, &v, tau.as_slice())?;
//! assert!(ddq.iter().zip(a).all(|(x, y)| (x - y).abs() < 1e-9));
//! # Ok::<(), rigid::multibody::MultibodyError>(())
//! ```

use super::{check_q, check_v, JointType, Model, MultibodyError};
use crate::spatial::{Mat6, Twist, Vec6};
use nalgebra::{DMatrix, DVector, Matrix6xX};

/// Per body: `X = [Ad_{liMi⁻¹}]` (parent to body), the columns of `S` (6 x nv) and `c_J`
/// (Featherstone's `jcalc` and `Xup{i} = XJ * Xtree{i}`).
fn jcalc(model: &Model, q: &[f64], v: &[f64]) -> Vec<(Mat6, Matrix6xX<f64>, Vec6)> {
    let joints = model.joints().iter();
    joints
        .map(|j| {
            let (qi, vi) = (&q[j.coordinates()], &v[j.dofs()]);
            let X = j
                .kind
                .placed_transform(&j.placement, qi)
                .inverse()
                .adjoint();
            (X, subspace(&j.kind, qi), j.kind.bias(qi, vi).to_vector())
        })
        .collect()
}

/// `S(q)` as a 6 x nv matrix.
fn subspace(kind: &JointType, q: &[f64]) -> Matrix6xX<f64> {
    let mut S = [Twist::zero(); 6];
    kind.subspace(q, &mut S[..kind.nv()]);
    Matrix6xX::from_fn(kind.nv(), |r, c| S[c].to_vector()[r])
}

/// `S x` for the joint's slice `x` of a velocity-like vector, as a 6-vector.
fn times(S: &Matrix6xX<f64>, x: &[f64]) -> Vec6 {
    S * DVector::from_column_slice(x)
}

/// `crm(v) = [ad_V]`.
fn crm(v: &Vec6) -> Mat6 {
    Twist::from_vector(v).ad()
}

/// spatial_v2's `a_grav`: gravity as a spatial acceleration `(0, g)`; the base moves with `−a_grav`.
fn a_grav(model: &Model) -> Vec6 {
    let g = model.gravity;
    Vec6::new(0.0, 0.0, 0.0, g.x, g.y, g.z)
}

/// Inverse dynamics `τ = M(q) q̈ + c(q, q̇) + g(q)` (spatial_v2 `ID.m`; Featherstone 2008,
/// Table 5.1).
///
/// # Errors
/// Wrong lengths, non-finite entries, or a non-unit quaternion.
pub fn rnea(
    model: &Model,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
) -> Result<DVector<f64>, MultibodyError> {
    check_q(model, q)?;
    check_v(model, "v", qd)?;
    check_v(model, "a", qdd)?;
    let a_grav = a_grav(model);
    let joints = model.joints();
    let bodies = jcalc(model, q, qd);
    let (mut v, mut a, mut f) = (Vec::<Vec6>::new(), Vec::<Vec6>::new(), Vec::<Vec6>::new());
    for (i, (j, (X, S, cJ))) in joints.iter().zip(&bodies).enumerate() {
        let vJ = times(S, &qd[j.dofs()]);
        let (vp, ap) = j
            .parent
            .map_or((Vec6::zeros(), -a_grav), |p| (v[p.0], a[p.0]));
        v.push(X * vp + vJ);
        a.push(X * ap + times(S, &qdd[j.dofs()]) + cJ + crm(&v[i]) * vJ);
        let I = model.inertias()[i].matrix();
        f.push(I * a[i] - crm(&v[i]).transpose() * (I * v[i]));
    }
    let mut tau = DVector::zeros(model.nv());
    for (i, (j, (X, S, _))) in joints.iter().zip(&bodies).enumerate().rev() {
        for (c, k) in j.dofs().enumerate() {
            tau[k] = S.column(c).dot(&f[i]) + model.armature()[k] * qdd[k];
        }
        if let Some(p) = j.parent {
            let fp = X.transpose() * f[i];
            f[p.0] += fp;
        }
    }
    Ok(tau)
}

/// The joint-space inertia matrix `M(q)` by the composite-rigid-body algorithm (spatial_v2
/// `HandC.m`; Featherstone 2008, Table 6.2): `M_ij = S_iᵀ Ic_i S_j` up the tree.
///
/// # Errors
/// Wrong length, non-finite entries, or a non-unit quaternion in `q`.
pub fn crba(model: &Model, q: &[f64]) -> Result<DMatrix<f64>, MultibodyError> {
    check_q(model, q)?;
    let joints = model.joints();
    let bodies = jcalc(model, q, &vec![0.0; model.nv()]);
    let mut Ic: Vec<Mat6> = model.inertias().iter().map(|G| G.matrix()).collect();
    for (i, j) in joints.iter().enumerate().rev() {
        if let Some(p) = j.parent {
            let X = &bodies[i].0;
            let Icp = X.transpose() * Ic[i] * X;
            Ic[p.0] += Icp;
        }
    }
    let mut H = DMatrix::from_diagonal(&DVector::from_column_slice(model.armature()));
    for (i, j) in joints.iter().enumerate() {
        let mut fh = Ic[i] * &bodies[i].1; // 6 x nv_i
        let mut Hii = H.view_mut((j.idx_v, j.idx_v), (j.nv, j.nv));
        Hii += bodies[i].1.transpose() * &fh;
        let mut k = i;
        while let Some(p) = joints[k].parent {
            fh = bodies[k].0.transpose() * fh;
            k = p.0;
            let (jk, Hkj) = (&joints[k], bodies[k].1.transpose() * &fh);
            H.view_mut((jk.idx_v, j.idx_v), (jk.nv, j.nv))
                .copy_from(&Hkj);
            H.view_mut((j.idx_v, jk.idx_v), (j.nv, jk.nv))
                .copy_from(&Hkj.transpose());
        }
    }
    Ok(H)
}

/// Forward dynamics `q̈ = M⁻¹ (τ - c - g)` by the articulated-body algorithm (spatial_v2
/// `FDab.m`; Featherstone 2008, Table 7.1).
///
/// # Errors
/// Wrong lengths, non-finite entries, a non-unit quaternion, or a joint whose articulated
/// inertia `D_i = S_iᵀ I^A_i S_i` is singular ([`MultibodyError::NotPositiveDefinite`]).
pub fn aba(
    model: &Model,
    q: &[f64],
    qd: &[f64],
    tau: &[f64],
) -> Result<DVector<f64>, MultibodyError> {
    check_q(model, q)?;
    check_v(model, "v", qd)?;
    check_v(model, "tau", tau)?;
    let a_grav = a_grav(model);
    let joints = model.joints();
    let bodies = jcalc(model, q, qd);
    let (mut v, mut c) = (Vec::<Vec6>::new(), Vec::<Vec6>::new());
    let mut IA: Vec<Mat6> = model.inertias().iter().map(|G| G.matrix()).collect();
    let mut pA = Vec::<Vec6>::new();
    for (i, (j, (X, S, cJ))) in joints.iter().zip(&bodies).enumerate() {
        let vJ = times(S, &qd[j.dofs()]);
        v.push(j.parent.map_or(Vec6::zeros(), |p| X * v[p.0]) + vJ);
        c.push(crm(&v[i]) * vJ + cJ);
        pA.push(-crm(&v[i]).transpose() * (IA[i] * v[i]));
    }
    let n = joints.len();
    let (mut U, mut Dinv) = (vec![Matrix6xX::zeros(0); n], vec![DMatrix::zeros(0, 0); n]);
    let mut u = vec![DVector::zeros(0); n];
    for (i, (j, (X, S, _))) in joints.iter().zip(&bodies).enumerate().rev() {
        let Ui = IA[i] * S; // 6 x nv_i
        let armature = DVector::from_column_slice(&model.armature()[j.dofs()]);
        let D = S.transpose() * &Ui + DMatrix::from_diagonal(&armature);
        let Di = D.try_inverse().ok_or(MultibodyError::NotPositiveDefinite)?;
        let ui = DVector::from_column_slice(&tau[j.dofs()]) - S.transpose() * pA[i];
        if let Some(p) = j.parent {
            let Ia = IA[i] - &Ui * &Di * Ui.transpose();
            let pa = pA[i] + Ia * c[i] + times(&Ui, (&Di * &ui).as_slice());
            IA[p.0] += X.transpose() * Ia * X;
            pA[p.0] += X.transpose() * pa;
        }
        (U[i], Dinv[i], u[i]) = (Ui, Di, ui);
    }
    let mut qdd = DVector::zeros(model.nv());
    let mut a = Vec::<Vec6>::new();
    for (i, (j, (X, S, _))) in joints.iter().zip(&bodies).enumerate() {
        let ap = j.parent.map_or(-a_grav, |p| a[p.0]);
        let ai = X * ap + c[i];
        let qddi = &Dinv[i] * (&u[i] - U[i].transpose() * ai);
        a.push(ai + times(S, qddi.as_slice()));
        qdd.rows_mut(j.idx_v, j.nv).copy_from(&qddi);
    }
    Ok(qdd)
}
