//! `(P, Q) = (-M⁻¹ X, -M⁻¹ Y)` for the derivatives of forward dynamics, skipping the zeros of
//! `X` and `Y`.
//!
//! Columns `c` of `∂τ/∂q` and `∂τ/∂v` are non-zero only on the dofs of `c`'s ancestors (the
//! chain `λ(c), λ(λ(c)), …`) and of its subtree (`c..end[c]`, contiguous in depth-first order),
//! so column `c` of each product is a sum of those columns of `M⁻¹` (symmetric: columns are
//! rows). The two products share the pattern, so each block of `M⁻¹` read serves both. `M⁻¹` is
//! first copied into blocks of 8 rows, its columns padded with zeros, so that every block is
//! full width; the sums over a block are accumulated in registers. On x86-64 the same code is also
//! compiled for AVX and chosen at run time; both builds do the same operations in the same order
//! (no fused multiply-add), so their results are identical.

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

/// `P = -M⁻¹ X`, `Q = -M⁻¹ Y`; `pad` (`blocks(nv) nv` blocks) holds the padded copy of `M⁻¹`.
pub(crate) fn neg_minv_times(
    minv: &DMatrix<f64>,
    (x, y): (&DMatrix<f64>, &DMatrix<f64>),
    (p, q): (&mut DMatrix<f64>, &mut DMatrix<f64>),
    pattern: &Pattern,
    pad: &mut [[f64; 8]],
) {
    let nv = minv.nrows();
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
    let args = Args {
        m: pad,
        nb,
        nv,
        x: x.as_slice(),
        y: y.as_slice(),
        pattern,
    };
    let (p, q) = (p.as_mut_slice(), q.as_mut_slice());
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx") {
        // SAFETY: the CPU supports AVX, checked just above.
        unsafe { kernel_avx(&args, p, q) };
        return;
    }
    kernel(&args, p, q);
}

struct Args<'a> {
    m: &'a [[f64; 8]],
    nb: usize,
    nv: usize,
    x: &'a [f64],
    y: &'a [f64],
    pattern: &'a Pattern<'a>,
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
fn kernel_avx(a: &Args, p: &mut [f64], q: &mut [f64]) {
    kernel(a, p, q);
}

/// Column by column, rows in blocks of 8: `P[r0 + t, c] = -Σ_r X[r, c] M⁻¹[r0 + t, r]`, likewise
/// `Q`, over the non-zero rows r of column c.
#[inline(always)]
fn kernel(a: &Args, p: &mut [f64], q: &mut [f64]) {
    let nv = a.nv;
    for (c, (pc, qc)) in p
        .chunks_exact_mut(nv)
        .zip(q.chunks_exact_mut(nv))
        .enumerate()
    {
        let (xc, yc) = (&a.x[c * nv..(c + 1) * nv], &a.y[c * nv..(c + 1) * nv]);
        for b in 0..a.nb {
            let (mut sp, mut sq) = ([0.0; 8], [0.0; 8]);
            for r in c..a.pattern.end[c] {
                add(&a.m[r * a.nb + b], (xc[r], yc[r]), &mut sp, &mut sq);
            }
            let mut r = a.pattern.parent[c];
            while r != usize::MAX {
                add(&a.m[r * a.nb + b], (xc[r], yc[r]), &mut sp, &mut sq);
                r = a.pattern.parent[r];
            }
            let rows = 8 * b..nv.min(8 * b + 8);
            for (k, r) in rows.enumerate() {
                pc[r] = -sp[k];
                qc[r] = -sq[k];
            }
        }
    }
}

/// `sp += s m`, `sq += t m` for a block `m` of 8 rows of a column of `M⁻¹`.
#[inline(always)]
fn add(m: &[f64; 8], (s, t): (f64, f64), sp: &mut [f64; 8], sq: &mut [f64; 8]) {
    for k in 0..8 {
        sp[k] += s * m[k];
        sq[k] += t * m[k];
    }
}
