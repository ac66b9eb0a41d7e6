//! The linear algebra of the constrained problems: the Delassus matrix through the tree-sparse
//! factor `M = LᵀL`, a dense Cholesky, and the proximal iterations.
//!
//! With `M = LᵀL` (Featherstone 2008, §6.5: `L` keeps the tree's sparsity) and `Z = L⁻ᵀ Jᵀ`:
//! `M⁻¹ = L⁻¹ L⁻ᵀ`, so the Delassus matrix is `K = J M⁻¹ Jᵀ = Zᵀ Z`, and for any `w = L⁻ᵀ f`
//! the solution of `M x = f + Jᵀ λ` is `x = L⁻¹ (w + Z λ)`, with `J x = Zᵀ w + K λ`. The column
//! of `Z` of a constraint row is nonzero only on the constraint's support (the chains of its two
//! joints), so building `Z` costs O(m d²) and `K` O(m² d) for a depth d. This is the Schur
//! complement form of the KKT system `[[M, −Jᵀ], [J, μ I]]` that Pinocchio's
//! `ContactCholeskyDecomposition` factorises as a whole (Carpentier, Budhiraja & Mansard 2021).

use super::workspace::{ConstraintData, Support};
use super::{ConstraintError, ProximalSettings, SolverStats};
use crate::multibody::algorithms::{ltl_solve_lower, NO_DOF};
use crate::multibody::Data;
use nalgebra::{DMatrix, DVector};

/// `Z = L⁻ᵀ Jᵀ` and `K = Zᵀ Z` from `cd.jacobian` and the factor `L` in `data.chol`
/// (`data.dof_parent` its parent dofs).
pub(crate) fn delassus(data: &Data, cd: &mut ConstraintData) {
    let n = cd.placements.len();
    delassus_rows(
        data,
        &cd.rows[..=n],
        &cd.support[..n],
        &cd.jacobian,
        None,
        cd.z.as_mut_slice(),
        cd.delassus.as_mut_slice(),
    );
}

/// Per block `c`, the row ranges `list[first[c]..first[c + 1]]` of the blocks whose supports
/// share a dof with its: `(list, first)`.
pub(crate) type Coupled<'a> = (&'a [(usize, usize)], &'a [usize]);

/// The kernel of [`delassus`] on any set of row blocks (constraints, contacts, joint limits):
/// block `c` has rows `rows[c]..rows[c + 1]` of `J` (`J.nrows()` may exceed `m = rows[n]`) and
/// the support `support[c]` (its dofs, closed under taking parents). Writes `Z = L⁻ᵀ Jᵀ`
/// column-major into `Z` (column r at `r * nv`; at least `nv m` entries) and `K = Zᵀ Z`, `m x m`
/// with stride `m`, into `K` (at least `m²` entries). With `coupled` (per block `c`, the row
/// ranges `list[first[c]..first[c + 1]]` of the blocks whose supports share a dof with its),
/// only those entries are computed and the others set to zero, which they are: two rows whose
/// supports share no dof have `Z_rᵀ Z_s = 0`.
pub(crate) fn delassus_rows(
    data: &Data,
    rows: &[usize],
    support: &[Support],
    J: &DMatrix<f64>,
    coupled: Option<Coupled>,
    Z: &mut [f64],
    K: &mut [f64],
) {
    let nv = data.chol.nrows();
    let n = support.len();
    let m = rows[n];
    let (L, lambda) = (data.chol.as_slice(), &data.dof_parent);
    // Z, column-major: column r = Z[r * nv..(r + 1) * nv]
    for c in 0..n {
        let support = &support[c].cols;
        let rows = rows[c]..rows[c + 1];
        // the whole row first: a row of Z is zero outside its constraint's support, which the
        // products below rely on, and a row may have held another support before (contacts
        // come and go between steps)
        for r in rows.clone() {
            Z[r * nv..(r + 1) * nv].fill(0.0);
            for &(k, _, _) in support {
                Z[r * nv + k] = J[(r, k)];
            }
        }
        // back substitution on the support, from its deepest dof up (it is closed under taking
        // parents, so the fill-in stays in it), the constraint's rows together so that each
        // chain of parents is walked once
        for &(k, _, _) in support.iter().rev() {
            let d = L[k * nv + k];
            for r in rows.clone() {
                Z[r * nv + k] /= d;
            }
            let mut j = lambda[k];
            while j != NO_DOF {
                let l = L[j * nv + k];
                for r in rows.clone() {
                    Z[r * nv + j] -= l * Z[r * nv + k];
                }
                j = lambda[j];
            }
        }
    }
    // K[r, s] = Z_rᵀ Z_s over the runs of consecutive dofs of r's constraint's support (Z_r is
    // zero outside it), for the rows s ≤ r of the blocks `coupled` says may share a dof with it
    // (every block when it is `None`); zero elsewhere
    if coupled.is_some() {
        K[..m * m].fill(0.0);
    }
    for c in 0..n {
        let runs = Runs::of(&support[c].cols);
        let ranges = match coupled {
            Some((list, first)) => &list[first[c]..first[c + 1]],
            None => &[(0, m)][..],
        };
        for r in rows[c]..rows[c + 1] {
            let zr = &Z[r * nv..(r + 1) * nv];
            for &(lo, hi) in ranges {
                for s in lo..hi.min(r + 1) {
                    let zs = &Z[s * nv..(s + 1) * nv];
                    let x = match runs.len {
                        1 => dot(
                            &zr[runs.runs[0].0..runs.runs[0].1],
                            &zs[runs.runs[0].0..runs.runs[0].1],
                        ),
                        _ => runs.iter().map(|(a, b)| dot(&zr[a..b], &zs[a..b])).sum(),
                    };
                    K[s * m + r] = x;
                    K[r * m + s] = x;
                }
            }
        }
    }
}

