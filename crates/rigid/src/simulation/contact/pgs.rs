//! Projected Gauss–Seidel on the exact Coulomb cone (Jean & Moreau's non-smooth Gauss–Seidel),
//! island by island: the blocks that share no dof with another island's have rows of `G` that
//! are zero against it, so each island is its own problem, swept until its own impulses stand
//! (a box at rest alone on the floor stops after a few sweeps and its polish while a stack
//! beside it goes on) and polished within its own budget of a dense solve.

use super::polish::{Polish, Problem};
use super::solver::Block;
use super::ContactSettings;
use crate::multibody::constraints::solver::{cholesky, cholesky_solve};
use nalgebra::DMatrix;

/// The islands of a step's problem: blocks connected through the rows of `G` they couple to;
/// the bilateral blocks all in one (the sweep solves their group whole).
#[derive(Clone, Debug, Default)]
pub(crate) struct Islands {
    /// Per block, whether it is placed yet (scratch), and the search's stack.
    placed: Vec<bool>,
    stack: Vec<usize>,
    /// The islands' blocks, each island ascending, the islands by their first block: island `i`
    /// is `order[starts[i]..starts[i + 1]]`.
    order: Vec<usize>,
    starts: Vec<usize>,
}

impl Islands {
    /// The islands of `blocks`, `coupled[first[b]..first[b + 1]]` the row ranges block `b`'s
    /// rows of `G` may be nonzero on.
    pub(crate) fn find(
        &mut self,
        blocks: &[Block],
        (coupled, first): (&[(usize, usize)], &[usize]),
    ) {
        let nb = blocks.len();
        self.placed.clear();
        self.placed.resize(nb, false);
        self.order.clear();
        self.starts.clear();
        let block_of = |r: usize| blocks.partition_point(|b| b.row + b.dim <= r);
        for start in 0..nb {
            if self.placed[start] {
                continue;
            }
            let begin = self.order.len();
            self.starts.push(begin);
            self.stack.clear();
            // the bilateral blocks lead: the first island takes them all
            let seeds = if blocks[start].bilateral {
                blocks.iter().take_while(|b| b.bilateral).count()
            } else {
                1
            };
            for s in start..start + seeds {
                self.placed[s] = true;
                self.stack.push(s);
            }
            while let Some(b) = self.stack.pop() {
                self.order.push(b);
                for &(lo, hi) in &coupled[first[b]..first[b + 1]] {
                    let mut c = block_of(lo);
                    while c < nb && blocks[c].row < hi {
                        if !self.placed[c] {
                            self.placed[c] = true;
                            self.stack.push(c);
                        }
                        c += 1;
                    }
                }
            }
            self.order[begin..].sort_unstable();
        }
        self.starts.push(self.order.len());
    }

    /// The islands, each its blocks ascending.
    pub(crate) fn iter(&self) -> impl Iterator<Item = &[usize]> {
        self.starts.windows(2).map(|w| &self.order[w[0]..w[1]])
    }
}

/// Projected Gauss–Seidel on `σ = σ₀ + K λ` (`σ` holds `σ₀` on entry, `K` m x m with stride m),
/// island by island ([`sweep_island`]). Returns the most sweeps an island took and whether every
/// island met the tolerance.
#[allow(clippy::too_many_arguments)]
pub(super) fn pgs(
    blocks: &[Block],
    islands: &Islands,
    coupled: (&[(usize, usize)], &[usize]),
    K: &[f64],
    (factor, step, idle): (&DMatrix<f64>, &mut [f64], &[bool]),
    target: &[f64],
    lambda: &mut [f64],
    sigma: &mut [f64],
    (settings, polish): (&ContactSettings, &mut Polish),
    friction: bool,
) -> (usize, bool) {
    let (mut most, mut all) = (0, true);
    for island in islands.iter() {
        let (it, ok) = sweep_island(
            blocks,
            island,
            coupled,
            K,
            (factor, &mut *step, idle),
            target,
            lambda,
            sigma,
            (settings, &mut *polish),
            friction,
        );
        most = most.max(it);
        all &= ok;
    }
    (most, all)
}

