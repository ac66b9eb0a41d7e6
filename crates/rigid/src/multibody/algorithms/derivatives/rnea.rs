//! The derivatives of inverse dynamics, `∂τ/∂q`, `∂τ/∂v`, `∂τ/∂a = M`, and of the generalised
//! gravity `∂g/∂q`, in one forward and one backward pass (Carpentier & Mansard, "Analytical
//! derivatives of rigid body dynamics algorithms", RSS 2018, Alg. 1), with every quantity in one
//! frame per tree (its root body's, as [`crba`](crate::multibody::crba)).

use super::Derivatives;
use crate::mass::SpatialInertia;
use crate::multibody::algorithms::{parent_placement, root_frame_bodies};
use crate::multibody::{check_data, check_q, check_v, Data, Model, MultibodyError};
use crate::spatial::{mat3_tr_vec, Twist, Vec3, Wrench};
use nalgebra::{DMatrix, DVector};

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

/// Which derivatives a pass computes.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Pass {
    /// `∂τ/∂q`, `∂τ/∂v` and `M` at `(q, v, a)`: into `dtau_dq`, `dtau_dv`, `mass_matrix`, `tau`.
    Full,
    /// `∂g/∂q` at `v = a = 0`: into `dg_dq` and `g`.
    Gravity,
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
    fext: &[crate::spatial::Wrench],
) -> Result<RneaDerivatives<'a>, MultibodyError> {
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
    check_q(model, q)?;
    check_data(model, data)?;
    derivatives_unchecked(model, data, q, None, None);
    Ok(&data.derivatives.dg_dq)
}

/// Both passes on checked inputs: `va = None` is the gravity pass.
pub(crate) fn derivatives_unchecked(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    va: Option<(&[f64], &[f64])>,
    fext: Option<&[Wrench]>,
) {
    forward(model, data, q, va, fext);
    let pass = if va.is_some() {
        Pass::Full
    } else {
        Pass::Gravity
    };
    backward(model, data, va.map(|(_, a)| a), pass);
}

/// The forward pass: root-frame placements, columns and inertias, then twists, accelerations,
/// forces and the per-dof variations.
fn forward(
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
        &mut data.composite_inertias,
    );
    let d = &mut data.derivatives;
    let J = &data.dof_J;
    let mut a_g = Twist::zero();
    for i in 0..model.joints.len() {
        let j = &model.joints[i];
        let (Vp, Ap) = match j.parent {
            Some(p) => (d.vel[p.0], d.acc[p.0]),
            None => {
                // the tree's frame {r}: its root body at q, where gravity is -Rᵀ g
                let oMr = parent_placement(model, i, q);
                a_g = Twist::new(Vec3::zeros(), -mat3_tr_vec(&oMr.rotation, &model.gravity));
                (Twist::zero(), a_g)
            }
        };
        let G = &data.composite_inertias[i];
        let dofs = j.idx_v..j.idx_v + j.nv;
        let Some((v, a)) = va else {
            // gravity only: V = 0, A = a_g
            d.vel[i] = Twist::zero();
            d.acc[i] = a_g;
            d.force[i] = G.momentum(&a_g);
            for k in dofs {
                d.da_dq[k] = a_g.cross(&J[k]);
            }
            continue;
        };
        let (mut vJ, mut aJ) = (Twist::zero(), Twist::zero());
        for k in dofs.clone() {
            vJ += J[k] * v[k];
            aJ += J[k] * a[k];
        }
        let V = Vp + vJ;
        let A = Ap + aJ + V.cross(&vJ);
        let h = G.momentum(&V);
        let mut f = G.momentum(&A) - V.ad_transpose(&h);
        if let Some(fext) = fext {
            f -= data.root_placements[i].act_wrench(&fext[i]);
        }
        d.vel[i] = V;
        d.acc[i] = A;
        d.force[i] = f;
        d.momentum[i] = h;
        d.sym[i] = variation_sym(G, &V);
        let W = V + Vp;
        for k in dofs {
            let Jk = J[k];
            let dv = Vp.cross(&Jk);
            d.dv_dq[k] = dv;
            d.da_dq[k] = Ap.cross(&Jk) + Vp.cross(&dv);
            d.da_dv[k] = W.cross(&Jk);
        }
    }
}

/// The symmetric part of the angular block of `B` for a body of inertia `G = (m, c, I)` (about
/// the frame origin, `c = m·com`) moving with `V = (ω, v)`:
/// `[ω]I - I[ω] - [c][v] - [v][c] = K + Kᵀ - c vᵀ - v cᵀ + 2 (c·v) 1` with `K = [ω] I` (the
/// columns of `I` crossed with `ω`; `I[ω] = -([ω]I)ᵀ`), stored `xx yy zz xy xz yz`.
#[inline]
fn variation_sym(G: &SpatialInertia, V: &Twist) -> [f64; 6] {
    let I = G.inertia_origin_matrix();
    let (c, w, v) = (G.first_moment(), V.w, V.v);
    let k0 = w.cross(&I.column(0).into_owned());
    let k1 = w.cross(&I.column(1).into_owned());
    let k2 = w.cross(&I.column(2).into_owned());
    let cv2 = 2.0 * c.dot(&v);
    [
        2.0 * (k0.x - c.x * v.x) + cv2,
        2.0 * (k1.y - c.y * v.y) + cv2,
        2.0 * (k2.z - c.z * v.z) + cv2,
        k1.x + k0.y - c.x * v.y - v.x * c.y,
        k2.x + k0.z - c.x * v.z - v.x * c.z,
        k2.y + k1.z - c.y * v.z - v.y * c.z,
    ]
}

