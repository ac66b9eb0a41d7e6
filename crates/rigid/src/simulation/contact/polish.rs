//! The active-set polish of projected Gauss–Seidel: where the sweep has found which contacts
//! separate, stick or slide but converges to the impulses slowly (a statically indeterminate
//! stance, a long chain between two contacts: the sweep's linear rate tends to 1), solve the
//! equations of that active set in one dense step, and keep the result only if it is feasible.
//!
//! Per block, a mode read from the current impulses (Silcowitz, Niebe and Erleben 2010,
//! "Projected Gauss–Seidel subspace minimization for interactive rigid body dynamics", §3; here
//! with the exact Coulomb cone, whose sliding law is solved by Newton's method):
//!
//! ```text
//! separated   λ_n = 0                   λ = 0
//! sticking    0 < λ_n, ‖λ_t‖ < μ λ_n     σ = σ*                            (3 equations)
//! sliding     ‖λ_t‖ = μ λ_n > 0          σ_n = σ*_n, λ_t = −μ λ_n σ_t/‖σ_t‖  (3 equations)
//! limit       λ > 0                     σ = σ*                            (1)
//! bilateral   always                    σ = σ*                            (its rows)
//! ```
//!
//! With `σ = σ₀ + K λ` the equations are linear but for the sliding law, linearised at the
//! current slip `ŝ = σ_t/s`: `δλ_t + μ ŝ δλ_n + (μ λ_n/s)(I − ŝŝᵀ) δσ_t = −(λ_t + μ λ_n ŝ)`.
//! Each Newton step is one dense solve of the active rows (not symmetric with a sliding
//! contact): Gaussian elimination with partial pivoting, in place (no allocation once the
//! workspace has grown; nalgebra's `LU` owns its matrix and permutation), on `A + ε I` with `ε =
//! 10⁻¹² max |A_ii|` so that redundant rows (four corners of a face) give a bounded solution,
//! then refined against `A` itself ([`REFINE`] steps). A step whose velocities exceed
//! [`LARGEST_STEP`] times the problem's (`‖δλ‖ max|A_ii|` against its speed: the largest
//! `|σ|` and `|σ*|` of the current step and `|K λ|` of the polish's start, for at rest `σ` and
//! `σ*` are ~0 and the speed the impulses cancel, gravity's kick, is the scale; the thresholds
//! of slip and approach below are relative to it too) solved an inconsistent singular system
//! (four coplanar corners held to targets no rigid motion meets) and ends the polish: its
//! cancellation would leave round-off of its size in `σ`.
//! After each step the modes are read again: a negative normal impulse separates, a separated
//! contact approaching faster than its target is held, a sticking one outside its cone slides, a
//! sliding one slipping along its friction sticks. The polish is kept when the modes stand and
//! every sliding law holds (to 10⁻⁸ of `μ λ_n`) within [`TRIES`] steps; otherwise `λ` and `σ`
//! return to where the sweep left them. A kept polish ends the solve as converged: its impulses
//! solve the problem (every mode's equations to round-off, every cone and complementarity
//! condition to the tolerances above), which the sweep's own test (no impulse changing by more
//! than 1e-10 of the largest) may not see for many sweeps where redundant contacts leave the
//! impulses' split free.

use super::pgs::len;
use super::solver::Block;

/// The contact problem a polish works on: `σ = σ₀ + K λ` (`K` m x m, stride m) over the blocks
/// of one island (`island`: indices into `blocks`, whose rows of `K` are zero against the
/// others'), `idle` the bilateral rows held at 0, `target` each row's `σ*`, `friction` as the
/// sweep's, `largest` the most active rows worth a dense solve.
#[derive(Clone, Copy)]
pub(crate) struct Problem<'a> {
    pub(crate) blocks: &'a [Block],
    pub(crate) island: &'a [usize],
    pub(crate) K: &'a [f64],
    pub(crate) idle: &'a [bool],
    pub(crate) target: &'a [f64],
    pub(crate) friction: bool,
    pub(crate) largest: usize,
}

