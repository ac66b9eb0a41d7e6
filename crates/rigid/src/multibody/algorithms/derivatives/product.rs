//! `(P, Q) = (-M⁻¹ X, -M⁻¹ Y)` for the derivatives of forward dynamics, skipping the zeros of
//! `X` and `Y`.
//!
//! Columns `c` of `∂τ/∂q` and `∂τ/∂v` are non-zero only on the dofs of `c`'s ancestors (the
//! chain `λ(c), λ(λ(c)), …`) and of its subtree (`c..end[c]`, contiguous in depth-first order),
//! so column `c` of each product is a sum of those columns of `M⁻¹` (symmetric: columns are
//! rows). The two products share the pattern, so each block of `M⁻¹` read serves both. `M⁻¹` is
//! first copied into blocks of 8 rows, its columns padded with zeros, so that every block is
//! full width; the sums over a block are accumulated in registers. On x86-64 with AVX2 and FMA
//! (checked at run time) the sums use fused multiply-adds, on 16 rows at a time; elsewhere plain
//! multiply and add (so the last bits of the result depend on the CPU, as with any BLAS).

use nalgebra::DMatrix;

/// Blocks of 8 rows per padded column of `M⁻¹` for `nv` rows.
pub(crate) fn blocks(nv: usize) -> usize {
    nv.div_ceil(8)
}

/// The sparsity of the right-hand sides: `parent[k]` the ancestor dof of k (`usize::MAX` at a
/// root), `end[k]` one past the last dof of k's subtree.
pub(crate) struct Pattern<'a> {
    pub parent: &'a [usize],
    pub end: &'a [usize],
}

/// `P = -M⁻¹ X`, `Q = -M⁻¹ Y`; `pad` (`blocks(nv) nv` blocks) holds the padded copy of `M⁻¹`,
/// `list` (`nv` entries) a column's non-zero rows.
pub(crate) fn neg_minv_times(
    minv: &DMatrix<f64>,
    (x, y): (&DMatrix<f64>, &DMatrix<f64>),
    (p, q): (&mut DMatrix<f64>, &mut DMatrix<f64>),
    pattern: &Pattern,
    pad: &mut [[f64; 8]],
    list: &mut [Entry],
) {
    let nv = minv.nrows();
    if nv == 0 {
        return;
    }
    let nb = blocks(nv);
    for (dst, src) in pad
        .chunks_exact_mut(nb)
        .zip(minv.as_slice().chunks_exact(nv))
    {
        for (b, d) in dst.iter_mut().enumerate() {
            let rows = &src[8 * b..nv.min(8 * b + 8)];
            d[..rows.len()].copy_from_slice(rows);
            d[rows.len()..].fill(0.0);
        }
    }
    #[cfg(target_arch = "x86_64")]
    let fma =
        std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma");
    #[cfg(not(target_arch = "x86_64"))]
    let fma = false;
    columns((x, y), (p, q), pattern, pad, list, fma);
}

