//! CRBA on a pack of `W` states, in the world frame (Pinocchio's `crba` with
//! `Convention::WORLD`; Featherstone 2008, §6.2): the composite inertias are sums of the bodies'
//! world-frame inertias, so the backward pass is additions, and each entry of `M` is one product
//! `M_kl = S_lᵀ (I^c_i S_k)` of world-frame columns.

use super::lanes::{L, T6, V3, X};
use super::pack::{placement, Pack, I3};
use crate::mass::SpatialInertia;
use crate::multibody::Model;

/// `M(q)` for the pack's states into `p.M` (the lower triangle, packed by columns: column `c`'s
/// rows `c..nv` from [`packed_at`]`(nv, c, c)`):
///
/// forward: `⁰X_i = ⁰X_λ liMi`, `I⁰_i = ⁰X_i · G_i` (the body's inertia in the world frame);
/// backward: `I^c_λ += I^c_i`; then for each dof `k` of joint `i`: `⁰S_k = [Ad_{⁰X_i}] S_k`,
/// `F_k = I^c_i ⁰S_k`, and `M_kl = ⁰S_lᵀ F_k` for the dofs `l ≤ k` of `i` and of its ancestors,
/// plus the armature on the diagonal.
#[inline(always)]
pub(super) fn crba<const W: usize>(model: &Model, p: &mut Pack<W>) {
    p.update_subspaces(model);
    let joints = model.joints();
    for (i, j) in joints.iter().enumerate() {
        let X = placement(model, i, &p.q);
        let oX = match j.parent {
            Some(par) => p.oX[par.0].compose(&X),
            None => X,
        };
        p.Yc[i] = world_inertia(&model.inertias()[i], &oX);
        p.oX[i] = oX;
    }
    for (i, j) in joints.iter().enumerate().rev() {
        if let Some(par) = j.parent {
            let y = p.Yc[i];
            let c = &mut p.Yc[par.0];
            c.m += y.m;
            c.h += y.h;
            for r in 0..3 {
                for s in 0..3 {
                    c.i.0[r][s] += y.i.0[r][s];
                }
            }
        }
    }
    let nv = model.nv();
    // the entries of M outside the ancestor pairs are zero: set by Pack::new, never written
    for (i, j) in joints.iter().enumerate() {
        for k in j.dofs() {
            p.oS[k] = world_column(model, &p.S, k, &p.oX[i]);
        }
        for k in j.dofs() {
            let F = inertia_twist(&p.Yc[i], &p.oS[k]);
            for &(l, at) in &p.support[p.support_of[k]..p.support_of[k + 1]] {
                p.M[at] = p.oS[l].dot(&F);
            }
            p.M[packed_at(nv, k, k)] += model.armature()[k];
        }
    }
}

/// Where entry `(r, c)`, `r ≥ c`, of an `nv x nv` lower triangle packed by columns is: column
/// `c` starts at `c (2 nv − c + 1) / 2` (LAPACK's packed storage `'L'`).
#[inline(always)]
pub(super) fn packed_at(nv: usize, r: usize, c: usize) -> usize {
    c * (2 * nv - c + 1) / 2 + (r - c)
}

/// `[Ad_{⁰X_i}] S_k`: column `k` in the world frame, `(R s_ω, R s_v + p × R s_ω)` (a column
/// of `R` when `S_k` is a coordinate axis, `Plan::dof_axis`).
#[inline(always)]
fn world_column<const W: usize>(model: &Model, S: &[T6<W>], k: usize, oX: &X<W>) -> T6<W> {
    match model.plan().dof_axis[k] {
        Some((c, s)) if c < 3 => {
            let w = oX.r.col(c).scale(L::splat(s));
            T6 {
                v: oX.p.cross(&w),
                w,
            }
        }
        Some((c, s)) => T6 {
            w: V3::zero(),
            v: oX.r.col(c - 3).scale(L::splat(s)),
        },
        None => {
            let w = oX.r.mul_v(&S[k].w);
            T6 {
                v: oX.r.mul_v(&S[k].v) + oX.p.cross(&w),
                w,
            }
        }
    }
}

/// `⁰X · G`: the constant body inertia `G = (m, h, I_O)` moved to the world frame by the pose
/// `(R, p)`: `h⁰ = m p + R h` and, about the world origin,
/// `I⁰ = R I_O Rᵀ + (m |p|² + 2 p · R h) 1 − (m p pᵀ + p (R h)ᵀ + (R h) pᵀ)` (the parallel-axis
/// theorem with the body's first moment; [`SpatialInertia::transformed`]).
#[inline(always)]
fn world_inertia<const W: usize>(G: &SpatialInertia, oX: &X<W>) -> I3<W> {
    let m = G.mass();
    let (r, p) = (&oX.r, &oX.p);
    let rh = r.mul_c(&G.first_moment());
    let rir = r.mul_cm(G.inertia_origin_matrix()).mul_tr_sym(r);
    let d = p.dot(p) * m + p.dot(&rh) * 2.0;
    let mp = p.scale(L::splat(m));
    let mut i = rir;
    for a in 0..3 {
        for b in 0..3 {
            i.0[a][b] -= mp.0[a] * p.0[b] + p.0[a] * rh.0[b] + rh.0[a] * p.0[b];
        }
        i.0[a][a] += d;
    }
    I3 {
        m: L::splat(m),
        h: mp + rh,
        i,
    }
}

/// `I T` of a spatial inertia `(m, h, I_O)` and a twist per lane: `(I_O ω + h × v, m v − h × ω)`.
#[inline(always)]
fn inertia_twist<const W: usize>(y: &I3<W>, t: &T6<W>) -> T6<W> {
    T6 {
        w: y.i.mul_v(&t.w) + y.h.cross(&t.v),
        v: t.v.scale(y.m) - y.h.cross(&t.w),
    }
}
