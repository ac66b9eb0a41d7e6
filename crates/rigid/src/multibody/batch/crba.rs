//! CRBA on a pack of `W` states: the single call's algorithm ([`crba`](crate::multibody::crba),
//! Featherstone 2008, Table 6.2, with every quantity in the root body's frame {r} of its tree),
//! step for step in lanes. The composite inertias are sums of the bodies' inertias in {r}, so the
//! backward pass is additions, and each entry of `M` is one product `M_lk = J_kᵀ F_l` of
//! {r}-frame columns, written down a contiguous column of the packed lower triangle.

use super::lanes::{one_iteration_at_a_time, L, M3, S3, T6, V3, X};
use super::pack::{Pack, I3};
use super::pose::{placement, rotate_about};
use crate::mass::{PrincipalForm, SpatialInertia};
use crate::multibody::joint::Shape;
use crate::multibody::plan::PlacementKind;
use crate::multibody::Model;
use crate::spatial::{trig, ModelVec3};

/// `M(q)` for the pack's states into `p.M` (the lower triangle, packed by columns: column `k`'s
/// rows `k..nv` from [`packed_at`]`(nv, k, k)`):
///
/// forward ([`turn_angles`], then [`root_frame_body`]): `rMi`, the columns
/// `J_k = [Ad_{rMi}] S_k` and the body's inertia `rG_i` in its tree's root frame;
/// backward, `i = n..1`: `F_k = Ic_i J_k` for the dofs `k` of joint `i`, then
/// `M_lk = J_kᵀ F_l` for `l` from `k` to the end of `i`'s subtree (a root's `J_k = s e_c` reads
/// `M_lk = s F_l[c]`), plus the armature on the diagonal, and `Ic_λ(i) += Ic_i`.
#[inline(always)]
pub(super) fn crba<const W: usize>(model: &Model, p: &mut Pack<W>) {
    p.update_subspaces(model);
    turn_angles(model, p);
    let joints = model.joints();
    for i in 0..joints.len() {
        root_frame_body(model, p, i);
    }
    let nv = model.nv();
    // the entries of M outside a dof's subtree are zero: set by Pack::new, never written
    for i in (0..joints.len()).rev() {
        let j = &joints[i];
        let end_v = model.plan().subtree_end_v[i];
        for k in j.dofs() {
            p.Fk[k] = inertia_twist(&p.Ic[i], &p.J[k]);
        }
        for k in j.dofs() {
            let at = packed_at(nv, k, k);
            // the diagonal first, with the armature, then the rows below it
            let (diagonal, rest) = p.M[at..at + end_v - k]
                .split_first_mut()
                .expect("a column holds its diagonal");
            let Fs = &p.Fk[k..end_v];
            let below = rest.iter_mut().zip(&Fs[1..]);
            let armature = model.armature()[k];
            match (j.parent, model.plan().dof_axis[k]) {
                (None, Some((c, s))) => {
                    *diagonal = Fs[0].get(c) * s + armature;
                    for (m, F) in below {
                        one_iteration_at_a_time();
                        *m = F.get(c) * s;
                    }
                }
                _ => {
                    let Jk = p.J[k];
                    *diagonal = Jk.dot(&Fs[0]) + armature;
                    for (m, F) in below {
                        one_iteration_at_a_time();
                        *m = Jk.dot(F);
                    }
                }
            }
        }
        if let Some(par) = j.parent {
            // a parent comes before its child
            let (before, from_i) = p.Ic.split_at_mut(i);
            before[par.0] += &from_i[0];
        }
    }
}

/// Where entry `(r, c)`, `r ≥ c`, of an `nv x nv` lower triangle packed by columns is: column
/// `c` starts at `c (2 nv − c + 1) / 2` (LAPACK's packed storage `'L'`).
#[inline(always)]
pub(super) fn packed_at(nv: usize, r: usize, c: usize) -> usize {
    c * (2 * nv - c + 1) / 2 + (r - c)
}

/// `(sin θ, cos θ)` into `p.sc` for the revolute joints below a root's child whose `X_T` is not
/// a [`General`](PlacementKind::General) rotation, the angles that [`root_frame_body`] turns
/// `R_λ` by, all before the forward pass: they do not depend on each other, so the CPU overlaps
/// their polynomials, where one joint at a time inside the pass each was a chain of latency
/// from parent to child (CRBA's full matrices 1.07–1.12x the states/s on UR5, Panda, Solo-12
/// and TALOS).
#[inline(always)]
pub(super) fn turn_angles<const W: usize>(model: &Model, p: &mut Pack<W>) {
    let (joints, plan) = (model.joints(), model.plan());
    for (i, j) in joints.iter().enumerate() {
        if let (Shape::Revolute(_), Some(par)) = (j.kind.shape(), j.parent) {
            if joints[par.0].parent.is_some() && plan.placement[i] != PlacementKind::General {
                let (s, c) = trig::sin_cos_lanes(p.q[j.idx_q].0);
                p.sc[i] = [L(s), L(c)];
            }
        }
    }
}