/// The columns of [`neg_minv_times`] once `pad` holds `M⁻¹`; `fma`: the CPU has AVX2 and FMA.
fn columns(
    (x, y): (&DMatrix<f64>, &DMatrix<f64>),
    (p, q): (&mut DMatrix<f64>, &mut DMatrix<f64>),
    pattern: &Pattern,
    pad: &[[f64; 8]],
    list: &mut [Entry],
    fma: bool,
) {
    let nv = x.nrows();
    let nb = blocks(nv);
    let (x, y) = (x.as_slice(), y.as_slice());
    let (p, q) = (p.as_mut_slice(), q.as_mut_slice());
    for (c, (pc, qc)) in p
        .chunks_exact_mut(nv)
        .zip(q.chunks_exact_mut(nv))
        .enumerate()
    {
        let (xc, yc) = (&x[c * nv..(c + 1) * nv], &y[c * nv..(c + 1) * nv]);
        // the column's non-zero rows: its subtree, then its ancestors
        let mut n = 0;
        let mut push = |r: usize| {
            list[n] = Entry {
                offset: r * nb,
                x: xc[r],
                y: yc[r],
            };
            n += 1;
        };
        for r in c..pattern.end[c] {
            push(r);
        }
        let mut r = pattern.parent[c];
        while r != usize::MAX {
            push(r);
            r = pattern.parent[r];
        }
        let list = &mut list[..n];
        // a zero column of X or Y (a free-flyer root's translations in ∂τ/∂q) gives a zero
        // column: then the other is computed alone, as if it were X
        let (zx, zy) = (
            list.iter().all(|e| e.x == 0.0),
            list.iter().all(|e| e.y == 0.0),
        );
        let (out, rest) = match (zx, zy) {
            (false, false) => (pc, Some(qc)),
            (true, true) => {
                pc.fill(0.0);
                qc.fill(0.0);
                continue;
            }
            (false, true) => {
                qc.fill(0.0);
                (pc, None)
            }
            (true, false) => {
                pc.fill(0.0);
                list.iter_mut().for_each(|e| e.x = e.y);
                (qc, None)
            }
        };
        let column = Column {
            m: pad,
            nb,
            nv,
            list,
        };
        #[cfg(target_arch = "x86_64")]
        if fma {
            // SAFETY: `fma` says that the CPU supports AVX2 and FMA (checked by the caller).
            unsafe { column_fma(&column, out, rest) };
            continue;
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = fma;
        column_plain(&column, out, rest);
    }
}

/// One non-zero row of a column of `(X, Y)`: its offset in the padded `M⁻¹` and the two values.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Entry {
    offset: usize,
    x: f64,
    y: f64,
}

/// The inputs of one output column.
struct Column<'a> {
    m: &'a [[f64; 8]],
    nb: usize,
    nv: usize,
    list: &'a [Entry],
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn column_fma(a: &Column, pc: &mut [f64], qc: Option<&mut [f64]>) {
    match qc {
        Some(qc) => sweep::<2, true, true>(a, pc, qc),
        None => sweep::<4, true, false>(a, pc, &mut []),
    }
}

fn column_plain(a: &Column, pc: &mut [f64], qc: Option<&mut [f64]>) {
    match qc {
        Some(qc) => sweep::<1, false, true>(a, pc, qc),
        None => sweep::<2, false, false>(a, pc, &mut []),
    }
}

/// Rows in `W` blocks of 8 at a time (then one): `P[r] = -Σ_s X[s] M⁻¹[r, s]` and, if `Y`,
/// `Q[r] = -Σ_s Y[s] M⁻¹[r, s]`, over the listed rows s; `FMA`: fused multiply-adds.
#[inline(always)]
fn sweep<const W: usize, const FMA: bool, const Y: bool>(
    a: &Column,
    pc: &mut [f64],
    qc: &mut [f64],
) {
    let mut b = 0;
    while b + W <= a.nb {
        row_blocks::<W, FMA, Y>(a, b, pc, qc);
        b += W;
    }
    while b < a.nb {
        row_blocks::<1, FMA, Y>(a, b, pc, qc);
        b += 1;
    }
}

/// `acc + s m`, fused or not.
#[inline(always)]
fn madd<const FMA: bool>(acc: f64, s: f64, m: f64) -> f64 {
    if FMA {
        s.mul_add(m, acc)
    } else {
        acc + s * m
    }
}

