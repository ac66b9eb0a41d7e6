//! The recursive Newton-Euler algorithm on expressions: `τ(q)` for given numeric joint velocities
//! and accelerations, a derivation of the explicit model independent of the Lagrange one in
//! [`lagrange`](super::lagrange) (the tests compare them term by term).
//!
//! Featherstone 2008, Table 5.1, in body coordinates, with gravity as the base's acceleration
//! `A_0 = (0, -g)`:
//! - `V_j = X_j⁻¹ V_λ + S_j q̇_j`, `A_j = X_j⁻¹ A_λ + S_j q̈_j + V_j × S_j q̇_j`, where
//!   `X_j⁻¹ (ω, v) = (Rᵀ ω, Rᵀ (v + ω × p))` for the child pose `(R, p)` in its parent;
//! - `F_j = G_j A_j + V_j ×* G_j V_j` with `G (ω, v) = (I ω + h × v, m v - h × ω)` and
//!   `(ω, v) ×* (n, f) = (ω × n + v × f, ω × f)`;
//! - `τ_j = S_jᵀ F_j + armature_j q̈_j`, `F_λ += (R n + p × R f, R f)`.
//!
//! With `q̇ = 0, q̈ = e_k` and no gravity, `τ` is column k of `M`; with `q̇ = e_j` it is
//! `c_ij`; with `q̇ = e_j + e_k` it is `c_ij + c_ik + b_ijk`; with gravity only, `g`.

use super::chain::Chain;
use super::expr::{Expr, Overflow};
use super::lagrange::overflow;
use super::sym::{add, cross, dot, dot_num, mat_t_vec, wrench_to_parent, V3};
use super::ExplicitError;
use crate::multibody::Model;

/// A twist or a wrench of expressions, angular part first.
type Pair = (V3, V3);

fn sub(a: &V3, b: &V3) -> V3 {
    std::array::from_fn(|k| a[k].sub(&b[k]))
}

/// `τ(q)` for the numeric joint velocities `v` and accelerations `a`, with or without gravity,
/// by the recursive Newton-Euler algorithm on expressions (see the module documentation).
///
/// # Errors
/// As [`ExplicitModel::derive`](super::ExplicitModel::derive); wrong lengths of `v` or `a`.
///
/// ```
/// use rigid::explicit::{symbolic_rnea, ExplicitModel};
/// use rigid::multibody::double_pendulum;
/// let model = double_pendulum();
/// // q̇ = 0, q̈ = 0, gravity only: τ = g(q)
/// let tau = symbolic_rnea(&model, &[0.0, 0.0], &[0.0, 0.0], true)?;
/// let explicit = ExplicitModel::derive(&model)?;
/// let values = explicit.parameters().values();
/// let q = [0.3, -0.7];
/// assert!((tau[1].eval(&q, &values) - explicit.gravity(1).eval(&q, &values)).abs() < 1e-12);
/// # Ok::<(), rigid::explicit::ExplicitError>(())
/// ```
pub fn symbolic_rnea(
    model: &Model,
    v: &[f64],
    a: &[f64],
    with_gravity: bool,
) -> Result<Vec<Expr>, ExplicitError> {
    let chain = Chain::new(model)?;
    let n = chain.n();
    if v.len() != n || a.len() != n {
        return Err(ExplicitError::Model(format!(
            "symbolic_rnea: v and a need {n} entries, got {} and {}",
            v.len(),
            a.len()
        )));
    }
    forward_backward(&chain, v, a, with_gravity).map_err(overflow("the symbolic RNEA"))
}