/// The runs of consecutive dofs of a support (ascending), at most [`Runs::MOST`]; the last
/// stretches to the support's end when there are more, and one run spans them all when the gaps
/// save less than [`Runs::GAP`] products per run beyond the first (a leg's chain below a
/// floating base: one dot product over the span is the cheaper). `Z` is zero in the gaps: the
/// products are the same.
struct Runs {
    runs: [(usize, usize); Runs::MOST],
    len: usize,
}

impl Runs {
    const MOST: usize = 16;
    /// The products a dot product of its own is taken to cost beyond its length (a guess, not
    /// tuned: Solo-12's legs, two runs of 6 and 3 over a span of up to 18, take one dot product;
    /// a heap's contact pairs, 12 dofs over a span of up to 108, take the runs).
    const GAP: usize = 16;

    fn of(cols: &[(usize, bool, bool)]) -> Self {
        let mut runs = [(0, 0); Self::MOST];
        let mut len = 0;
        for &(k, _, _) in cols {
            match runs[..len].last_mut() {
                Some(last) if last.1 == k || len == Self::MOST => last.1 = k + 1,
                _ => {
                    runs[len] = (k, k + 1);
                    len += 1;
                }
            }
        }
        if len > 1 {
            let inside: usize = runs[..len].iter().map(|(a, b)| b - a).sum();
            let (start, end) = (runs[0].0, runs[len - 1].1);
            if inside + Self::GAP * (len - 1) >= end - start {
                runs[0] = (start, end);
                len = 1;
            }
        }
        Self { runs, len }
    }

    fn iter(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.runs[..self.len].iter().copied()
    }
}

/// `aᵀ b` with four partial sums (independent chains of additions).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut s = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for i in 0..4 {
            s[i] += x[i] * y[i];
        }
    }
    (s[0] + s[1]) + (s[2] + s[3]) + tail
}

/// `y = Zᵀ x` over the supports (`y` of length m).
pub(crate) fn z_transpose_times(cd: &ConstraintData, x: &[f64], y: &mut [f64]) {
    for c in 0..cd.placements.len() {
        for r in cd.rows[c]..cd.rows[c + 1] {
            y[r] = cd.support[c]
                .cols
                .iter()
                .map(|&(k, _, _)| cd.z[(k, r)] * x[k])
                .sum();
        }
    }
}

/// `x ← L⁻¹ (x + Z λ)`: the primal solution from `x = w` and the multipliers.
pub(crate) fn primal(data: &Data, cd: &ConstraintData, lambda: &DVector<f64>, x: &mut [f64]) {
    let n = cd.placements.len();
    primal_rows(
        data,
        &cd.rows[..=n],
        &cd.support[..n],
        cd.z.as_slice(),
        lambda.as_slice(),
        x,
    );
}

/// The kernel of [`primal`] on any set of row blocks (see [`delassus_rows`]).
pub(crate) fn primal_rows(
    data: &Data,
    rows: &[usize],
    support: &[Support],
    Z: &[f64],
    lambda: &[f64],
    x: &mut [f64],
) {
    let nv = data.chol.nrows();
    for c in 0..support.len() {
        for r in rows[c]..rows[c + 1] {
            if lambda[r] != 0.0 {
                for &(k, _, _) in &support[c].cols {
                    x[k] += Z[r * nv + k] * lambda[r];
                }
            }
        }
    }
    ltl_solve_lower(data.chol.as_slice(), &data.dof_parent, x);
}