/// Blocks `b..b + W` of rows.
#[inline(always)]
fn row_blocks<const W: usize, const FMA: bool, const Y: bool>(
    a: &Column,
    b: usize,
    pc: &mut [f64],
    qc: &mut [f64],
) {
    let (mut sp, mut sq) = ([[0.0; 8]; W], [[0.0; 8]; W]);
    for e in a.list {
        let m: &[[f64; 8]; W] = a.m[e.offset + b..e.offset + b + W]
            .try_into()
            .expect("blocks");
        for w in 0..W {
            for k in 0..8 {
                sp[w][k] = madd::<FMA>(sp[w][k], e.x, m[w][k]);
                if Y {
                    sq[w][k] = madd::<FMA>(sq[w][k], e.y, m[w][k]);
                }
            }
        }
    }
    for w in 0..W {
        let rows = 8 * (b + w)..a.nv.min(8 * (b + w) + 8);
        for (o, x) in pc[rows.clone()].iter_mut().zip(&sp[w]) {
            *o = -x;
        }
        if Y {
            for (o, x) in qc[rows].iter_mut().zip(&sq[w]) {
                *o = -x;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both kernels (plain, and fused on a CPU that has it) give `-M⁻¹ X` and `-M⁻¹ Y` for
    /// right-hand sides with a tree's pattern, zero columns included, on sizes around the blocks.
    #[test]
    fn sparse_products_equal_the_dense_ones() {
        for nv in [1, 5, 8, 13, 16, 23, 38] {
            // a depth-first tree of dofs: each dof's parent is on the chain of the previous one
            let mut parent = vec![usize::MAX; nv];
            for k in 1..nv {
                let mut chain = vec![k - 1];
                while parent[*chain.last().unwrap()] != usize::MAX {
                    chain.push(parent[*chain.last().unwrap()]);
                }
                parent[k] = chain[(k * 5) % chain.len()];
            }
            let inside = |mut k: usize, c: usize| loop {
                if k == c {
                    return true;
                }
                if parent[k] == usize::MAX {
                    return false;
                }
                k = parent[k];
            };
            let end: Vec<usize> = (0..nv)
                .map(|c| (c + 1..nv).find(|&k| !inside(k, c)).unwrap_or(nv))
                .collect();
            let value = |r: usize, c: usize, s: f64| {
                if inside(r, c) || inside(c, r) {
                    ((r * 13 + c * 7) % 17) as f64 * s - 1.0
                } else {
                    0.0
                }
            };
            let a = DMatrix::from_fn(nv, nv, |r, c| ((r * 3 + c * 5) % 7) as f64 * 0.1);
            let minv = &a * a.transpose() + DMatrix::identity(nv, nv);
            let mut x = DMatrix::from_fn(nv, nv, |r, c| value(r, c, 0.3));
            let mut y = DMatrix::from_fn(nv, nv, |r, c| value(r, c, -0.2));
            x.column_mut(0).fill(0.0); // one side zero
            if nv > 2 {
                y.column_mut(2).fill(0.0);
                x.column_mut(nv - 1).fill(0.0); // both sides zero
                y.column_mut(nv - 1).fill(0.0);
            }
            let (px, py) = (-&minv * &x, -&minv * &y);
            let pattern = Pattern {
                parent: &parent,
                end: &end,
            };
            let mut pad = vec![[0.0; 8]; blocks(nv) * nv];
            let mut list = vec![Entry::default(); nv];
            let (mut p, mut q) = (DMatrix::zeros(nv, nv), DMatrix::zeros(nv, nv));
            neg_minv_times(
                &minv,
                (&x, &y),
                (&mut p, &mut q),
                &pattern,
                &mut pad,
                &mut list,
            );
            let tol = 1e-12 * px.amax().max(1.0);
            assert!((&p - &px).amax().max((&q - &py).amax()) < tol, "nv {nv}");
            let mut fmas = vec![false];
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx2")
                && std::arch::is_x86_feature_detected!("fma")
            {
                fmas.push(true);
            }
            for fma in fmas {
                p.fill(9.0);
                q.fill(9.0);
                columns((&x, &y), (&mut p, &mut q), &pattern, &pad, &mut list, fma);
                let err = (&p - &px).amax().max((&q - &py).amax());
                assert!(err < tol, "nv {nv}, fma {fma}: {err:e}");
            }
        }
    }
}