/// Projected Gauss–Seidel on one island's blocks (`island`, ascending):
/// first the bilateral group (the leading `mb` rows, `factor` that of `K_BB + ρ I`; in the
/// island of block 0) by the proximal step `λ_B ← λ_B − (K_BB + ρ I)⁻¹ (σ_B − σ*_B)`; then per
/// block, the normal row `λ_n ← max(0, λ_n − (σ_n − σ*_n)/K_nn)`, then (when `friction` and the
/// block is a contact with `μ > 0`) the tangent rows by the 2x2 block and a radial projection on
/// the disc `‖λ_t‖ ≤ μ λ_n`; `σ` kept equal to `σ₀ + K λ`. Stops when no impulse of the island
/// changed by more than `tolerance` times its largest, or its polish is kept. Returns the sweeps
/// done and whether it converged.
#[allow(clippy::too_many_arguments)]
fn sweep_island(
    blocks: &[Block],
    island: &[usize],
    (coupled, first): (&[(usize, usize)], &[usize]),
    K: &[f64],
    (factor, step, idle): (&DMatrix<f64>, &mut [f64], &[bool]),
    target: &[f64],
    lambda: &mut [f64],
    sigma: &mut [f64],
    (settings, polish): (&ContactSettings, &mut Polish),
    friction: bool,
) -> (usize, bool) {
    let m = lambda.len();
    // σ += K e_r d over the rows coupled to row r's block (K is zero elsewhere)
    let update = |sigma: &mut [f64], b: usize, r: usize, d: f64| {
        let col = &K[r * m..(r + 1) * m];
        for &(lo, hi) in &coupled[first[b]..first[b + 1]] {
            for (s, k) in sigma[lo..hi].iter_mut().zip(&col[lo..hi]) {
                *s += k * d;
            }
        }
    };
    // the block of each bilateral row
    let block_of = |r: usize| blocks.partition_point(|b| b.row + b.dim <= r);
    let mb = if blocks[island[0]].bilateral {
        step.len()
    } else {
        0
    };
    // the polish's budget: a dense solve of n rows (n³/3 products a try) worth at most 16
    // sweeps (one sweep: each row against the rows of the blocks it is coupled to)
    let sweep: usize = if !settings.polish {
        0
    } else {
        island
            .iter()
            .map(|&i| {
                blocks[i].dim
                    * coupled[first[i]..first[i + 1]]
                        .iter()
                        .map(|(lo, hi)| hi - lo)
                        .sum::<usize>()
            })
            .sum()
    };
    let polish_rows = (48.0 * sweep as f64).cbrt() as usize;
    let mut failed = 0;
    for it in 1..=settings.max_iterations {
        let (mut change, mut largest): (f64, f64) = (0.0, 0.0);
        if mb > 0 {
            let d = &mut *step;
            for r in 0..mb {
                d[r] = if idle[r] { 0.0 } else { target[r] - sigma[r] };
            }
            cholesky_solve(factor, mb, d);
            for r in 0..mb {
                if d[r] != 0.0 {
                    lambda[r] += d[r];
                    update(sigma, block_of(r), r, d[r]);
                    change = change.max(d[r].abs());
                }
                largest = largest.max(lambda[r].abs());
            }
        }
        for &i in island {
            let b = &blocks[i];
            if b.bilateral {
                continue;
            }
            let r = b.row;
            let g = K[r * m + r];
            if g > 0.0 {
                let new = (lambda[r] - (sigma[r] - target[r]) / g).max(0.0);
                let d = new - lambda[r];
                if d != 0.0 {
                    lambda[r] = new;
                    update(sigma, i, r, d);
                    change = change.max(d.abs());
                }
            }
            largest = largest.max(lambda[r]);
            if !(friction && b.dim == 3 && b.friction > 0.0) {
                continue;
            }
            let (r1, r2) = (r + 1, r + 2);
            let (a, c, e) = (K[r1 * m + r1], K[r1 * m + r2], K[r2 * m + r2]);
            // the tangent impulse minimising the block's energy ½ xᵀ A x + bᵀ x on the disc
            // ‖x‖ ≤ μ λ_n, b = σ_t − A λ_t: at the boundary A x + b = −κ x, the slip velocity
            // opposite the friction (maximal dissipation)
            let b1 = sigma[r1] - a * lambda[r1] - c * lambda[r2];
            let b2 = sigma[r2] - c * lambda[r1] - e * lambda[r2];
            let (t1, t2) = disc_qp(a, c, e, b1, b2, b.friction * lambda[r]);
            let (d1, d2) = (t1 - lambda[r1], t2 - lambda[r2]);
            if d1 != 0.0 {
                lambda[r1] = t1;
                update(sigma, i, r1, d1);
            }
            if d2 != 0.0 {
                lambda[r2] = t2;
                update(sigma, i, r2, d2);
            }
            change = change.max(d1.abs()).max(d2.abs());
            largest = largest.max(t1.abs()).max(t2.abs());
        }
        let tol = settings.tolerance * largest;
        if change <= tol {
            return (it, true);
        }
        if settings.polish && failed < 2 && polish_after(it) {
            let problem = Problem {
                blocks,
                island,
                K,
                idle,
                target,
                friction,
                largest: polish_rows,
            };
            if polish.apply(problem, lambda, sigma) {
                return (it, true);
            }
            failed += 1;
        }
    }
    (settings.max_iterations, false)
}