/// The workspace, reused from step to step (it grows with the largest problem seen).
#[derive(Clone, Debug, Default)]
pub(crate) struct Polish {
    /// Per block of the island, its mode.
    modes: Vec<Mode>,
    /// The unknowns' rows (each row's impulse), and the equations' (row, kind).
    unknowns: Vec<usize>,
    equations: Vec<(usize, Equation)>,
    /// `A` (n x n, row-major), its factors (of `A + ε I`) and their row swaps, the right-hand
    /// side, the solution and the refinement's residual.
    a: Vec<f64>,
    lu: Vec<f64>,
    swaps: Vec<usize>,
    b: Vec<f64>,
    x: Vec<f64>,
    r: Vec<f64>,
    /// `λ` and `σ` before the polish (restored when it is refused).
    saved: Vec<f64>,
    /// The largest `|K λ|` of the island's rows at the polish's start.
    kick: f64,
}

/// What a block's impulses are held to in the polish.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Mode {
    /// `λ = 0`.
    Free,
    /// `σ = σ*` on every row.
    Held,
    /// `σ_n = σ*_n`, `λ_t = −μ λ_n σ_t/‖σ_t‖`.
    Slide,
}

/// One equation of the polish.
#[derive(Clone, Copy, Debug)]
enum Equation {
    /// `σ_r = σ*_r`.
    Velocity,
    /// Tangent `i` of a sliding contact, Newton's linearisation of
    /// `λ_t + μ λ_n ŝ = 0` at the current `ŝ = σ_t/s`: `δλ_t + μ ŝ δλ_n + (μ λ_n/s) P δσ_t =
    /// −(λ_t + μ λ_n ŝ)`, `P = I − ŝ ŝᵀ`; the row is the block's normal row, `(ŝ, s, μ)` given.
    Slip(usize, [f64; 2], f64, f64),
}

/// A sliding contact's tangent impulse is on the cone's boundary within this share of `μ λ_n`.
const ON_CONE: f64 = 1e-9;

/// The most Newton steps (and changes of the active set) in one polish.
const TRIES: usize = 4;

/// The largest Newton step taken, `‖δλ‖∞ max|A_ii|` (over the velocity rows) over the problem's
/// speed (the largest `|σ|`, `|σ*|` or `|K λ|` at the polish's start): its cancellation leaves
/// at most ~1e-10 of that scale of round-off in `σ`.
const LARGEST_STEP: f64 = 1e6;

/// Steps of iterative refinement of each Newton step's solve against the unregularised `A`.
const REFINE: usize = 2;

impl Polish {
    /// Polishes `λ` and `σ` for the active set of `p`'s blocks. Returns whether the polished
    /// impulses were kept (else `λ` and `σ` are as they came).
    pub(crate) fn apply(&mut self, p: Problem, lambda: &mut [f64], sigma: &mut [f64]) -> bool {
        let friction = p.friction;
        self.modes.clear();
        for b in p.island.iter().map(|&i| &p.blocks[i]) {
            let r = b.row;
            let mode = if b.bilateral {
                Mode::Held
            } else if lambda[r] <= 0.0 {
                Mode::Free
            } else if slides(b, friction) {
                let t = len(lambda[r + 1], lambda[r + 2]);
                if t < b.friction * lambda[r] * (1.0 - ON_CONE) {
                    Mode::Held
                } else {
                    Mode::Slide
                }
            } else {
                Mode::Held
            };
            self.modes.push(mode);
        }
        // beyond the dense solve's budget from the start: refused before `|K λ|` is computed
        let n = self.unknowns(p);
        if n == 0 || n > p.largest {
            return false;
        }
        let rows = || {
            p.island.iter().flat_map(|&i| {
                let b = &p.blocks[i];
                b.row..b.row + b.dim
            })
        };
        let m = lambda.len();
        self.kick = rows()
            .map(|r| {
                rows()
                    .map(|s| p.K[r * m + s] * lambda[s])
                    .sum::<f64>()
                    .abs()
            })
            .fold(0.0, f64::max);
        self.saved.clear();
        self.saved.extend_from_slice(lambda);
        self.saved.extend_from_slice(sigma);
        for _ in 0..TRIES {
            if !self.solve(p, lambda, sigma) {
                break;
            }
            if !self.next_modes(p, lambda, sigma) {
                return true;
            }
        }
        self.restore(lambda, sigma);
        false
    }