/// `S x` for a symmetric 3x3 stored `xx yy zz xy xz yz`.
#[inline(always)]
fn sym_mul(s: &[f64; 6], x: &Vec3) -> Vec3 {
    Vec3::new(
        s[0] * x.x + s[3] * x.y + s[4] * x.z,
        s[3] * x.x + s[1] * x.y + s[5] * x.z,
        s[4] * x.x + s[5] * x.y + s[2] * x.z,
    )
}

/// `Bc x = ((S - [L]) x_ω, -2 p × x_ω)` for the composite `S`, momentum `(L, p)` (`x_v` does not
/// enter).
#[inline(always)]
fn b_times(s: &[f64; 6], h: &Wrench, xw: &Vec3) -> Wrench {
    Wrench::new(sym_mul(s, xw) - h.m.cross(xw), -2.0 * h.f.cross(xw))
}

/// The backward pass: composite sums, then the rows and columns of each joint's dofs.
fn backward(model: &Model, data: &mut Data, a: Option<&[f64]>, pass: Pass) {
    let nv = model.nv;
    let Data {
        derivatives: d,
        dof_J: J,
        composite_inertias: Ic,
        mass_matrix,
        tau,
        g,
        ..
    } = data;
    let Derivatives {
        dtau_dq,
        dtau_dv,
        dg_dq,
        force,
        momentum,
        sym,
        dv_dq,
        da_dq,
        da_dv,
        yj,
        bj,
        df_dq,
        df_dv,
        dof_end,
        ..
    } = d;
    let full = pass == Pass::Full;
    let (dq, tau): (&mut [f64], &mut DVector<f64>) = if full {
        (dtau_dq.as_mut_slice(), tau)
    } else {
        (dg_dq.as_mut_slice(), g)
    };
    let dv = dtau_dv.as_mut_slice();
    let M = mass_matrix.as_mut_slice();
    // column-major: entry (row r, column c) at c * nv + r
    for i in (0..model.joints.len()).rev() {
        let j = &model.joints[i];
        let (Y, F) = (Ic[i], force[i]);
        let (iv, own) = (j.idx_v, j.idx_v + j.nv);
        let end = dof_end[iv];
        let (S, H) = (sym[i], momentum[i]);
        for k in iv..own {
            let Jk = J[k];
            tau[k] = Jk.dot(&F) + a.map_or(0.0, |a| model.armature[k] * a[k]);
            if full {
                yj[k] = Y.momentum(&Jk);
                bj[k] = sym_mul(&S, &Jk.w) + H.m.cross(&Jk.w) + 2.0 * H.f.cross(&Jk.v);
                df_dq[k] = Y.momentum(&da_dq[k]) + b_times(&S, &H, &dv_dq[k].w);
                df_dv[k] = Y.momentum(&da_dv[k]) + b_times(&S, &H, &Jk.w);
            } else {
                df_dq[k] = Y.momentum(&da_dq[k]);
                yj[k] = Y.momentum(&Jk);
            }
        }
        // rows of the joint's dofs, columns of its subtree
        for k in iv..own {
            let Jk = J[k];
            for c in iv..end {
                dq[c * nv + k] = Jk.dot(&df_dq[c]);
            }
            if full {
                for c in iv..end {
                    dv[c * nv + k] = Jk.dot(&df_dv[c]);
                    M[c * nv + k] = Jk.dot(&yj[c]);
                }
                M[k * nv + k] += model.armature[k];
            }
        }
        // columns of the joint's dofs, rows of its strict subtree
        for k in iv..own {
            let col = k * nv;
            for c in own..end {
                dq[col + c] = da_dq[k].dot(&yj[c]);
            }
            if full {
                let (dvq, dav, Jw) = (dv_dq[k].w, da_dv[k], J[k].w);
                for c in own..end {
                    dq[col + c] += bj[c].dot(&dvq);
                    dv[col + c] = dav.dot(&yj[c]) + bj[c].dot(&Jw);
                    M[col + c] = M[c * nv + k];
                }
            }
        }
        // J_k ×* F for the ancestors' rows (it cancels the turning of J_k in the own block)
        for k in iv..own {
            df_dq[k] -= J[k].ad_transpose(&F);
        }
        if let Some(p) = j.parent {
            Ic[p.0] += Y;
            force[p.0] += F;
            if full {
                momentum[p.0] += H;
                let sp = &mut sym[p.0];
                for (x, y) in sp.iter_mut().zip(S) {
                    *x += y;
                }
            }
        }
    }
}
