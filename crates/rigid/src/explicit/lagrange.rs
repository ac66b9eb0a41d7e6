//! The explicit model from the energies (Lagrange): the kinetic-energy matrix `M(q)` by composite
//! inertias, the Christoffel symbols of `M` split into Coriolis `b_ijk` and centrifugal `c_ij`
//! terms, and gravity `g = ∂U/∂q` from the potential energy.
//!
//! - `M`: the composite inertia of the subtree of joint j in j's frame,
//!   `Ic_j = G_j + Σ_children X_cᵀ Ic_c X_c` ([`SymInertia::transformed`]); then
//!   `M_jj = S_jᵀ Ic_j S_j` and, carrying the wrench `F = Ic_j S_j` to each ancestor i,
//!   `M_ij = S_iᵀ F` (Featherstone 2008, Table 6.2; `K = ½ q̇ᵀ M q̇`, Lynch & Park §8.1).
//! - `c(q, q̇) = Σ_{j<k} b_ijk q̇_j q̇_k + Σ_j c_ij q̇_j²` with the Christoffel symbols
//!   `Γ_ijk = ½ (∂M_ij/∂q_k + ∂M_ik/∂q_j - ∂M_jk/∂q_i)`: `b_ijk = 2 Γ_ijk` (Coriolis),
//!   `c_ij = Γ_ijj` (centrifugal), as Armstrong, Khatib & Burdick (1986) tabulate them
//!   (Lynch & Park §8.1.2).
//! - `U = -gᵀ Σ_b m_b c_b` (the composite first moment of the whole tree in the world) and
//!   `g_i = ∂U/∂q_i`.
//!
//! The symbolic RNEA of [`rnea`](super::rnea) derives the same quantities another way; the tests
//! check that both agree term by term.

use super::chain::Chain;
use super::expr::{Expr, Overflow};
use super::sym::{dot_num, wrench_to_parent, SymInertia, SymTransform};
use super::ExplicitError;

/// Largest number of terms of one expression before the derivation gives up (a fully generic
/// 7-joint chain, every axis and inertia rotated at random, reaches 450 000 terms in 10 s; an
/// 8-joint one would reach 2.3 million; the Panda stays below 30 000).
pub(crate) const SWELL_LIMIT: usize = 1_000_000;

/// An error if `e` has grown beyond [`SWELL_LIMIT`] terms.
pub(crate) fn guard(e: Expr, what: &str) -> Result<Expr, ExplicitError> {
    if e.len() > SWELL_LIMIT {
        return Err(ExplicitError::Swell {
            what: what.to_string(),
            terms: e.len(),
        });
    }
    Ok(e)
}

pub(crate) fn overflow(what: &str) -> impl Fn(Overflow) -> ExplicitError + '_ {
    move |_| ExplicitError::Swell {
        what: what.to_string(),
        terms: 0,
    }
}

/// `M(q)` (full symmetric, row-major `n x n`) and `g(q)`.
pub(crate) struct Energies {
    pub mass: Vec<Expr>,
    pub gravity: Vec<Expr>,
}

/// `S_iᵀ F` for the wrench `F = (n, f)`.
fn project(chain: &Chain, i: usize, n: &super::sym::V3, f: &super::sym::V3) -> Expr {
    let (w, v) = chain.subspace(i);
    dot_num(w, n).add(&dot_num(v, f))
}

/// `M(q)` by composite inertias and `g(q) = ∂U/∂q`.
pub(crate) fn energies(chain: &Chain) -> Result<Energies, ExplicitError> {
    let n = chain.n();
    let space = chain.space;
    let transforms: Vec<SymTransform> = (0..n).map(|j| chain.transform(j)).collect();
    // composite inertias, leaves first (children come after their parent)
    let mut composite: Vec<SymInertia> = (0..n).map(|j| chain.body_inertia(j)).collect();
    // the whole tree's first moment in the world
    let mut world_h = super::sym::zero_vec(space);
    for j in (0..n).rev() {
        let Some(p) = chain.joints[j].parent else {
            // in the world only the first moment is needed (for U)
            let h = composite[j]
                .transformed_first_moment(&transforms[j])
                .map_err(overflow("the first moment"))?;
            world_h = super::sym::add(&world_h, &h);
            continue;
        };
        let moved = composite[j]
            .transformed(&transforms[j])
            .map_err(overflow("a composite inertia"))?;
        let size = |g: &SymInertia| g.i.iter().flatten().map(Expr::len).max().unwrap_or(0);
        let (before, after) = (size(&composite[j]).max(1), size(&moved));
        // each joint above multiplies the size again: stop early if the next would be too large
        let next = if chain.joints[p].parent.is_some() {
            after.saturating_mul(after.div_ceil(before))
        } else {
            after
        };
        if after > SWELL_LIMIT || next > SWELL_LIMIT {
            return Err(ExplicitError::Swell {
                what: format!(
                    "the composite inertia seen from joint '{}' ({after} terms, growing {}x per joint)",
                    chain.joints[p].name,
                    after.div_ceil(before)
                ),
                terms: next,
            });
        }
        composite[p] = composite[p].add(&moved);
    }
    let mut mass = vec![Expr::zero(space); n * n];
    for j in 0..n {
        let (w, v) = chain.subspace(j);
        let (mut nn, mut ff) = composite[j].momentum(w, v);
        let mut mjj = project(chain, j, &nn, &ff);
        if let Some(a) = chain.joints[j].armature {
            mjj = mjj.add(&Expr::param(space, a, 1.0));
        }
        mass[j * n + j] = mjj;
        let mut i = j;
        while let Some(p) = chain.joints[i].parent {
            (nn, ff) = wrench_to_parent(&transforms[i], &nn, &ff).map_err(overflow("a wrench"))?;
            i = p;
            let mij = guard(project(chain, i, &nn, &ff), "a mass-matrix entry")?;
            mass[i * n + j] = mij.clone();
            mass[j * n + i] = mij;
        }
    }
    let gravity = match chain.gravity {
        None => vec![Expr::zero(space); n],
        Some(g) => {
            // U = -g (ĝ · H)
            let u = dot_num(chain.gravity_dir, &world_h)
                .mul(&Expr::param(space, g, -1.0))
                .map_err(overflow("the potential energy"))?;
            (0..n).map(|i| u.derivative(i)).collect()
        }
    };
    Ok(Energies { mass, gravity })
}

/// The Coriolis terms `b_ijk` (`j < k`, index `(i n + j) n + k`) and the centrifugal terms `c_ij`
/// (index `i n + j`) from the Christoffel symbols of `M` (`M` row-major `n x n`).
pub(crate) fn christoffel(mass: &[Expr], n: usize) -> (Vec<Expr>, Vec<Expr>) {
    let space = mass[0].space();
    // dm[(i n + j) n + k] = ∂M_ij / ∂q_k
    let dm: Vec<Expr> = (0..n * n * n)
        .map(|x| mass[x / n].derivative(x % n))
        .collect();
    let d = |i: usize, j: usize, k: usize| &dm[(i * n + j) * n + k];
    let mut b = vec![Expr::zero(space); n * n * n];
    let mut c = vec![Expr::zero(space); n * n];
    for i in 0..n {
        for j in 0..n {
            for k in j + 1..n {
                b[(i * n + j) * n + k] = d(i, j, k).add(d(i, k, j)).sub(d(j, k, i));
            }
            c[i * n + j] = d(i, j, j).add_scaled(d(j, j, i), -0.5);
        }
    }
    (b, c)
}