/// Body `i` in its tree's root frame {r}, per lane, with the shortcuts of the single call's
/// [`root_frame_bodies`](crate::multibody::algorithms::root_frame_bodies): `rMi` into `p.rX`,
/// `J_k` into `p.J`, and its inertia `rG_i` into `p.Ic` (the start of its composite inertia).
///
/// - a root: `rMi = 1`, `J_k = S_k`, `rG_i = G_i`;
/// - a root's child: `rMi = liMi = X_T X_J(q)`;
/// - deeper, a revolute joint whose `X_T` has no rotation turns two columns of `R_λ`; one whose
///   `R_T` is a signed permutation picks and signs columns of `R_λ` first; one whose `R_T` turns
///   about a coordinate axis turns two columns twice; a prismatic joint without rotation keeps
///   `R_λ`; anything else is the product `rM_λ liMi`;
/// - `rG_i` by the body's [`PrincipalForm`] when it has one, else by the adjoint congruence.
///
/// The deeper revolute joints' `(sin θ, cos θ)` are read from `p.sc`: call [`turn_angles`] first.
#[inline(always)]
pub(super) fn root_frame_body<const W: usize>(model: &Model, p: &mut Pack<W>, i: usize) {
    let plan = model.plan();
    let j = &model.joints()[i];
    let shape = j.kind.shape();
    let rMi = match j.parent {
        None => {
            p.rX[i] = X::identity();
            p.Ic[i] = I3::splat(&model.inertias()[i]);
            for k in j.dofs() {
                p.J[k] = p.S[k];
            }
            return;
        }
        Some(par) if model.joints()[par.0].parent.is_none() => placement(model, i, &p.q),
        Some(par) => {
            let rMp = &p.rX[par.0];
            let (R, t) = (&rMp.r, &plan.placement_translation[i]);
            // read only in the arms that turn `R_λ` (as `turn_angles` wrote them)
            let angle = || (p.sc[i][0], p.sc[i][1]);
            match (shape, plan.placement[i]) {
                (Shape::Revolute(axis), PlacementKind::Identity) => {
                    let (s, c) = angle();
                    X {
                        r: rotate_about(R, &axis, s, c),
                        p: rotated(t, R) + rMp.p,
                    }
                }
                (Shape::Revolute(axis), PlacementKind::SignedPermutation(perm)) => {
                    let col = |n: usize| R.col(perm[n].0).scale(L::splat(perm[n].1));
                    let RT = M3::from_columns(&[col(0), col(1), col(2)]);
                    let (s, c) = angle();
                    X {
                        r: rotate_about(&RT, &axis, s, c),
                        p: rotated(t, R) + rMp.p,
                    }
                }
                (
                    Shape::Revolute(axis),
                    PlacementKind::AxisTurn {
                        axis: e,
                        s: sT,
                        c: cT,
                    },
                ) => {
                    let (s, c) = angle();
                    let RT = rotate_about(R, &e, L::splat(sT), L::splat(cT));
                    X {
                        r: rotate_about(&RT, &axis, s, c),
                        p: rotated(t, R) + rMp.p,
                    }
                }
                (Shape::Prismatic(axis), PlacementKind::Identity) => {
                    let d = V3::c_scale(&axis, p.q[j.idx_q]) + V3::splat(&j.placement.translation);
                    X {
                        r: *R,
                        p: R.mul_v(&d) + rMp.p,
                    }
                }
                (
                    Shape::Prismatic(axis),
                    PlacementKind::AxisTurn {
                        axis: e,
                        s: sT,
                        c: cT,
                    },
                ) => {
                    let r = rotate_about(R, &e, L::splat(sT), L::splat(cT));
                    let d = r.mul_v(&V3::c_scale(&axis, p.q[j.idx_q]));
                    X {
                        p: rotated(t, R) + d + rMp.p,
                        r,
                    }
                }
                _ => rMp.compose(&placement(model, i, &p.q)),
            }
        }
    };
    p.Ic[i] = match &plan.principal[i] {
        Some(form) => principal_moved(form, &rMi),
        None => moved(&model.inertias()[i], &rMi),
    };
    for k in j.dofs() {
        p.J[k] = column(model, &p.S, k, &rMi);
    }
    p.rX[i].set(&rMi);
}

