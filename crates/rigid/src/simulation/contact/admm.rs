//! The second solver of the contact problem: the alternating direction method of multipliers on
//! the same rows as the Gauss–Seidel sweep, island by island (the blocks that share a dof, whose
//! rows of `G` are zero against every other island's).
//!
//! The Signorini–Coulomb problem `λ ∈ K_μ ⊥ σ̄ + Γ(σ̄) ∈ K_μ*`, `σ̄ = G λ + g` (`g = σ_f − σ*`,
//! `Γ` the De Saxcé shift, [`residuals`](super::residuals)) is, for `Γ` held fixed at `s`, the
//! optimality condition of the convex problem `min ½ λᵀ G λ + λᵀ (g + s)` over the cones. ADMM
//! splits it as `x = z`, `z ∈ K`, with the scaled dual `y` (Boyd et al. 2011, §3.1; on this
//! problem Carpentier, Le Lidec, Montaut et al. 2024, "From compliant to rigid contact
//! simulation: a unified and efficient approach", Alg. 1, Pinocchio's `ADMMContactSolverTpl`):
//!
//! ```text
//! s     = Γ(G x + g)                       the shift at the last iterate
//! x⁺    = (G + ρ I)⁻¹ (ρ z − y − g − s)     one Cholesky solve
//! z⁺    = Π_K(x⁺ + y/ρ)                     per block: the cone K_μ, λ ≥ 0, or free (bilateral)
//! y⁺    = y + ρ (x⁺ − z⁺)
//! ```
//!
//! At a fixed point `x = z = λ`, `−y = G λ + g + s = σ̄ + Γ(σ̄)` and `λ = Π_K(λ + y/ρ)`, which is
//! `λ ∈ K ⊥ −y ∈ K*`: the problem itself. `ρ` starts at `√(L_min L_max)` of `G`'s diagonal and is
//! rebalanced (primal against dual residual, at most every 10 iterations, refactoring `G + ρI`).
//! It stops when `‖x − z‖∞` and the change of `z` in an iteration are both within `tolerance`
//! of the largest impulse, the meaning the Gauss–Seidel sweep gives it. The proximal `ρ` makes
//! redundant rows (four corners of a face) harmless, and it spreads the load over them as the
//! sweep, which settles on whichever corner it met first, does not.

use super::pgs::Islands;
use super::solver::Block;
use super::ContactSettings;
use crate::multibody::constraints::solver::{cholesky, cholesky_solve};
use nalgebra::DMatrix;

/// The workspace, reused from step to step (it grows with the largest island seen).
#[derive(Clone, Debug, Default)]
pub(crate) struct Admm {
    /// The blocks of the island being solved.
    order: Vec<usize>,
    /// The rows of the island being solved, and their block's cone per row.
    rows: Vec<usize>,
    /// `G` of the island (n x n, row-major), the factor of `G + ρ I`.
    g_island: Vec<f64>,
    factor: DMatrix<f64>,
    g: Vec<f64>,
    x: Vec<f64>,
    z: Vec<f64>,
    y: Vec<f64>,
    s: Vec<f64>,
    rhs: Vec<f64>,
}

/// What a block's rows are held to.
#[derive(Clone, Copy)]
enum Cone {
    /// `‖λ_t‖ ≤ μ λ_n` (a contact with friction).
    Coulomb(f64),
    /// `λ_n ≥ 0`, `λ_t = 0` (a contact without friction, or the position correction's).
    Normal,
    /// `λ ≥ 0` (a limit).
    Positive,
    /// Free (a bilateral row), or held at 0 (an idle one).
    Free,
}