/// In-place Cholesky `A = G Gᵀ` of the leading `n x n` block of `a` (lower triangle; the upper
/// one is left as it was).
///
/// # Errors
/// [`ConstraintError::Singular`] when a pivot is not positive (relative to the largest diagonal
/// entry, 1e-14) or not finite.
pub(crate) fn cholesky(a: &mut DMatrix<f64>, n: usize) -> Result<(), ConstraintError> {
    let scale = (0..n).map(|i| a[(i, i)].abs()).fold(0.0, f64::max);
    for j in 0..n {
        let mut d = a[(j, j)];
        for k in 0..j {
            d -= a[(j, k)] * a[(j, k)];
        }
        if d.is_nan() || d <= 1e-14 * scale || !d.is_finite() {
            return Err(ConstraintError::Singular);
        }
        let d = d.sqrt();
        a[(j, j)] = d;
        for i in j + 1..n {
            let mut s = a[(i, j)];
            for k in 0..j {
                s -= a[(i, k)] * a[(j, k)];
            }
            a[(i, j)] = s / d;
        }
    }
    Ok(())
}

/// `x ← (G Gᵀ)⁻¹ x` with the factor of [`cholesky`] in the leading `n x n` block of `g`.
pub(crate) fn cholesky_solve(g: &DMatrix<f64>, n: usize, x: &mut [f64]) {
    for i in 0..n {
        let mut s = x[i];
        for k in 0..i {
            s -= g[(i, k)] * x[k];
        }
        x[i] = s / g[(i, i)];
    }
    for i in (0..n).rev() {
        let mut s = x[i];
        for k in i + 1..n {
            s -= g[(k, i)] * x[k];
        }
        x[i] = s / g[(i, i)];
    }
}

/// The proximal iterations on `K λ = b` (`K` in `cd.delassus`, `b` in `cd.b`), from `λ_0 = 0`,
/// into `cd.lambda` and `cd.stats` ([`proximal_solve`]).
///
/// # Errors
/// [`ConstraintError::Singular`] when `K + μ I` is not positive definite.
pub(crate) fn proximal(
    cd: &mut ConstraintData,
    settings: &ProximalSettings,
) -> Result<(), ConstraintError> {
    let m = cd.dim();
    cd.stats = proximal_solve(
        &cd.delassus,
        &mut cd.chol,
        &cd.b.as_slice()[..m],
        cd.lambda.as_mut_slice(),
        &mut cd.prev.as_mut_slice()[..m],
        settings,
    )?;
    Ok(())
}

/// The proximal point iterations on a symmetric positive semi-definite system `K x = b`
/// (`n = b.len()`), from `x_0 = 0`: `(K + μ I) x_{k+1} = b + μ x_k` until
/// `‖K x − b‖∞ ≤ absolute_accuracy` or `‖x_{k+1} − x_k‖∞ ≤ relative_accuracy`, at most
/// `max_iter` times (RSS 2021, Alg. 1: Rockafellar's proximal point method, which converges for
/// any `μ > 0` when `b` is in the range of `K`, and then to the `x` of least norm, the iterates
/// staying in that range). With `μ = 0` one exact solve. `chol` receives the factor of
/// `K + μ I`; `prev` is scratch.
///
/// # Errors
/// [`ConstraintError::Singular`] when `K + μ I` is not positive definite.
pub(crate) fn proximal_solve(
    K: &DMatrix<f64>,
    chol: &mut DMatrix<f64>,
    b: &[f64],
    x: &mut [f64],
    prev: &mut [f64],
    settings: &ProximalSettings,
) -> Result<SolverStats, ConstraintError> {
    let n = b.len();
    for i in 0..n {
        for k in 0..=i {
            chol[(i, k)] = K[(i, k)];
        }
        chol[(i, i)] += settings.mu;
    }
    cholesky(chol, n)?;
    Ok(proximal_iterations(K, chol, b, x, prev, settings))
}

