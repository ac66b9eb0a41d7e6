//! The states between the caller's rows and the lanes: row-major inputs transposed into the
//! lanes of a pack and its results transposed back out, `W x W` at a time, in 4x4 blocks of AVX
//! registers when the pack runs in the CPU's own instructions (`Io::native`), else lane by lane;
//! the full CRBA matrices from their packed triangles; the prefetch of the rows ahead; and the
//! caller's velocity order ([`Batch::with_velocity_order`](super::Batch::with_velocity_order)):
//! a chunk's input rows reordered into a buffer, its results in place.

use super::crba::packed_at;
use super::lanes::L;
use super::simd::{Algo, Io};
use crate::error::DimensionError;
use crate::multibody::Model;

/// Asks the CPU to bring rows `k..k + m` of the inputs (those that exist) into its caches, so
/// that they are there when they are checked and transposed in: a pack asks for the rows
/// [`CHUNK`](super::CHUNK) states ahead, in the chunk after its own (none with a velocity
/// order, whose kernels read a chunk's reordered copy).
#[inline(always)]
pub(super) fn prefetch_rows(io: &Io, model: &Model, k: usize, m: usize) {
    #[cfg(target_arch = "x86_64")]
    for (xs, per) in [
        (io.qs, model.nq()),
        (io.vs, model.nv()),
        (io.xs, model.nv()),
    ] {
        let rows = &xs[(k * per).min(xs.len())..((k + m) * per).min(xs.len())];
        for line in rows.chunks(8) {
            // SAFETY: a prefetch reads nothing (and `line` is in bounds).
            unsafe {
                std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(
                    line.as_ptr().cast(),
                );
            }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (io, model, k, m);
}

/// A caller's velocity order ([`Batch::with_velocity_order`](super::Batch::with_velocity_order)):
/// its entry `k` is rigid's `map[k]`, and `moved` lists the `k` with `map[k] ≠ k`. A
/// permutation maps `moved` onto itself, so only those entries of vectors and row-major
/// matrices are reordered, one by one; the others are copied as whole rows or left in place
/// (Pinocchio's layout moves 6 of `nv` per free-flyer). CRBA's packed triangle still gathers
/// every entry. The identity is no order at all (`map` empty): the batch takes its plain path.
#[derive(Clone, Debug, Default)]
pub(super) struct Order {
    pub(super) map: Vec<usize>,
    moved: Vec<usize>,
}

impl Order {
    /// The order `map`, a permutation of `0..map.len()` (the caller checked it); none if it
    /// moves nothing.
    pub(super) fn new(map: &[usize]) -> Self {
        let moved: Vec<usize> = (0..map.len()).filter(|&k| map[k] != k).collect();
        if moved.is_empty() {
            return Self::default();
        }
        Self {
            map: map.to_vec(),
            moved,
        }
    }

    /// Rigid's own order: nothing to reorder.
    pub(super) fn is_empty(&self) -> bool {
        self.map.is_empty()
    }

    /// Whether this order is one of `nv` velocities (rigid's own fits any model).
    pub(super) fn fits(&self, nv: usize) -> Result<(), DimensionError> {
        if self.is_empty() {
            return Ok(());
        }
        DimensionError::check("order", nv, self.map.len())
    }
}

/// Rows of `nv = order.map.len()` velocity-space numbers from the caller's order into rigid's
/// (`dst`, as long as `src`): rigid's entry `map[k]` of a row is the caller's `k`. The rows are
/// copied whole, then the moved entries put in place.
pub(super) fn rows_in_order(src: &[f64], order: &Order, dst: &mut [f64]) {
    let nv = order.map.len();
    dst.copy_from_slice(src);
    for (s, d) in src.chunks_exact(nv).zip(dst.chunks_exact_mut(nv)) {
        for &k in &order.moved {
            d[order.map[k]] = s[k];
        }
    }
}

/// One state's result of `algo` (`y`, rigid's order) in the caller's order, in place: a vector
/// `y_k ← y_map[k]` (RNEA, ABA), a matrix `Y_rc ← Y_map[r],map[c]` (row-major `nv x nv`:
/// CRBA, the derivatives; or the packed lower triangle), through `tmp` (`y.len()` numbers).
/// Vectors and row-major matrices read and write only the moved entries: a moved row whole
/// (copied from its source row, then its moved columns), an unmoved row's moved columns.
pub(super) fn order_out(algo: Algo, y: &mut [f64], order: &Order, tmp: &mut [f64]) {
    let (map, moved, n) = (&order.map, &order.moved, order.map.len());
    let tmp = &mut tmp[..y.len()];
    match algo {
        Algo::Rnea | Algo::Aba => {
            for &k in moved {
                tmp[k] = y[k];
            }
            for &k in moved {
                y[k] = tmp[map[k]];
            }
        }
        Algo::CrbaLower => {
            tmp.copy_from_slice(y);
            for c in 0..n {
                for r in c..n {
                    let (a, b) = (map[r].max(map[c]), map[r].min(map[c]));
                    y[packed_at(n, r, c)] = tmp[packed_at(n, a, b)];
                }
            }
        }
        Algo::Crba | Algo::RneaDerivatives => {
            // the sources: the moved rows whole, the moved columns of the others
            for (r, (row, saved)) in y.chunks_exact(n).zip(tmp.chunks_exact_mut(n)).enumerate() {
                if map[r] == r {
                    for &k in moved {
                        saved[k] = row[k];
                    }
                } else {
                    saved.copy_from_slice(row);
                }
            }
            for (r, row) in y.chunks_exact_mut(n).enumerate() {
                let from = &tmp[map[r] * n..][..n];
                if map[r] != r {
                    row.copy_from_slice(from);
                }
                for &k in moved {
                    row[k] = from[map[k]];
                }
            }
        }
    }
}

/// Lanes `0..m` of `src` (one lane vector per output index) into `m` rows of `dst`, `stride`
/// apart (row `l`, lane `l`'s numbers, is `dst[l stride..][..src.len()]`): `W x W` blocks,
/// then the remainder one by one. With `native` (the pack runs in the CPU's instructions for
/// its width: AVX2 for 4 lanes, AVX-512F for 8), a block is transposed in registers as 4x4
/// blocks of AVX ([`transpose4`]: one for 4 lanes, two or four for 8, as the pack is filled);
/// otherwise by the generic loop, which the compiler makes scalar moves through the stack.
/// (An 8x8 transposition in AVX-512's shuffles, 24 instead of 32 per 64 numbers, was slower on
/// a Zen 5: 0.87–0.98 of the quarters' states/s for CRBA on UR5, Panda, Solo-12 and TALOS, 7
/// interleaved rounds; BENCHMARKS.md.)
#[inline(always)]
pub(super) fn transpose_out<const W: usize>(
    src: &[L<W>],
    m: usize,
    dst: &mut [f64],
    stride: usize,
    native: bool,
) {
    let per = src.len();
    let full = per / W * W;
    assert!(
        m <= W && per <= stride && (m == 0 || dst.len() >= (m - 1) * stride + per),
        "transpose_out: {m} rows of {per}, {stride} apart, into {}",
        dst.len()
    );
    #[cfg(target_arch = "x86_64")]
    if native && (W == 4 || W == 8) {
        let (lanes, out) = (src.as_ptr().cast::<f64>(), dst.as_mut_ptr());
        for b in (0..full).step_by(W) {
            // the W x W block as 4 x 4 quarters: lanes h..h + 4 of entries b + e..b + e + 4
            for h in (0..m).step_by(4) {
                for e in (0..W).step_by(4) {
                    // SAFETY: `src[b + e..b + e + 4]` are four rows of `W ≥ h + 4` `f64`; row
                    // `h + l < m` of `dst` starts at `(h + l) stride` and holds `per ≥ b + e + 4`
                    // numbers, `(m − 1) stride + per ≤ dst.len()` (asserted above); `src` and
                    // `dst` are borrowed apart, so they do not overlap; with `native`, the CPU
                    // has AVX (AVX2 for 4 lanes, AVX-512F for 8).
                    unsafe {
                        let (from, to) = (lanes.add(W * (b + e) + h), out.add(h * stride + b + e));
                        transpose4(from, W, to, stride, (m - h).min(4));
                    }
                }
            }
        }
    } else {
        transpose_blocks(src, m, dst, stride);
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        let _ = native;
        transpose_blocks(src, m, dst, stride);
    }
    for (t, x) in src.iter().enumerate().skip(full) {
        for l in 0..m {
            dst[l * stride + t] = x.0[l];
        }
    }
}

/// Rows `k..k + W` of the row-major `src` (`dst.len()` numbers each) into the lanes of `dst`:
/// lane `l` of entry `t` is `src[(k + l) per + t]`, the inverse of [`transpose_out`] for a full
/// pack, in 4x4 blocks in registers ([`transpose4`]), then the last `per mod 4` entries one by
/// one. Only for a pack in the CPU's own instructions (`Io::native`) of 4 or 8 lanes (the
/// generic path, and a task's last pack when it is not full, go lane by lane through
/// [`Pack::gather`](super::pack::Pack::gather)). Panics if `src` holds fewer than
/// `(k + W) per` numbers.
///
/// # Safety
/// On x86-64 the CPU has AVX (the blocks are [`transpose4`]'s).
#[inline(always)]
pub(super) unsafe fn transpose_in<const W: usize>(src: &[f64], k: usize, dst: &mut [L<W>]) {
    let per = dst.len();
    let rows = &src[k * per..(k + W) * per];
    let full = per / 4 * 4;
    #[cfg(target_arch = "x86_64")]
    {
        assert!(W == 4 || W == 8, "transpose_in: {W} lanes");
        let (from, to) = (rows.as_ptr(), dst.as_mut_ptr().cast::<f64>());
        for e in (0..full).step_by(4) {
            for h in (0..W).step_by(4) {
                // SAFETY: rows h..h + 4 (< W) of `rows` hold entries e..e + 4 (≤ per), `per`
                // apart; entries e..e + 4 of `dst` hold lanes h..h + 4, W apart; `rows` and
                // `dst` are borrowed apart; the CPU has AVX (the caller's promise).
                unsafe { transpose4(from.add(h * per + e), per, to.add(e * W + h), W, 4) };
            }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let full = 0;
    for (t, y) in dst.iter_mut().enumerate().skip(full) {
        for (l, x) in y.0.iter_mut().enumerate() {
            *x = rows[l * per + t];
        }
    }
}

/// The `W x W` blocks of [`transpose_out`], lane by lane.
#[inline(always)]
fn transpose_blocks<const W: usize>(src: &[L<W>], m: usize, dst: &mut [f64], stride: usize) {
    let per = src.len();
    for b in (0..per / W * W).step_by(W) {
        let mut block = [[0.0; W]; W];
        for (t, x) in src[b..b + W].iter().enumerate() {
            for (l, row) in block.iter_mut().enumerate() {
                row[t] = x.0[l];
            }
        }
        for (l, row) in block[..m].iter().enumerate() {
            dst[l * stride + b..][..W].copy_from_slice(row);
        }
    }
}

/// The 4x4 block at `src` (four rows of four, `src_stride` apart) transposed into the first `m`
/// rows at `dst`, `stride` apart: `unpacklo/hi` pair the rows' even and odd entries within each
/// 128-bit half, `permute2f128` joins the halves.
///
/// # Safety
/// `src + k src_stride` points to four readable `f64` for `k < 4`, `dst + l stride` to four
/// writable `f64` for `l < m ≤ 4`, the two blocks do not overlap, and the CPU has AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
unsafe fn transpose4(src: *const f64, src_stride: usize, dst: *mut f64, stride: usize, m: usize) {
    // SAFETY: the caller's promise.
    unsafe {
        transpose4_from(
            [0, 1, 2, 3].map(|k| src.add(k * src_stride)),
            dst,
            stride,
            m,
        )
    }
}

/// [`transpose4`] from four rows anywhere: row `k` of the block is the four `f64` at `src[k]`.
///
/// # Safety
/// Each `src[k]` points to four readable `f64`, `dst + l stride` to four writable `f64` for
/// `l < m ≤ 4`, the rows read and written do not overlap, and the CPU has AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
unsafe fn transpose4_from(src: [*const f64; 4], dst: *mut f64, stride: usize, m: usize) {
    use std::arch::x86_64::{
        _mm256_loadu_pd, _mm256_permute2f128_pd, _mm256_storeu_pd, _mm256_unpackhi_pd,
        _mm256_unpacklo_pd,
    };
    // SAFETY: the caller's promise.
    unsafe {
        let [a, b, c, d] = src.map(|row| _mm256_loadu_pd(row));
        let (t0, t1) = (_mm256_unpacklo_pd(a, b), _mm256_unpackhi_pd(a, b));
        let (t2, t3) = (_mm256_unpacklo_pd(c, d), _mm256_unpackhi_pd(c, d));
        let rows = [
            _mm256_permute2f128_pd(t0, t2, 0x20),
            _mm256_permute2f128_pd(t1, t3, 0x20),
            _mm256_permute2f128_pd(t0, t2, 0x31),
            _mm256_permute2f128_pd(t1, t3, 0x31),
        ];
        // every pack but a task's last is full: four stores with no count to test
        if m == 4 {
            for (l, r) in rows.into_iter().enumerate() {
                _mm256_storeu_pd(dst.add(l * stride), r);
            }
        } else {
            for (l, r) in rows.into_iter().take(m).enumerate() {
                _mm256_storeu_pd(dst.add(l * stride), r);
            }
        }
    }
}

/// Where each entry of a symmetric `nv x nv` matrix is in its lower triangle packed by columns:
/// entry `(r, c)` of the row-major matrix is `packed_at(nv, max(r, c), min(r, c))`, made with
/// each [`Pack`](super::pack::Pack) for [`symmetric_out`], which reads them four at a time
/// (computed there, they were 4.6 % of a TALOS profile; with the table 0.99–1.07x the states/s
/// on UR5, Panda, Solo-12 and TALOS, 3 interleaved rounds). The entries that the tree makes zero
/// (row `r` of column `c` at or past the end of `c`'s subtree, which CRBA never writes) are all
/// read from the first of them, one line of the cache that stays near, instead of each from its
/// own place in the triangle: on TALOS (nv 38) 784 of the 1444 reads of a full matrix, and the
/// triangle (47 KB in 8 lanes) does not fit in L1. Its fields are private and [`Mirror::new`]
/// is its only maker, so every entry is below `nv (nv + 1) / 2`.
#[derive(Clone, Debug)]
pub(crate) struct Mirror {
    nv: usize,
    at: Vec<u32>,
}

impl Mirror {
    /// The table for `nv x nv` matrices whose column `c` is zero from row `ends[c]` on
    /// (`nv = ends.len()`; an end is clamped to `c + 1..=nv`).
    pub(crate) fn new(ends: &[usize]) -> Self {
        let nv = ends.len();
        let ends: Vec<usize> = ends
            .iter()
            .enumerate()
            .map(|(c, &e)| e.clamp(c + 1, nv))
            .collect();
        let zero = (0..nv).find_map(|c| (ends[c] < nv).then(|| packed_at(nv, ends[c], c)));
        let index = |k: usize| {
            let (r, c) = (k / nv, k % nv);
            let (hi, lo) = (r.max(c), r.min(c));
            let e = match zero {
                Some(z) if hi >= ends[lo] => z,
                _ => packed_at(nv, hi, lo),
            };
            u32::try_from(e)
                .expect("a packed triangle of fewer than 2³² entries (the pack's `M` holds them)")
        };
        Self {
            nv,
            at: (0..nv * nv).map(index).collect(),
        }
    }

    /// The table of `model`'s mass matrices: column `k` ends where the subtree of `k`'s joint
    /// does.
    pub(crate) fn of(model: &Model) -> Self {
        let plan = model.plan();
        let ends: Vec<usize> = (0..model.nv())
            .map(|k| plan.subtree_end_v[plan.dof_joint[k]])
            .collect();
        Self::new(&ends)
    }
}

/// Lanes `0..m` of `packed` (one lane vector per entry of an `nv x nv` symmetric matrix's lower
/// triangle, packed by columns: [`packed_at`]) into `m` full row-major matrices, one after the
/// other in `dst` (`nv²` numbers each): entry `(r, c)` of matrix `l` is lane `l` of
/// `packed[packed_at(nv, max(r, c), min(r, c))]`, found in `mirror`. With `native` (as in
/// [`transpose_out`]) and `nv ≥ 4`, each row's columns go four at a time, 4x4 blocks of lanes
/// and columns transposed in registers from four entries of the triangle ([`transpose4_from`];
/// a row's last four columns overlap the block before when `nv` is not a multiple of 4, writing
/// its numbers again); otherwise one by one. One pass, no mirroring after. As for
/// [`transpose_out`], `native` is the caller's word that the CPU has AVX.
#[inline(always)]
pub(super) fn symmetric_out<const W: usize>(
    packed: &[L<W>],
    mirror: &Mirror,
    m: usize,
    dst: &mut [f64],
    native: bool,
) {
    let nv = mirror.nv;
    let per = nv * nv;
    assert!(
        m <= W && packed.len() == nv * (nv + 1) / 2 && dst.len() >= m * per,
        "symmetric_out: {m} matrices of {nv} x {nv} from {} entries into {}",
        packed.len(),
        dst.len()
    );
    #[cfg(target_arch = "x86_64")]
    if native && (W == 4 || W == 8) && nv >= 4 {
        let (lanes, out) = (packed.as_ptr().cast::<f64>(), dst.as_mut_ptr());
        for (r, row) in mirror.at.chunks_exact(nv).enumerate() {
            for c in (0..nv).step_by(4).map(|c| c.min(nv - 4)) {
                let e = &row[c..c + 4];
                let entries = [e[0], e[1], e[2], e[3]].map(|e| e as usize);
                for h in (0..m).step_by(4) {
                    // SAFETY: each entry `< packed.len()` (`Mirror::new`, the only maker of a
                    // `Mirror`, stores `packed_at` of an `(r, c)` with `r ≥ c`, both `< nv`;
                    // `packed.len()` asserted above) is `W ≥ h + 4` lanes; matrix `h + l < m`
                    // holds `(r, c..c + 4)` at `(h + l) per + r nv + c`, `c + 4 ≤ nv`, in
                    // `dst.len() ≥ m per` (asserted above); `packed` and `dst` are borrowed
                    // apart; with `native`, the CPU has AVX (AVX2 for 4 lanes, AVX-512F for 8).
                    unsafe {
                        let from = entries.map(|e| lanes.add(W * e + h));
                        transpose4_from(from, out.add(h * per + r * nv + c), per, (m - h).min(4));
                    }
                }
            }
        }
        return;
    }
    let _ = native;
    if nv == 0 {
        return;
    }
    for (l, matrix) in dst.chunks_exact_mut(per).take(m).enumerate() {
        for (y, &e) in matrix.iter_mut().zip(&mirror.at) {
            *y = packed[e as usize].0[l];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{packed_at, symmetric_out, transpose_out, Mirror, L};

    /// `transpose_out` of `W` lanes, in registers (when the CPU has AVX) and in the generic loop:
    /// lane `l` of entry `t` lands at `dst[l stride + t]` for every `l < m`, for pack fillings
    /// `m = 0..=W` and lengths that leave every remainder, and nothing else of `dst` is written.
    fn transposes<const W: usize>(native: bool) {
        for per in 0..=21 {
            let src: Vec<L<W>> = (0..per)
                .map(|t| L(std::array::from_fn(|l| (100 * t + l) as f64)))
                .collect();
            for m in 0..=W {
                let stride = per + 3;
                let mut dst = vec![f64::NAN; W * stride];
                transpose_out(&src, m, &mut dst, stride, native);
                for (k, y) in dst.iter().enumerate() {
                    let (l, t) = (k / stride, k % stride);
                    if l < m && t < per {
                        assert_eq!(*y, (100 * t + l) as f64, "W {W}, per {per}, m {m}, [{k}]");
                    } else {
                        assert!(y.is_nan(), "W {W}, per {per}, m {m}: [{k}] written");
                    }
                }
            }
        }
    }

    /// `transpose_in` of `W` lanes (4 and 8, in registers): lane `l` of entry `t` is row
    /// `k + l`'s entry `t`, for lengths that leave every remainder and a first row `k` past 0
    /// (with rows after the pack, so that a wrong offset reads a wrong number).
    #[cfg(target_arch = "x86_64")]
    fn transposes_in<const W: usize>() {
        for per in 1..=21 {
            let k = 3;
            let src: Vec<f64> = (0..(k + W + 2) * per).map(|i| i as f64).collect();
            let mut dst = vec![L([f64::NAN; W]); per];
            // SAFETY: the caller checked that the CPU has AVX.
            unsafe { super::transpose_in(&src, k, &mut dst) };
            for (t, y) in dst.iter().enumerate() {
                for (l, x) in y.0.iter().enumerate() {
                    assert_eq!(
                        *x,
                        ((k + l) * per + t) as f64,
                        "W {W}, per {per}, lane {l}, {t}"
                    );
                }
            }
        }
    }

    #[test]
    #[cfg(target_arch = "x86_64")]
    fn transpose_in_puts_each_row_in_its_lane() {
        if std::arch::is_x86_feature_detected!("avx") {
            transposes_in::<4>();
            transposes_in::<8>();
        }
    }

    /// The paths a test can take on this CPU: the generic one, and the registers' with AVX.
    fn natives() -> Vec<bool> {
        #[cfg(target_arch = "x86_64")]
        let avx = std::arch::is_x86_feature_detected!("avx");
        #[cfg(not(target_arch = "x86_64"))]
        let avx = false;
        if avx {
            vec![false, true]
        } else {
            vec![false]
        }
    }

    #[test]
    fn transpose_out_puts_each_lane_in_its_row() {
        transposes::<2>(false);
        for native in natives() {
            transposes::<4>(native);
            transposes::<8>(native);
        }
    }

    /// `symmetric_out` of `W` lanes: matrix `l`'s entry `(r, c)` is lane `l` of the packed
    /// triangle's `(max, min)`, for sizes below, at and past the blocks of four (and every
    /// remainder), every pack filling, and nothing written past the `m` matrices.
    fn symmetric<const W: usize>(native: bool) {
        for nv in 0..=9 {
            let packed: Vec<L<W>> = (0..nv * (nv + 1) / 2)
                .map(|e| L(std::array::from_fn(|l| (100 * e + l) as f64)))
                .collect();
            for m in 0..=W {
                let mut dst = vec![f64::NAN; W * nv * nv + 2];
                symmetric_out(&packed, &Mirror::new(&vec![nv; nv]), m, &mut dst, native);
                for (k, y) in dst.iter().enumerate() {
                    let (l, r, c) = (
                        k / (nv * nv).max(1),
                        k / nv.max(1) % nv.max(1),
                        k % nv.max(1),
                    );
                    if l < m && nv > 0 {
                        let e = packed_at(nv, r.max(c), r.min(c));
                        assert_eq!(*y, (100 * e + l) as f64, "W {W}, nv {nv}, m {m}, [{k}]");
                    } else {
                        assert!(y.is_nan(), "W {W}, nv {nv}, m {m}: [{k}] written");
                    }
                }
            }
        }
    }

    /// `symmetric_out` with a tree's zeros (column `c` non-zero down to row `ends[c]`): the
    /// zeros come out zero, read from one entry, and every other entry from its own place.
    fn symmetric_with_zeros<const W: usize>(native: bool) {
        for nv in 1..=13 {
            let ends: Vec<usize> = (0..nv).map(|c| (c + 1 + (c * 7) % 4).min(nv)).collect();
            let nonzero = |r: usize, c: usize| r.max(c) < ends[r.min(c)];
            let packed: Vec<L<W>> = (0..nv * (nv + 1) / 2)
                .map(|e| {
                    // column `c` and row `r` of entry `e`
                    let c = (0..nv).rfind(|&c| packed_at(nv, c, c) <= e).unwrap();
                    let r = c + e - packed_at(nv, c, c);
                    let x = |l: usize| {
                        if nonzero(r, c) {
                            (100 * e + l + 1) as f64
                        } else {
                            0.0
                        }
                    };
                    L(std::array::from_fn(x))
                })
                .collect();
            let mirror = Mirror::new(&ends);
            for m in 0..=W {
                let mut dst = vec![f64::NAN; W * nv * nv];
                symmetric_out(&packed, &mirror, m, &mut dst, native);
                for (k, y) in dst.iter().enumerate() {
                    let (l, r, c) = (k / (nv * nv), k / nv % nv, k % nv);
                    if l >= m {
                        assert!(y.is_nan(), "W {W}, nv {nv}, m {m}: [{k}] written");
                    } else if nonzero(r, c) {
                        let e = packed_at(nv, r.max(c), r.min(c));
                        assert_eq!(*y, (100 * e + l + 1) as f64, "W {W}, nv {nv}, m {m}, [{k}]");
                    } else {
                        assert_eq!(*y, 0.0, "W {W}, nv {nv}, m {m}, [{k}] ({r}, {c})");
                    }
                }
            }
            // the zeros are all read from one entry
            let at: std::collections::BTreeSet<u32> = (0..nv * nv)
                .filter(|&k| !nonzero(k / nv, k % nv))
                .map(|k| mirror.at[k])
                .collect();
            assert!(at.len() <= 1, "nv {nv}: zeros read from {at:?}");
        }
    }

    #[test]
    fn symmetric_out_reads_a_trees_zeros_from_one_entry() {
        symmetric_with_zeros::<2>(false);
        for native in natives() {
            symmetric_with_zeros::<4>(native);
            symmetric_with_zeros::<8>(native);
        }
    }

    #[test]
    fn symmetric_out_mirrors_each_lane_into_its_matrix() {
        for native in natives() {
            symmetric::<2>(native);
            symmetric::<4>(native);
            symmetric::<8>(native);
        }
    }
}