impl Admm {
    /// Solves `σ = σ₀ + K λ` (`σ` holds `σ₀ + K λ` of the warm `λ` on entry; `K` m x m, stride
    /// m) for the blocks' cones, as [`pgs`](super::pgs) does, island by island, `idle` the
    /// bilateral rows held at 0. Returns the largest number of iterations of an island and
    /// whether every island met the tolerance.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn solve(
        &mut self,
        blocks: &[Block],
        islands: &Islands,
        K: &[f64],
        idle: &[bool],
        target: &[f64],
        lambda: &mut [f64],
        sigma: &mut [f64],
        settings: &ContactSettings,
        friction: bool,
    ) -> (usize, bool) {
        let m = lambda.len();
        let (mut most, mut all) = (0, true);
        for island in islands.iter() {
            self.order.clear();
            self.order.extend_from_slice(island);
            self.rows.clear();
            for &b in &self.order {
                self.rows
                    .extend(blocks[b].row..blocks[b].row + blocks[b].dim);
            }
            let (it, ok) = self.island_solve(
                blocks, K, m, idle, target, lambda, sigma, settings, friction,
            );
            most = most.max(it);
            all &= ok;
        }
        (most, all)
    }

    /// ADMM on the island of `self.order` (rows `self.rows`).
    #[allow(clippy::too_many_arguments)]
    fn island_solve(
        &mut self,
        blocks: &[Block],
        K: &[f64],
        m: usize,
        idle: &[bool],
        target: &[f64],
        lambda: &mut [f64],
        sigma: &mut [f64],
        settings: &ContactSettings,
        friction: bool,
    ) -> (usize, bool) {
        let n = self.rows.len();
        let rows = &self.rows;
        self.g_island.resize(n * n, 0.0);
        for v in [
            &mut self.g,
            &mut self.x,
            &mut self.z,
            &mut self.y,
            &mut self.s,
            &mut self.rhs,
        ] {
            v.resize(n, 0.0);
        }
        if self.factor.nrows() < n {
            self.factor = DMatrix::zeros(n, n);
        }
        let G = &mut self.g_island;
        for (a, &ra) in rows.iter().enumerate() {
            for (b, &rb) in rows.iter().enumerate() {
                G[a * n + b] = K[rb * m + ra];
            }
        }
        // g = σ − σ* − G λ (σ̄ = G λ + g), and the warm start z = Π_K(λ), y = −(σ̄ + Γ(σ̄))
        let cones = |b: &Block| {
            if b.bilateral {
                Cone::Free
            } else if b.dim == 1 {
                Cone::Positive
            } else if friction && b.friction > 0.0 {
                Cone::Coulomb(b.friction)
            } else {
                Cone::Normal
            }
        };
        for (a, &ra) in rows.iter().enumerate() {
            let gl: f64 = (0..n).map(|b| G[a * n + b] * lambda[rows[b]]).sum();
            self.g[a] = sigma[ra] - target[ra] - gl;
            self.z[a] = lambda[ra];
        }
        let project = |order: &[usize], z: &mut [f64]| {
            let mut a = 0;
            for &bi in order {
                let b = &blocks[bi];
                let z = &mut z[a..a + b.dim];
                match cones(b) {
                    Cone::Coulomb(mu) => cone_project(mu, z),
                    Cone::Normal => {
                        z[0] = z[0].max(0.0);
                        z[1..].fill(0.0);
                    }
                    Cone::Positive => z[0] = z[0].max(0.0),
                    Cone::Free => {
                        for (i, zi) in z.iter_mut().enumerate() {
                            if idle[b.row + i] {
                                *zi = 0.0;
                            }
                        }
                    }
                }
                a += b.dim;
            }
        };
        let shift = |order: &[usize], sbar: &[f64], s: &mut [f64]| {
            let mut a = 0;
            for &bi in order {
                let b = &blocks[bi];
                s[a..a + b.dim].fill(0.0);
                if let Cone::Coulomb(mu) = cones(b) {
                    s[a] = mu * (sbar[a + 1] * sbar[a + 1] + sbar[a + 2] * sbar[a + 2]).sqrt();
                }
                a += b.dim;
            }
        };
        project(&self.order, &mut self.z);
        // σ̄(z) into x (scratch), then s and y
        for a in 0..n {
            self.x[a] = self.g[a] + (0..n).map(|b| G[a * n + b] * self.z[b]).sum::<f64>();
        }
        shift(&self.order, &self.x, &mut self.s);
        for a in 0..n {
            self.y[a] = -(self.x[a] + self.s[a]);
        }
        self.x.copy_from_slice(&self.z);
        // ρ from the spread of G's diagonal
        let (lo, hi) = (0..n)
            .map(|a| G[a * n + a])
            .filter(|d| *d > 0.0)
            .fold((f64::INFINITY, 0.0f64), |(l, h), d| (l.min(d), h.max(d)));
        if hi == 0.0 {
            return (0, true);
        }
        let mut rho = (lo * hi).sqrt();
        let refactor = |factor: &mut DMatrix<f64>, rho: f64| {
            for a in 0..n {
                for b in 0..=a {
                    factor[(a, b)] = G[a * n + b];
                }
                factor[(a, a)] += rho;
            }
            cholesky(factor, n).is_ok()
        };
        if !refactor(&mut self.factor, rho) {
            return (0, false);
        }
        // the velocity scale of the dual residual: the free motion's
        let speed = self.g.iter().fold(1e-300, |a: f64, g| a.max(g.abs()));
        let mut last_factor = 0;
        let mut done = (settings.max_iterations, false);
        for it in 1..=settings.max_iterations {
            // x⁺ = (G + ρ I)⁻¹ (ρ z − y − g − s)
            for a in 0..n {
                self.rhs[a] = rho * self.z[a] - self.y[a] - self.g[a] - self.s[a];
            }
            self.x.copy_from_slice(&self.rhs);
            cholesky_solve(&self.factor, n, &mut self.x);
            // σ̄(x) = G x + g = rhs − ρ x + g, and the next shift
            for a in 0..n {
                self.rhs[a] += self.g[a] - rho * self.x[a];
            }
            shift(&self.order, &self.rhs, &mut self.s);
            // z⁺ = Π_K(x⁺ + y/ρ), y⁺ = y + ρ (x⁺ − z⁺)
            let (mut dz, mut primal, mut dual, mut largest) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
            for a in 0..n {
                self.rhs[a] = self.x[a] + self.y[a] / rho;
            }
            project(&self.order, &mut self.rhs);
            for a in 0..n {
                let z = self.rhs[a];
                dz = dz.max((z - self.z[a]).abs());
                self.z[a] = z;
                let r = self.x[a] - z;
                primal = primal.max(r.abs());
                self.y[a] += rho * r;
                largest = largest.max(z.abs());
                dual = dual.max(self.y[a].abs());
            }
            let tol = settings.tolerance * largest;
            if primal <= tol && dz <= tol {
                done = (it, true);
                break;
            }
            // rebalance ρ: the primal residual against the dual one (ρ Δz), each relative
            let (rp, rd) = (primal / largest.max(1e-300), rho * dz / dual.max(speed));
            if it - last_factor >= 10 && (rp > 10.0 * rd || rd > 10.0 * rp) {
                let scale = (rp / rd.max(1e-300)).sqrt().clamp(0.01, 100.0);
                rho *= scale;
                // keep y (the dual) as is: the scaled problem has the same fixed points
                if !refactor(&mut self.factor, rho) {
                    done = (it, false);
                    break;
                }
                last_factor = it;
            }
        }
        // λ = z; σ = σ* + G z + g
        for (a, &ra) in rows.iter().enumerate() {
            lambda[ra] = self.z[a];
            sigma[ra] =
                target[ra] + self.g[a] + (0..n).map(|b| G[a * n + b] * self.z[b]).sum::<f64>();
        }
        done
    }
}

/// The projection onto the Coulomb cone `‖x_t‖ ≤ μ x_n` (`x = (x_n, x_t)`): itself inside, 0
/// inside the polar cone, else onto the cone's edge (the second-order cone's projection).
fn cone_project(mu: f64, x: &mut [f64]) {
    let t = (x[1] * x[1] + x[2] * x[2]).sqrt();
    if t <= mu * x[0] {
        return;
    }
    if mu * t <= -x[0] {
        x.fill(0.0);
        return;
    }
    let n = (mu * t + x[0]) / (mu * mu + 1.0);
    let k = mu * n / t;
    x[0] = n;
    x[1] *= k;
    x[2] *= k;
}
