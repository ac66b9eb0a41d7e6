//! The derivatives of inverse dynamics on a pack of `W` states: the single call's algorithm
//! ([`rnea_derivatives`](crate::multibody::rnea_derivatives), Carpentier & Mansard, "Analytical
//! derivatives of rigid body dynamics algorithms", RSS 2018, Alg. 1, every quantity in the frame
//! {r} of each tree's root body frozen at `q`), step for step in lanes, with the bodies posed in
//! {r} as the lane CRBA poses them ([`root_frame_body`]). Only `∂τ/∂q` and `∂τ/∂v` are written
//! (not `τ`, not `M`), row-major per lane, into [`DerivPack::dq`] and [`DerivPack::dv`].

use super::crba::{inertia_twist, root_frame_body, turn_angles};
use super::lanes::{Aligned, L, S3, T6, V3};
use super::pack::{Pack, I3};
use super::pose::placement;
use crate::multibody::{JointType, Model};

/// The derivatives' workspace of one pack, made on its first use (a [`Pack`] that never
/// computes them does not hold one): per joint, in its tree's root frame, the twist `V_i`, the
/// bias acceleration `A⁰_i` (velocity terms and gravity), the acceleration `A_i`, its part
/// `A_i − A⁰_i` from `q̈`, the force `f_i` (then the composite `F_i`), the momentum `h_i = G_i V_i`
/// (then its composite), the symmetric part of `B_i`'s angular block (`xx yy zz xy xz yz`, then
/// its composite) and, at a root, `g' = −R_rootᵀ g`; per dof `∂V/∂q_k`, `∂A/∂q_k`, `∂A/∂v_k`,
/// `Ic J_k`, `(Bcᵀ J_k)_ω`, `∂F/∂q_k`, `∂F/∂v_k`; the two `nv x nv` outputs, row-major (entries
/// between branches are never written and stay zero).
#[derive(Clone, Debug)]
pub(crate) struct DerivPack<const W: usize> {
    vel: Aligned<T6<W>>,
    acc0: Aligned<T6<W>>,
    acc: Aligned<T6<W>>,
    acc_a: Aligned<T6<W>>,
    force: Aligned<T6<W>>,
    momentum: Aligned<T6<W>>,
    sym: Aligned<S3<W>>,
    gravity: Aligned<V3<W>>,
    dv_dq: Aligned<T6<W>>,
    da_dq: Aligned<T6<W>>,
    da_dv: Aligned<T6<W>>,
    yj: Aligned<T6<W>>,
    bj: Aligned<V3<W>>,
    df_dq: Aligned<T6<W>>,
    df_dv: Aligned<T6<W>>,
    /// `∂τ/∂q` and `∂τ/∂v`, entry `(r, c)` at `r nv + c`.
    pub(crate) dq: Aligned<L<W>>,
    pub(crate) dv: Aligned<L<W>>,
}

impl<const W: usize> DerivPack<W> {
    /// The workspace for `model`'s shape.
    pub(crate) fn new(model: &Model) -> Self {
        let (n, nv) = (model.njoints(), model.nv());
        let (z, zj, zk) = (
            L::zero(),
            Aligned::new(T6::zero(), n),
            Aligned::new(T6::zero(), nv),
        );
        Self {
            vel: zj.clone(),
            acc0: zj.clone(),
            acc: zj.clone(),
            acc_a: zj.clone(),
            force: zj.clone(),
            momentum: zj,
            sym: Aligned::new(S3([z; 6]), n),
            gravity: Aligned::new(V3::zero(), n),
            dv_dq: zk.clone(),
            da_dq: zk.clone(),
            da_dv: zk.clone(),
            yj: zk.clone(),
            bj: Aligned::new(V3::zero(), nv),
            df_dq: zk.clone(),
            df_dv: zk,
            dq: Aligned::new(z, nv * nv),
            dv: Aligned::new(z, nv * nv),
        }
    }
}