    /// The number of unknowns [`solve`](Self::solve) sets up for the current modes.
    fn unknowns(&self, p: Problem) -> usize {
        let blocks = p.island.iter().map(|&i| &p.blocks[i]);
        blocks
            .zip(&self.modes)
            .map(|(b, mode)| match *mode {
                Mode::Free => 0,
                Mode::Held if b.bilateral => (b.row..b.row + b.dim).filter(|&r| !p.idle[r]).count(),
                Mode::Held | Mode::Slide if b.dim == 3 && !slides(b, p.friction) => 1,
                Mode::Held | Mode::Slide => b.dim,
            })
            .sum()
    }

    /// One Newton step on the modes' equations from the current `λ`, `σ`. False if the system
    /// is singular, empty or has more than `largest` rows, or the step is beyond
    /// [`LARGEST_STEP`] (an inconsistent singular system).
    fn solve(&mut self, p: Problem, lambda: &mut [f64], sigma: &mut [f64]) -> bool {
        let Problem {
            blocks,
            island,
            K,
            idle,
            target,
            friction,
            largest,
        } = p;
        let m = lambda.len();
        let fast = scale(p, sigma).max(scale(p, target)).max(self.kick);
        self.unknowns.clear();
        self.equations.clear();
        for (b, mode) in island.iter().map(|&i| &blocks[i]).zip(&self.modes) {
            let r = b.row;
            let rows = r..r + b.dim;
            let s = if b.dim == 3 {
                len(sigma[r + 1], sigma[r + 2])
            } else {
                0.0
            };
            match *mode {
                Mode::Free => {
                    for c in rows {
                        add_column(K, m, c, -lambda[c], lambda, sigma);
                    }
                }
                Mode::Held if b.bilateral => {
                    for r in rows.filter(|&r| !idle[r]) {
                        self.unknowns.push(r);
                        self.equations.push((r, Equation::Velocity));
                    }
                }
                Mode::Held | Mode::Slide if b.dim == 3 && !slides(b, friction) => {
                    self.unknowns.push(r);
                    self.equations.push((r, Equation::Velocity));
                }
                Mode::Slide if s > 1e-12 * fast => {
                    self.unknowns.extend(rows);
                    let sh = [sigma[r + 1] / s, sigma[r + 2] / s];
                    self.equations.push((r, Equation::Velocity));
                    for k in 0..2 {
                        let slip = Equation::Slip(k, sh, s, b.friction);
                        self.equations.push((r, slip));
                    }
                }
                Mode::Held | Mode::Slide => {
                    for r in rows {
                        self.unknowns.push(r);
                        self.equations.push((r, Equation::Velocity));
                    }
                }
            }
        }
        let n = self.unknowns.len();
        if n == 0 || n > largest {
            return false;
        }
        self.a.clear();
        self.a.resize(n * n, 0.0);
        self.b.clear();
        for (i, &(p, eq)) in self.equations.iter().enumerate() {
            let row = &mut self.a[i * n..(i + 1) * n];
            match eq {
                Equation::Velocity => {
                    for (a, &c) in row.iter_mut().zip(&self.unknowns) {
                        *a = K[c * m + p];
                    }
                    self.b.push(target[p] - sigma[p]);
                }
                Equation::Slip(k, sh, s, mu) => {
                    let g = mu * lambda[p] / s;
                    // P's row k
                    let pk = [
                        f64::from(u8::from(k == 0)) - sh[k] * sh[0],
                        f64::from(u8::from(k == 1)) - sh[k] * sh[1],
                    ];
                    for (a, &c) in row.iter_mut().zip(&self.unknowns) {
                        let col = &K[c * m..(c + 1) * m];
                        let mut v = g * (pk[0] * col[p + 1] + pk[1] * col[p + 2]);
                        if c == p + 1 + k {
                            v += 1.0;
                        }
                        if c == p {
                            v += mu * sh[k];
                        }
                        *a = v;
                    }
                    self.b.push(-(lambda[p + 1 + k] + mu * lambda[p] * sh[k]));
                }
            }
        }
        if !self.dense_solve(n) {
            return false;
        }
        // a step whose velocities `A δλ` dwarf the problem's solved an inconsistent singular
        // system (four coplanar corners held to targets no rigid motion meets: one must
        // separate); taken, its cancellation would leave ~1e-16 ‖δλ‖ max|A_ii| of round-off in
        // σ (the scale over the velocity rows: a sliding law's rows are dimensionless)
        let a_max = (self.equations.iter().enumerate())
            .filter(|(_, (_, e))| matches!(e, Equation::Velocity))
            .fold(0.0f64, |m, (i, _)| m.max(self.a[i * n + i].abs()));
        let within = amax(&self.x) * a_max <= LARGEST_STEP * fast; // false on NaN
        if !within {
            return false;
        }
        for (&c, &d) in self.unknowns.iter().zip(&self.x) {
            add_column(K, m, c, d, lambda, sigma);
        }
        true
    }