/// The iterations of [`proximal_solve`] on the factor `chol` of `K + μ I` it made (and kept:
/// the derivatives of the constrained dynamics run them on each column).
pub(crate) fn proximal_iterations(
    K: &DMatrix<f64>,
    chol: &DMatrix<f64>,
    b: &[f64],
    x: &mut [f64],
    prev: &mut [f64],
    settings: &ProximalSettings,
) -> SolverStats {
    let n = b.len();
    let mu = settings.mu;
    prev.fill(0.0);
    let mut stats = SolverStats::default();
    let max_iter = if mu == 0.0 { 1 } else { settings.max_iter };
    for it in 1..=max_iter {
        for i in 0..n {
            x[i] = b[i] + mu * prev[i];
        }
        cholesky_solve(chol, n, &mut x[..n]);
        let mut rel: f64 = 0.0;
        let mut abs: f64 = 0.0;
        for i in 0..n {
            rel = rel.max((x[i] - prev[i]).abs());
            let mut r = -b[i];
            for k in 0..n {
                r += K[(i, k)] * x[k];
            }
            abs = abs.max(r.abs());
        }
        prev.copy_from_slice(&x[..n]);
        stats = SolverStats {
            iterations: it,
            absolute_residual: abs,
            relative_residual: rel,
            converged: mu == 0.0
                || abs <= settings.absolute_accuracy
                || rel <= settings.relative_accuracy,
            dynamics_residual: 0.0,
        };
        if stats.converged {
            break;
        }
    }
    stats
}

/// The minimum-norm least-squares solution `y = G⁺ b` of a symmetric positive semi-definite
/// system (`n = b.len()`), by the Cholesky factorisation with complete (diagonal) pivoting
/// `P G Pᵀ = L Lᵀ`, `L` n x r, stopped at the rank r where the largest remaining pivot is at most
/// `1e-12` times the largest diagonal entry (Higham 2002, §10.3, LAPACK's `dpstrf`); then
/// `G⁺ = Pᵀ L (LᵀL)⁻² Lᵀ P` (`Lᵀ` has full row rank). `c` receives `L`, `n2` the factor of
/// `LᵀL`, `perm` the pivots; `y` the solution. Returns the rank.
pub(crate) fn pinv_solve(
    G: &DMatrix<f64>,
    c: &mut DMatrix<f64>,
    n2: &mut DMatrix<f64>,
    perm: &mut [usize],
    b: &[f64],
    y: &mut [f64],
) -> usize {
    let n = b.len();
    for i in 0..n {
        perm[i] = i;
        for k in 0..=i {
            c[(i, k)] = G[(i, k)];
        }
    }
    let tol = 1e-12 * (0..n).map(|i| G[(i, i)]).fold(0.0, f64::max);
    let mut rank = n;
    for j in 0..n {
        let p = (j..n)
            .max_by(|&a, &b| c[(a, a)].total_cmp(&c[(b, b)]))
            .expect("j < n");
        if c[(p, p)].is_nan() || c[(p, p)] <= tol {
            rank = j;
            break;
        }
        if p != j {
            // symmetric swap of rows and columns j and p in the lower triangle
            perm.swap(j, p);
            for k in 0..j {
                let t = c[(j, k)];
                c[(j, k)] = c[(p, k)];
                c[(p, k)] = t;
            }
            let t = c[(j, j)];
            c[(j, j)] = c[(p, p)];
            c[(p, p)] = t;
            for i in j + 1..p {
                let t = c[(i, j)];
                c[(i, j)] = c[(p, i)];
                c[(p, i)] = t;
            }
            for i in p + 1..n {
                let t = c[(i, j)];
                c[(i, j)] = c[(i, p)];
                c[(i, p)] = t;
            }
        }
        let d = c[(j, j)].sqrt();
        c[(j, j)] = d;
        for i in j + 1..n {
            c[(i, j)] /= d;
        }
        for k in j + 1..n {
            let ckj = c[(k, j)];
            for i in k..n {
                c[(i, k)] -= c[(i, j)] * ckj;
            }
        }
    }
    let r = rank;
    // LᵀL (r x r) and its Cholesky factor
    for i in 0..r {
        for k in 0..=i {
            n2[(i, k)] = (i..n).map(|l| c[(l, i)] * c[(l, k)]).sum();
        }
    }
    if cholesky(n2, r).is_err() {
        // only a non-finite G gets here (LᵀL is positive definite for the rank found): say so
        y[..n].fill(f64::NAN);
        return r;
    }
    // w = Lᵀ P b, solved twice with LᵀL, then y = Pᵀ L w
    for i in 0..r {
        y[i] = (i..n).map(|l| c[(l, i)] * b[perm[l]]).sum();
    }
    cholesky_solve(n2, r, &mut y[..r]);
    cholesky_solve(n2, r, &mut y[..r]);
    // z = L w (n), written from the last row up so that y[..r] is read before it is overwritten
    for l in (0..n).rev() {
        let z: f64 = (0..r.min(l + 1)).map(|i| c[(l, i)] * y[i]).sum();
        y[l] = z;
    }
    // y ← Pᵀ z: y[perm[l]] = z[l]
    for l in 0..n {
        c[(l, 0)] = y[l]; // the factor is no longer needed: reuse its first column
    }
    for l in 0..n {
        y[perm[l]] = c[(l, 0)];
    }
    rank
}