/// `∂τ/∂q` and `∂τ/∂v` at `(q, v, a)` for the pack's states (`q`, `v`, `x = a` in) into
/// `p.deriv`'s `dq` and `dv` (made on the first call), as the single call computes them:
///
/// forward, `i = 1..n` ([`turn_angles`], then [`root_frame_body`]: `rMi`,
/// `J_k = [Ad_{rMi}] S_k`, `G_i` in {r}; at a root `V_λ = 0`,
/// `A⁰_λ = A_λ = a_g = (0, −R_rootᵀ g)` with `R_root` from `X_T X_J(q)`):
/// `V_i = V_λ + Σ_k J_k v_k`, `A⁰_i = A⁰_λ + V_i × Σ_k J_k v_k`, `A_i = A⁰_i + A^a_λ + Σ_k J_k a_k`,
/// `f_i = G_i A_i + V_i ×* G_i V_i`, `h_i = G_i V_i`, the symmetric part of `B_i`'s angular block
/// `[ω]I − I[ω] − [c][v] − [v][c]`, and per dof `∂V/∂q_k = V_λ × J_k`,
/// `∂A/∂v_k = (V_i + V_λ) × J_k`, `∂A/∂q_k = A_λ × J_k + V_λ × ∂V/∂q_k`;
/// backward, `i = n..1`, with the composites `Ic`, `Bc`, `F` summed in place: per dof
/// `∂F/∂q_k = Ic ∂A/∂q_k + Bc ∂V/∂q_k`, `∂F/∂v_k = Ic ∂A/∂v_k + Bc J_k`; rows
/// `∂τ_k/∂x_c = J_kᵀ ∂F/∂x_c` over the subtree, columns
/// `∂τ_c/∂q_k = (Ic J_c)ᵀ ∂A/∂q_k + (Bcᵀ J_c)ᵀ ∂V/∂q_k`, `∂τ_c/∂v_k = (Ic J_c)ᵀ ∂A/∂v_k +
/// (Bcᵀ J_c)ᵀ J_k` over the strict subtree, then `∂F/∂q_k += J_k ×* F_i` for the ancestors' rows.
/// A free-flyer root (`J_k = e_k`) reads its rows off `∂F/∂x_c` and its columns off
/// `(Ic J_c)_f × g'` and `−[ad_V]ᵀ (Ic J_c) + (Bcᵀ J_c, 0)` ([`free_flyer_root`]).
///
/// The joints' motion subspaces are constant (the caller refused the others).
#[inline(always)]
pub(super) fn rnea_derivatives<const W: usize>(model: &Model, p: &mut Pack<W>) {
    let mut d = p
        .deriv
        .take()
        .unwrap_or_else(|| Box::new(DerivPack::new(model)));
    p.update_subspaces(model);
    turn_angles(model, p);
    forward(model, p, &mut d);
    backward(model, p, &mut d);
    p.deriv = Some(d);
}