    /// `x = A⁻¹ b` (`A` n x n row-major): `A + ε I` factored (bounded where rows are redundant),
    /// then [`REFINE`] steps of refinement against `A` itself, since the regularisation's bias
    /// (`ε |x|` in the residual) is amplified where the held rows are ill-conditioned. False on
    /// a zero pivot.
    fn dense_solve(&mut self, n: usize) -> bool {
        let eps = 1e-12 * (0..n).map(|i| self.a[i * n + i].abs()).fold(0.0, f64::max);
        self.lu.clear();
        self.lu.extend_from_slice(&self.a);
        for i in 0..n {
            self.lu[i * n + i] += eps;
        }
        if !lu_factor(&mut self.lu, n, &mut self.swaps) {
            return false;
        }
        self.x.clear();
        self.x.extend_from_slice(&self.b);
        lu_apply(&self.lu, n, &self.swaps, &mut self.x);
        for _ in 0..REFINE {
            self.r.clear();
            for i in 0..n {
                let row = &self.a[i * n..(i + 1) * n];
                let ax: f64 = row.iter().zip(&self.x).map(|(a, x)| a * x).sum();
                self.r.push(self.b[i] - ax);
            }
            lu_apply(&self.lu, n, &self.swaps, &mut self.r);
            for (x, d) in self.x.iter_mut().zip(&self.r) {
                *x += d;
            }
        }
        true
    }

    /// The modes the solution `λ`, `σ` of the current ones calls for; true if any changed or a
    /// sliding contact has not yet converged (the solution is then not taken yet).
    fn next_modes(&mut self, p: Problem, lambda: &[f64], sigma: &[f64]) -> bool {
        let (target, friction) = (p.target, p.friction);
        let big = scale(p, lambda);
        let fast = scale(p, sigma).max(scale(p, target)).max(self.kick);
        let (tiny, slow) = (1e-12 * big, 1e-9 * fast);
        let mut changed = false;
        let blocks = p.island.iter().map(|&i| &p.blocks[i]);
        for (b, mode) in blocks.zip(self.modes.iter_mut()) {
            if b.bilateral {
                continue;
            }
            let r = b.row;
            let ln = lambda[r];
            let next = match *mode {
                Mode::Free if sigma[r] < target[r] - slow => Mode::Held,
                Mode::Free => continue,
                _ if !ln.is_finite() || ln < -tiny => Mode::Free,
                _ if !slides(b, friction) => continue,
                Mode::Held => {
                    if len(lambda[r + 1], lambda[r + 2]) <= b.friction * ln * (1.0 + ON_CONE) + tiny
                    {
                        continue;
                    }
                    Mode::Slide
                }
                Mode::Slide => {
                    // converged: λ_t = −μ λ_n ŝ (or no slip, on the cone's boundary)
                    let (s1, s2) = (sigma[r + 1], sigma[r + 2]);
                    let s = len(s1, s2);
                    let R = b.friction * ln;
                    let (t1, t2) = (lambda[r + 1], lambda[r + 2]);
                    let ok = if s <= slow {
                        len(t1, t2) <= R * (1.0 + ON_CONE) + tiny
                    } else {
                        len(t1 + R * s1 / s, t2 + R * s2 / s) <= R * 1e-8 + tiny
                    };
                    if ok {
                        continue;
                    }
                    if t1 * s1 + t2 * s2 > 0.0 {
                        Mode::Held // slipping along its friction: it sticks
                    } else {
                        Mode::Slide // another Newton step
                    }
                }
            };
            *mode = next;
            changed = true;
        }
        changed
    }