fn forward_backward(
    chain: &Chain,
    v: &[f64],
    a: &[f64],
    with_gravity: bool,
) -> Result<Vec<Expr>, Overflow> {
    let n = chain.n();
    let s = chain.space;
    let zero = || super::sym::zero_vec(s);
    let base_acc: V3 = match (with_gravity, chain.gravity) {
        (true, Some(g)) => std::array::from_fn(|k| Expr::param(s, g, -chain.gravity_dir[k])),
        _ => zero(),
    };
    let mut vel: Vec<Pair> = Vec::with_capacity(n);
    let mut acc: Vec<Pair> = Vec::with_capacity(n);
    let mut force: Vec<Pair> = Vec::with_capacity(n);
    let transforms: Vec<_> = (0..n).map(|j| chain.transform(j)).collect();
    for j in 0..n {
        let t = &transforms[j];
        let (vp, ap) = match chain.joints[j].parent {
            Some(p) => (vel[p].clone(), acc[p].clone()),
            None => ((zero(), zero()), (zero(), base_acc.clone())),
        };
        // X⁻¹ (ω, v) = (Rᵀ ω, Rᵀ (v + ω × p))
        let to_child = |x: &Pair| -> Result<Pair, Overflow> {
            let w = mat_t_vec(&t.r, &x.0)?;
            let lin = mat_t_vec(&t.r, &add(&x.1, &cross(&x.0, &t.p)?))?;
            Ok((w, lin))
        };
        let (sw, sv) = chain.subspace(j);
        let sq: Pair = (
            sw.map(|x| Expr::constant(s, x * v[j])),
            sv.map(|x| Expr::constant(s, x * v[j])),
        );
        let vj = to_child(&vp)?;
        let vj = (add(&vj.0, &sq.0), add(&vj.1, &sq.1));
        let aj = to_child(&ap)?;
        let sa: Pair = (
            sw.map(|x| Expr::constant(s, x * a[j])),
            sv.map(|x| Expr::constant(s, x * a[j])),
        );
        // V × S q̇ = (ω × ω_s, v × ω_s + ω × v_s)
        let vxs = (
            cross(&vj.0, &sq.0)?,
            add(&cross(&vj.1, &sq.0)?, &cross(&vj.0, &sq.1)?),
        );
        let aj = (
            add(&add(&aj.0, &sa.0), &vxs.0),
            add(&add(&aj.1, &sa.1), &vxs.1),
        );
        let g = chain.body_inertia(j);
        let gv = |x: &Pair| -> Result<Pair, Overflow> {
            // (I ω + h × v, m v - h × ω)
            let iw: V3 = [
                dot(&g.i[0], &x.0)?,
                dot(&g.i[1], &x.0)?,
                dot(&g.i[2], &x.0)?,
            ];
            let nn = add(&iw, &cross(&g.h, &x.1)?);
            let mv: V3 = [g.m.mul(&x.1[0])?, g.m.mul(&x.1[1])?, g.m.mul(&x.1[2])?];
            Ok((nn, sub(&mv, &cross(&g.h, &x.0)?)))
        };
        let ga = gv(&aj)?;
        let gvv = gv(&vj)?;
        // V ×* (n, f) = (ω × n + v × f, ω × f)
        let bias = (
            add(&cross(&vj.0, &gvv.0)?, &cross(&vj.1, &gvv.1)?),
            cross(&vj.0, &gvv.1)?,
        );
        force.push((add(&ga.0, &bias.0), add(&ga.1, &bias.1)));
        vel.push(vj);
        acc.push(aj);
    }
    let mut tau = vec![Expr::zero(s); n];
    for j in (0..n).rev() {
        let (sw, sv) = chain.subspace(j);
        let (nn, ff) = &force[j];
        tau[j] = dot_num(sw, nn).add(&dot_num(sv, ff));
        if let Some(arm) = chain.joints[j].armature {
            tau[j] = tau[j].add(&Expr::param(s, arm, a[j]));
        }
        if let Some(p) = chain.joints[j].parent {
            let (n2, f2) = wrench_to_parent(&transforms[j], nn, ff)?;
            force[p] = (add(&force[p].0, &n2), add(&force[p].1, &f2));
        }
    }
    Ok(tau)
}