/// The single call's `forward_velocity` and `forward_acceleration` in one pass (each joint reads
/// only its parent's results of both), in their order of operations.
#[inline(always)]
fn forward<const W: usize>(model: &Model, p: &mut Pack<W>, d: &mut DerivPack<W>) {
    for (i, j) in model.joints().iter().enumerate() {
        root_frame_body(model, p, i);
        let (Vp, A0p, Ap, Aap) = match j.parent {
            Some(par) => (d.vel[par.0], d.acc0[par.0], d.acc[par.0], d.acc_a[par.0]),
            None => {
                // the tree's frame {r}: its root body at q, where gravity is −Rᵀ g
                let oMr = placement(model, i, &p.q);
                let g = -oMr.r.tr_mul_v(&V3::splat(&model.gravity()));
                d.gravity[i] = g;
                let a_g = T6 {
                    w: V3::zero(),
                    v: g,
                };
                (T6::zero(), a_g, a_g, T6::zero())
            }
        };
        let G = p.Ic[i];
        let mut vJ = T6::zero();
        for k in j.dofs() {
            vJ += p.J[k].scale(p.v[k]);
        }
        let V = Vp + vJ;
        let A0 = A0p + V.cross(&vJ);
        let h = inertia_twist(&G, &V);
        // G A⁰ − [ad_V]ᵀ h, the subtraction of the negated product written as an addition
        let mut f = inertia_twist(&G, &A0) + V.cross_star(&h);
        d.sym[i] = variation_sym(&G, &V);
        let Vs = V + Vp;
        for k in j.dofs() {
            d.dv_dq[k] = Vp.cross(&p.J[k]);
            d.da_dv[k] = Vs.cross(&p.J[k]);
        }
        let mut Aa = Aap;
        for k in j.dofs() {
            Aa += p.J[k].scale(p.x[k]);
        }
        f += inertia_twist(&G, &Aa);
        d.vel[i] = V;
        d.acc0[i] = A0;
        d.acc_a[i] = Aa;
        d.acc[i] = A0 + Aa;
        d.force[i] = f;
        d.momentum[i] = h;
        // V_λ = 0 at a root: ∂A/∂q_k = A_λ × J_k (elsewhere a zero V_λ adds zeros)
        for k in j.dofs() {
            d.da_dq[k] = match j.parent {
                None => Ap.cross(&p.J[k]),
                Some(_) => Ap.cross(&p.J[k]) + Vp.cross(&d.dv_dq[k]),
            };
        }
    }
}

/// The single call's `backward` for `Output::Full` without `τ` and `M`: the composites summed in
/// place (`p.Ic`, `d.force`, `d.momentum`, `d.sym`), the rows and columns of each joint's dofs.
#[inline(always)]
fn backward<const W: usize>(model: &Model, p: &mut Pack<W>, d: &mut DerivPack<W>) {
    let nv = model.nv();
    let joints = model.joints();
    for i in (0..joints.len()).rev() {
        let j = &joints[i];
        let (Y, F, S, H) = (p.Ic[i], d.force[i], d.sym[i], d.momentum[i]);
        let (iv, own) = (j.idx_v, j.idx_v + j.nv);
        let end = model.plan().subtree_end_v[i];
        for k in iv..own {
            let Jk = p.J[k];
            d.yj[k] = inertia_twist(&Y, &Jk);
            d.bj[k] = S.mul_v(&Jk.w) + H.w.cross(&Jk.w) + H.v.cross(&Jk.v).scale(L::splat(2.0));
            d.df_dq[k] = inertia_twist(&Y, &d.da_dq[k]) + b_times(&S, &H, &d.dv_dq[k].w);
            d.df_dv[k] = inertia_twist(&Y, &d.da_dv[k]) + b_times(&S, &H, &Jk.w);
        }
        if j.parent.is_none() && j.kind == JointType::FreeFlyer {
            free_flyer_root(nv, i, iv, end, d);
            continue;
        }
        // rows of the joint's dofs, columns of its subtree
        for k in iv..own {
            let (Jk, row) = (p.J[k], k * nv);
            for c in iv..end {
                d.dq[row + c] = Jk.dot(&d.df_dq[c]);
            }
            for c in iv..end {
                d.dv[row + c] = Jk.dot(&d.df_dv[c]);
            }
        }
        // columns of the joint's dofs, rows of its strict subtree
        for k in iv..own {
            let (daq, dvq, dav, Jw) = (d.da_dq[k], d.dv_dq[k].w, d.da_dv[k], p.J[k].w);
            for c in own..end {
                d.dq[c * nv + k] = daq.dot(&d.yj[c]) + d.bj[c].dot(&dvq);
                d.dv[c * nv + k] = dav.dot(&d.yj[c]) + d.bj[c].dot(&Jw);
            }
        }
        // J_k ×* F for the ancestors' rows (it cancels the turning of J_k in the own block)
        for k in iv..own {
            d.df_dq[k] += p.J[k].cross_star(&F);
        }
        if let Some(par) = j.parent {
            p.Ic[par.0] += &Y;
            d.force[par.0] += F;
            d.momentum[par.0] += H;
            d.sym[par.0] += &S;
        }
    }
}