    fn restore(&self, lambda: &mut [f64], sigma: &mut [f64]) {
        let m = lambda.len();
        lambda.copy_from_slice(&self.saved[..m]);
        sigma.copy_from_slice(&self.saved[m..]);
    }
}

/// Whether the block's tangent rows are in the sweep (a contact with friction).
fn slides(b: &Block, friction: bool) -> bool {
    b.dim == 3 && friction && b.friction > 0.0 && !b.bilateral
}

/// `max |x_r|` over the rows of `p`'s island.
fn scale(p: Problem, x: &[f64]) -> f64 {
    let rows = p.island.iter().flat_map(|&i| {
        let b = &p.blocks[i];
        b.row..b.row + b.dim
    });
    rows.fold(0.0f64, |a, r| a.max(x[r].abs()))
}

/// `max |x_i|` (NaN if any is).
fn amax(x: &[f64]) -> f64 {
    x.iter().fold(0.0, |a: f64, v| {
        if a.is_nan() || v.is_nan() {
            f64::NAN
        } else {
            a.max(v.abs())
        }
    })
}

/// `λ_c += d`, `σ += K e_c d`.
fn add_column(K: &[f64], m: usize, c: usize, d: f64, lambda: &mut [f64], sigma: &mut [f64]) {
    if d != 0.0 {
        lambda[c] += d;
        for (s, k) in sigma.iter_mut().zip(&K[c * m..(c + 1) * m]) {
            *s += k * d;
        }
    }
}

/// Factors `A` in place (`A` n x n row-major) as `P A = L U` by Gaussian elimination with
/// partial pivoting: `U` on and above the diagonal, `L`'s multipliers below it (unit diagonal),
/// `swaps[k]` the row swapped with row `k` at step `k`. Returns false on a zero pivot.
fn lu_factor(a: &mut [f64], n: usize, swaps: &mut Vec<usize>) -> bool {
    swaps.clear();
    for k in 0..n {
        let p = (k..n)
            .max_by(|&i, &j| a[i * n + k].abs().total_cmp(&a[j * n + k].abs()))
            .unwrap_or(k);
        if a[p * n + k] == 0.0 || !a[p * n + k].is_finite() {
            return false;
        }
        swaps.push(p);
        if p != k {
            for j in 0..n {
                a.swap(k * n + j, p * n + j);
            }
        }
        let pivot = a[k * n + k];
        for i in k + 1..n {
            let f = a[i * n + k] / pivot;
            a[i * n + k] = f;
            if f != 0.0 {
                for j in k + 1..n {
                    a[i * n + j] -= f * a[k * n + j];
                }
            }
        }
    }
    true
}

/// `b ← A⁻¹ b` from [`lu_factor`]'s factors: the swaps, `L y = P b`, then `U x = y`.
fn lu_apply(lu: &[f64], n: usize, swaps: &[usize], b: &mut [f64]) {
    for (k, &p) in swaps.iter().enumerate() {
        b.swap(k, p);
    }
    for i in 1..n {
        let s: f64 = (0..i).map(|j| lu[i * n + j] * b[j]).sum();
        b[i] -= s;
    }
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|j| lu[k * n + j] * b[j]).sum();
        b[k] = (b[k] - s) / lu[k * n + k];
    }
}
