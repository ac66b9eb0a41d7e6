//! RNEA on a pack of `W` states: [`rnea`](crate::multibody::rnea)'s two loops (Featherstone
//! 2008, Table 5.1), every quantity a lane vector.

use super::lanes::{T6, V3};
use super::pack::{momentum, s_dot, Pack};
use super::pose::{fresh_pose, kept_pose, Pose};
use crate::multibody::Model;

/// `τ = ID(q, v, a)` for the pack's states: `q`, `v`, `x = a` in, `out = τ`.
///
/// forward, i = 1..n (`V_0 = 0`, `A_0 = -g`): `V_i = [Ad_{liMi⁻¹}] V_λ + S_i q̇_i`,
/// `A_i = [Ad_{liMi⁻¹}] A_λ + S_i q̈_i + V_i × S_i q̇_i + c_J`, `F_i = G_i A_i + V_i ×* G_i V_i`;
/// backward, i = n..1: `τ_i = S_iᵀ F_i + armature q̈_i`, `F_λ += [Ad_{liMi}]⁻ᵀ F_i`.
/// A joint that turns about a coordinate axis (`Plan::turn`) has its pose as a [`Turn`](super::pose::Turn).
#[inline(always)]
pub(super) fn rnea<const W: usize>(model: &Model, p: &mut Pack<W>) {
    let a_world = T6 {
        w: V3::zero(),
        v: V3::splat(&-model.gravity()),
    };
    p.update_subspaces(model);
    for i in 0..model.njoints() {
        fresh_pose!(model, p, i, |X| forward(model, p, i, X, &a_world));
    }
    let joints = model.joints();
    for i in (0..joints.len()).rev() {
        let j = &joints[i];
        let F = p.F[i];
        for k in j.dofs() {
            p.out[k] = s_dot(model, &p.S, k, &F) + p.x[k] * model.armature()[k];
        }
        if let Some(par) = j.parent {
            let Fp = kept_pose!(model, p, i, |X| X.act_wrench(&F));
            p.F[par.0] += Fp;
        }
    }
}

/// Joint `i`'s step of the forward pass, with its pose `X`.
#[inline(always)]
fn forward<const W: usize, P: Pose<W>>(
    model: &Model,
    p: &mut Pack<W>,
    i: usize,
    X: &P,
    a_world: &T6<W>,
) {
    let (mut V, mut A) = match model.joints()[i].parent {
        Some(par) => (X.inv_act(&p.V[par.0]), X.inv_act(&p.A[par.0])),
        None => (T6::zero(), X.inv_act(a_world)),
    };
    // the single call's order of additions, for its bits: A + S q̈, then + V × S q̇
    p.add_joint_twist(model, i, &p.x, &mut A);
    A += p.joint_velocity(model, i, &mut V);
    if let Some(cJ) = p.joint_bias(model, i) {
        A += cJ;
    }
    let G = &model.inertias()[i];
    p.F[i] = momentum(G, &A) + V.cross_star(&momentum(G, &V));
    p.V[i] = V;
    p.A[i] = A;
}