/// The rows and columns of free-flyer root `i` at dofs `iv..iv + 6` of a tree whose dofs end at
/// `end`, where `J_k = e_k`, `V_λ = 0`, `A_λ = (0, g')`: row `k` of column `c` is component `k`
/// of `∂F/∂q_c` (`∂F/∂v_c`); for a descendant row `c` with `y = Ic J_c`, `b = (Bcᵀ J_c)_ω`,
/// `∂τ_c/∂q_k` is component `k` of `y_f × g'` for `k < 3` and zero after, and `∂τ_c/∂v_k`
/// component `k` of `−[ad_V]ᵀ y + (b, 0)`.
#[inline(always)]
fn free_flyer_root<const W: usize>(
    nv: usize,
    i: usize,
    iv: usize,
    end: usize,
    d: &mut DerivPack<W>,
) {
    for c in iv..end {
        let (fq, fv) = (d.df_dq[c], d.df_dv[c]);
        for k in 0..6 {
            d.dq[(iv + k) * nv + c] = fq.get(k);
            d.dv[(iv + k) * nv + c] = fv.get(k);
        }
    }
    let (g, V) = (d.gravity[i], d.vel[i]);
    for c in iv + 6..end {
        let (y, b, row) = (d.yj[c], d.bj[c], c * nv + iv);
        let t = y.v.cross(&g);
        // [ad_V]ᵀ y = −(V ×* y)
        let u = V.cross_star(&y);
        for k in 0..3 {
            d.dq[row + k] = t.0[k];
            d.dq[row + 3 + k] = L::zero();
            d.dv[row + k] = -u.w.0[k] + b.0[k];
            d.dv[row + 3 + k] = -u.v.0[k];
        }
    }
}

/// The symmetric part of the angular block of `B` for a body of inertia `G = (m, c, I)` moving
/// with `V = (ω, v)`: `K + Kᵀ − c vᵀ − v cᵀ + 2 (c·v) 1` with `K = [ω] I`, stored
/// `xx yy zz xy xz yz` (the single call's `variation_sym`, in its order).
#[inline(always)]
fn variation_sym<const W: usize>(G: &I3<W>, V: &T6<W>) -> S3<W> {
    let (c, w, v) = (&G.h.0, &V.w, &V.v.0);
    let k0 = w.cross(&G.i.col(0)).0;
    let k1 = w.cross(&G.i.col(1)).0;
    let k2 = w.cross(&G.i.col(2)).0;
    let cv2 = G.h.dot(&V.v) * 2.0;
    S3([
        (k0[0] - c[0] * v[0]) * 2.0 + cv2,
        (k1[1] - c[1] * v[1]) * 2.0 + cv2,
        (k2[2] - c[2] * v[2]) * 2.0 + cv2,
        k1[0] + k0[1] - c[0] * v[1] - v[0] * c[1],
        k2[0] + k0[2] - c[0] * v[2] - v[0] * c[2],
        k2[1] + k1[2] - c[1] * v[2] - v[1] * c[2],
    ])
}

/// `Bc x = ((S − [L]) x_ω, −2 p × x_ω)` for the composite `S` and momentum `h = (L, p)` (`x_v`
/// does not enter).
#[inline(always)]
fn b_times<const W: usize>(s: &S3<W>, h: &T6<W>, xw: &V3<W>) -> T6<W> {
    T6 {
        w: s.mul_v(xw) - h.w.cross(xw),
        v: h.v.cross(xw).scale(L::splat(-2.0)),
    }
}