/// `[Ad_{rMi}] S_k`: column `k` in the root frame, `(R s_ω, R s_v + p × R s_ω)` (a column of `R`
/// when `S_k` is a coordinate axis, `Plan::dof_axis`).
#[inline(always)]
fn column<const W: usize>(model: &Model, S: &[T6<W>], k: usize, rX: &X<W>) -> T6<W> {
    match model.plan().dof_axis[k] {
        Some((c, s)) if c < 3 => {
            let w = rX.r.col(c).scale(L::splat(s));
            T6 {
                v: rX.p.cross(&w),
                w,
            }
        }
        Some((c, s)) => T6 {
            w: V3::zero(),
            v: rX.r.col(c - 3).scale(L::splat(s)),
        },
        None => {
            let w = rX.r.mul_v(&S[k].w);
            T6 {
                v: rX.r.mul_v(&S[k].v) + rX.p.cross(&w),
                w,
            }
        }
    }
}

/// `R x` for a constant `x` kept as `s e_k` when it lies on an axis ([`ModelVec3::rotated`]).
#[inline(always)]
fn rotated<const W: usize>(x: &ModelVec3, r: &M3<W>) -> V3<W> {
    match *x {
        ModelVec3::Axis(k, s) => r.col(k).scale(L::splat(s)),
        ModelVec3::General(x) => r.mul_c(&x),
    }
}

/// [`PrincipalForm::transformed`] per lane: `c' = R c + p`, `h' = m c'`,
/// `I'_O = λ₁ 1 + (R u₂)(R u₂)ᵀ + (R u₃)(R u₃)ᵀ + (h'·c') 1 − h' c'ᵀ`.
#[inline(always)]
fn principal_moved<const W: usize>(f: &PrincipalForm, x: &X<W>) -> I3<W> {
    let c = rotated(&f.com, &x.r) + x.p;
    let (a, b) = (rotated(&f.u2, &x.r), rotated(&f.u3, &x.r));
    let h = c.scale(L::splat(f.mass));
    let d = h.dot(&c) + f.lambda1;
    let mut i = S3([L::zero(); 6]);
    for r in 0..3 {
        for s in r..3 {
            // in the single call's order: `h_r c_s` for r ≤ s, ((d + a a) + b b) − h c on the diagonal
            let (aa, bb, hc) = (a.0[r] * a.0[s], b.0[r] * b.0[s], h.0[r] * c.0[s]);
            *i.at_mut(r, s) = if r == s {
                d + aa + bb - hc
            } else {
                aa + bb - hc
            };
        }
    }
    I3 {
        m: L::splat(f.mass),
        h,
        i,
    }
}

/// [`SpatialInertia::transformed`] per lane, in its order, for the bodies without a principal
/// form: the constant `G = (m, h, I_O)` moved by the pose `(R, p)`, with `g = R h + (m/2) p`,
/// `I' = R I_O Rᵀ − p gᵀ − g pᵀ + 2 (g · p) 1` (the parallel-axis theorem with the body's first
/// moment) and `h' = R h + m p`.
#[inline(always)]
fn moved<const W: usize>(G: &SpatialInertia, x: &X<W>) -> I3<W> {
    let m = G.mass();
    let (r, p) = (&x.r, &x.p);
    let h = r.mul_c(&G.first_moment());
    let ri = r.mul_cm(G.inertia_origin_matrix());
    let g = h + p.scale(L::splat(0.5 * m));
    let d = g.dot(p) * 2.0;
    let mut i = S3([L::zero(); 6]);
    for a in 0..3 {
        for b in a..3 {
            let rir = ri.0[a][0] * r.0[b][0] + ri.0[a][1] * r.0[b][1] + ri.0[a][2] * r.0[b][2];
            *i.at_mut(a, b) = rir - p.0[a] * g.0[b] - g.0[a] * p.0[b];
        }
        *i.at_mut(a, a) += d;
    }
    I3 {
        m: L::splat(m),
        h: h + p.scale(L::splat(m)),
        i,
    }
}

/// `I T` of a spatial inertia `(m, h, I_O)` and a twist per lane: `(I_O ω + h × v, m v − h × ω)`.
#[inline(always)]
pub(super) fn inertia_twist<const W: usize>(y: &I3<W>, t: &T6<W>) -> T6<W> {
    T6 {
        w: y.i.mul_v(&t.w) + y.h.cross(&t.v),
        v: t.v.scale(y.m) - y.h.cross(&t.w),
    }
}