/// Whether the active-set [polish](super::polish) follows sweep `it` (not yet converged): after
/// sweeps 4, 8, 16, ..., at most twice refused in one solve (each Newton step costs a dense
/// solve of the active rows, at most ~16 sweeps' work by the budget in `sweep_island`).
fn polish_after(it: usize) -> bool {
    it >= 4 && it.is_power_of_two()
}

/// The Cholesky factor of `K_BB + ρ I` (`ρ = 10⁻¹⁰ max diag K_BB`) into the leading `mb x mb`
/// block of `factor` (`mb = idle.len()`): `K_BB` the leading rows and columns of `K` (`m x m`,
/// stride `m`). A row whose `K_rr` is at most 1e-9 of the largest moves nothing (a planar loop's
/// out-of-plane row, zero to round-off): it is marked `idle` and given a unit pivot of its own,
/// so that its impulse stays 0 rather than growing by round-off over `ρ` each sweep (which held
/// the sweep from ever meeting its tolerance). A factor that fails (NaN in `K`) is left as the
/// identity's, and the NaN shows in the state.
pub(super) fn factor_bilateral(K: &[f64], m: usize, factor: &mut DMatrix<f64>, idle: &mut [bool]) {
    let mb = idle.len();
    let top = (0..mb).map(|r| K[r * m + r]).fold(0.0, f64::max);
    let rho = 1e-10 * top;
    for (r, i) in idle.iter_mut().enumerate() {
        *i = K[r * m + r] <= 1e-9 * top;
    }
    for i in 0..mb {
        for k in 0..=i {
            factor[(i, k)] = if idle[i] || idle[k] {
                f64::from(u8::from(i == k))
            } else {
                K[k * m + i]
            };
        }
        if !idle[i] {
            factor[(i, i)] += rho;
        }
    }
    if cholesky(factor, mb).is_err() {
        factor.fill(0.0);
        factor.fill_diagonal(1.0);
    }
}

/// The minimiser of `½ xᵀ A x + bᵀ x` over the disc `‖x‖ ≤ R` (`A = [[a, c], [c, e]]` positive
/// semi-definite): the unconstrained minimiser `−A⁻¹ b` if it is inside, else `x(κ) = −(A + κ
/// I)⁻¹ b` on the circle, `κ > 0` by Newton's method on `1/‖x(κ)‖ − 1/R` (the trust-region
/// subproblem, Moré & Sorensen 1983).
fn disc_qp(a: f64, c: f64, e: f64, b1: f64, b2: f64, R: f64) -> (f64, f64) {
    let nb = len(b1, b2);
    if R <= 0.0 || nb == 0.0 {
        return (0.0, 0.0);
    }
    if a + e <= 0.0 || (a + e).is_nan() {
        // no inertia along the tangents: the linear objective's minimiser on the circle
        return (-R * b1 / nb, -R * b2 / nb);
    }
    // eigen-decomposition of A: l1 ≥ l2 ≥ 0, unit eigenvector u of l1, w ⊥ u
    let (mean, half) = (0.5 * (a + e), len(0.5 * (a - e), c));
    let (l1, l2) = (mean + half, (mean - half).max(0.0));
    // (d + half, c) and (c, half − d) are eigenvectors of l1 (d = (a − e)/2); the one of the
    // larger norm, which is zero only when A = mean I (then any unit vector is)
    let d = 0.5 * (a - e);
    let u = if d >= 0.0 {
        (d + half, c)
    } else {
        (c, half - d)
    };
    let nu = len(u.0, u.1);
    let u = if nu > 0.0 {
        (u.0 / nu, u.1 / nu)
    } else {
        (1.0, 0.0)
    };
    let (p, q) = (u.0 * b1 + u.1 * b2, -u.1 * b1 + u.0 * b2);
    let at = |k: f64| {
        let (x, y) = (-p / (l1 + k), -q / (l2 + k));
        (u.0 * x - u.1 * y, u.1 * x + u.0 * y)
    };
    let norm = |k: f64| len(p / (l1 + k), q / (l2 + k));
    if l2 > 1e-14 * l1 && norm(0.0) <= R {
        return at(0.0);
    }
    let mut k = 0.0f64.max(1e-14 * l1);
    for _ in 0..50 {
        let n = norm(k);
        let d = (p * p / (l1 + k).powi(3) + q * q / (l2 + k).powi(3)) / n.powi(3);
        let step = (1.0 / n - 1.0 / R) / d;
        let next = (k - step).max(0.5 * k);
        if (next - k).abs() <= 1e-14 * (l1 + next) {
            k = next;
            break;
        }
        k = next;
    }
    let (x, y) = at(k);
    // on the circle to round-off
    let s = R / len(x, y).max(R);
    (x * s, y * s)
}

/// `√(x² + y²)` (the impulses here are far from overflow: no need of `hypot`'s care, which
/// costs a tenth of a contact step).
pub(super) fn len(x: f64, y: f64) -> f64 {
    (x * x + y * y).sqrt()
}
