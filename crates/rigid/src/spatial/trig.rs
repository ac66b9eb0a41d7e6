//! `sin q` and `cos q` together, for joint angles: about twice as fast as the C library's
//! `sincos` on the revolute joints' hot path, and within one unit in the last place of it.
//!
//! Method (fdlibm, Sun Microsystems 1993, as in musl's `__rem_pio2`, `__sin` and `__cos`):
//! `n = round(2q/π)`, `r = q - n π/2` by a three-part Cody-Waite split of `π/2` (each
//! `n · pio2_k` exact for `|n| < 2²⁰`), then the minimax polynomials of `sin r` and `cos r` on
//! `|r| ≤ π/4`, and the quadrant `n mod 4` picks and signs them. Angles beyond `|q| ≤ 10⁵`
//! (and NaN) go to the standard library. The constants are fdlibm's, bit for bit.

/// Leading 33 bits of `π/2`.
const PIO2_1: f64 = f64::from_bits(0x3FF9_21FB_5440_0000); // 1.57079632673412561417e+00
/// Next 33 bits of `π/2`.
const PIO2_2: f64 = f64::from_bits(0x3DD0_B461_1A60_0000); // 6.07710050630396597660e-11
/// `π/2 - PIO2_1 - PIO2_2`.
const PIO2_2T: f64 = f64::from_bits(0x3BA3_198A_2E03_7073); // 2.02226624879595063154e-21
const S1: f64 = f64::from_bits(0xBFC5_5555_5555_5549); // -1.66666666666666324348e-01
const S2: f64 = f64::from_bits(0x3F81_1111_1110_F8A6); // 8.33333333332248946124e-03
const S3: f64 = f64::from_bits(0xBF2A_01A0_19C1_61D5); // -1.98412698298579493134e-04
const S4: f64 = f64::from_bits(0x3EC7_1DE3_57B1_FE7D); // 2.75573137070700676789e-06
const S5: f64 = f64::from_bits(0xBE5A_E5E6_8A2B_9CEB); // -2.50507602534068634195e-08
const S6: f64 = f64::from_bits(0x3DE5_D93A_5ACF_D57C); // 1.58969099521155010221e-10
const C1: f64 = f64::from_bits(0x3FA5_5555_5555_554C); // 4.16666666666666019037e-02
const C2: f64 = f64::from_bits(0xBF56_C16C_16C1_5177); // -1.38888888888741095749e-03
const C3: f64 = f64::from_bits(0x3EFA_01A0_19CB_1590); // 2.48015872894767294178e-05
const C4: f64 = f64::from_bits(0xBE92_7E4F_809C_52AD); // -2.75573143513906633035e-07
const C5: f64 = f64::from_bits(0x3E21_EE9E_BDB4_B1C4); // 2.08757232129817482790e-09
const C6: f64 = f64::from_bits(0xBDA8_FAE9_BE88_38D4); // -1.13596475577881948265e-11

/// `(sin q, cos q)`.
#[inline]
#[must_use]
pub(crate) fn sin_cos(q: f64) -> (f64, f64) {
    // NaN, infinities and |q| ≥ 10⁵ go to the C library
    if q.abs().partial_cmp(&1e5) != Some(std::cmp::Ordering::Less) {
        return q.sin_cos();
    }
    // round to nearest by the 1.5·2⁵² trick (`f64::round` is a libm call without SSE4.1)
    const ROUND: f64 = 6_755_399_441_055_744.0;
    let n = (q * std::f64::consts::FRAC_2_PI + ROUND) - ROUND;
    let r = ((q - n * PIO2_1) - n * PIO2_2) - n * PIO2_2T;
    let z = r * r;
    let s = r + r * z * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    let c =
        w + (((1.0 - w) - hz) + z * z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6))))));
    match (n as i64) & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// [`sin_cos`] of `W` angles side by side, one per lane, for the batch kernels
/// ([`multibody::batch`](crate::multibody::batch)): the same operations in each lane (the
/// quadrant picked by comparisons, or by its integer bits in AVX-512, instead of a `match`), so
/// the results are [`sin_cos`]'s bit for bit; lanes with `|q| ≥ 10⁵` or NaN are redone by the
/// standard library, as there.
///
/// Eight lanes on a CPU with AVX-512F run in its intrinsics ([`avx512::sin_cos_8`]): the
/// compiler split the portable loops below into 4-, 2- and 1-lane pieces for 8 lanes, where the
/// batch RNEA spent a fifth of its time on TALOS (BENCHMARKS.md). Four lanes keep the portable
/// loops, which the compiler makes AVX2 as they are: `avx2::sin_cos_4` in their place left the
/// 4-lane RNEA 0.87–0.90 of its states per second on a Zen 5.
#[inline(always)]
#[must_use]
#[allow(clippy::manual_range_contains)] // two comparisons per lane, which vectorise
pub(crate) fn sin_cos_lanes<const W: usize>(q: [f64; W]) -> ([f64; W], [f64; W]) {
    #[cfg(target_arch = "x86_64")]
    if W == 8 && std::arch::is_x86_feature_detected!("avx512f") {
        // SAFETY: the CPU has AVX-512F (checked above).
        if let Some((s, c)) = unsafe { avx512::sin_cos_8(std::array::from_fn(|i| q[i])) } {
            return (std::array::from_fn(|i| s[i]), std::array::from_fn(|i| c[i]));
        }
    }
    const ROUND: f64 = 6_755_399_441_055_744.0;
    // each step a loop over the lanes, which the compiler makes one vector instruction
    #[inline(always)]
    fn map<const W: usize>(x: [f64; W], f: impl Fn(f64) -> f64) -> [f64; W] {
        let mut r = x;
        for v in &mut r {
            *v = f(*v);
        }
        r
    }
    #[inline(always)]
    fn zip<const W: usize>(x: [f64; W], y: [f64; W], f: impl Fn(f64, f64) -> f64) -> [f64; W] {
        let mut r = x;
        for (v, y) in r.iter_mut().zip(y) {
            *v = f(*v, y);
        }
        r
    }
    let n = map(q, |x| (x * std::f64::consts::FRAC_2_PI + ROUND) - ROUND);
    let r = zip(q, n, |x, n| ((x - n * PIO2_1) - n * PIO2_2) - n * PIO2_2T);
    let z = map(r, |r| r * r);
    let sp = map(z, |z| {
        S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6))))
    });
    let s = zip(zip(r, z, |r, z| r * z), sp, |rz, p| rz * p);
    let s = zip(r, s, |r, s| r + s);
    let cp = map(z, |z| {
        C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6))))
    });
    let c = zip(z, cp, |z, p| {
        let hz = 0.5 * z;
        let w = 1.0 - hz;
        w + (((1.0 - w) - hz) + z * z * p)
    });
    // the quadrant n mod 4 as -2..=2 (exact: n is an integer below 2²⁰), picked and signed by
    // comparisons, which the lanes do together (0: (s, c); ±1: (c, -s) / (-c, s); ±2: (-s, -c))
    let quadrant = map(n, |n| n - 4.0 * ((n * 0.25 + ROUND) - ROUND));
    let (mut sin, mut cos) = (s, c);
    for i in 0..W {
        let k = quadrant[i];
        let (a, b) = if k * k == 1.0 {
            (c[i], s[i])
        } else {
            (s[i], c[i])
        };
        sin[i] = if k < -0.5 || k > 1.5 { -a } else { a };
        cos[i] = if k > 0.5 || k < -1.5 { -b } else { b };
    }
    // the lanes out of the reduction's range, apart (a branch per lane here would keep the
    // compiler from computing the lanes together)
    let mut inside = true;
    for x in q {
        inside &= x.abs() < 1e5;
    }
    if !inside {
        library_lanes(&q, &mut sin, &mut cos);
    }
    (sin, cos)
}

/// [`sin_cos_lanes`]' lanes with `|q| ≥ 10⁵` or NaN, by the standard library.
#[cold]
#[inline(never)]
fn library_lanes(q: &[f64], sin: &mut [f64], cos: &mut [f64]) {
    for ((q, s), c) in q.iter().zip(sin).zip(cos) {
        if q.abs().partial_cmp(&1e5) != Some(std::cmp::Ordering::Less) {
            (*s, *c) = q.sin_cos();
        }
    }
}

/// `out[k] = [sin q_k, cos q_k]` for the entries `k` of `q` listed in `at`, several at a time in
/// the lanes of a vector register: four in AVX2 where the CPU has it (detected at run time, as
/// glibc picks its own `sincos`), else two in SSE2 (the x86-64 baseline). The lanes do the same
/// operations as [`sin_cos`] (no fused multiply-add), so the results are the same bit for bit.
/// Computed ahead of a chain of rotations, the joints' sines and cosines are off its critical
/// path, and each group costs about what one angle does alone.
#[inline]
pub(crate) fn sin_cos_at(q: &[f64], at: &[usize], out: &mut [[f64; 2]]) {
    #[cfg(target_arch = "x86_64")]
    if at.len() >= 4 && std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the CPU has AVX2 (checked above).
        unsafe { avx2::sin_cos_at(q, at, out) };
        return;
    }
    sin_cos_pairs(q, at, out);
}

/// [`sin_cos_at`] two at a time (SSE2), then the odd one alone.
#[inline(always)]
fn sin_cos_pairs(q: &[f64], at: &[usize], out: &mut [[f64; 2]]) {
    let mut pairs = at.chunks_exact(2);
    for k in pairs.by_ref() {
        let (s, c) = sin_cos_2([q[k[0]], q[k[1]]]);
        out[k[0]] = [s[0], c[0]];
        out[k[1]] = [s[1], c[1]];
    }
    for &k in pairs.remainder() {
        let (s, c) = sin_cos(q[k]);
        out[k] = [s, c];
    }
}

/// [`sin_cos`] of two angles at once.
#[inline(always)]
fn sin_cos_2(q: [f64; 2]) -> ([f64; 2], [f64; 2]) {
    #[cfg(target_arch = "x86_64")]
    if q[0].abs() < 1e5 && q[1].abs() < 1e5 {
        // SAFETY: SSE2 is part of the x86-64 baseline: every x86-64 CPU has it.
        return unsafe { sse2::sin_cos_2(q) };
    }
    let ((s0, c0), (s1, c1)) = (sin_cos(q[0]), sin_cos(q[1]));
    ([s0, s1], [c0, c1])
}

#[cfg(target_arch = "x86_64")]
mod sse2 {
    //! SSE2 is part of the x86-64 baseline, so these functions can always be called.
    use super::{C1, C2, C3, C4, C5, C6, PIO2_1, PIO2_2, PIO2_2T, S1, S2, S3, S4, S5, S6};
    use std::arch::x86_64::{
        __m128d, _mm_add_epi64, _mm_add_pd, _mm_and_pd, _mm_and_si128, _mm_andnot_pd,
        _mm_castsi128_pd, _mm_cmpeq_epi32, _mm_cvtpd_epi32, _mm_cvtsd_f64, _mm_mul_pd, _mm_or_pd,
        _mm_set1_epi32, _mm_set1_epi64x, _mm_set1_pd, _mm_set_pd, _mm_slli_epi64, _mm_sub_pd,
        _mm_unpackhi_pd, _mm_unpacklo_epi32, _mm_xor_pd,
    };

    #[inline]
    #[target_feature(enable = "sse2")]
    fn k(x: f64) -> __m128d {
        _mm_set1_pd(x)
    }

    /// Both lanes with `|q| < 10⁵` (checked by the caller).
    #[inline]
    #[target_feature(enable = "sse2")]
    pub(super) fn sin_cos_2(q: [f64; 2]) -> ([f64; 2], [f64; 2]) {
        const ROUND: f64 = 6_755_399_441_055_744.0;
        let x = _mm_set_pd(q[1], q[0]);
        let n = _mm_sub_pd(
            _mm_add_pd(_mm_mul_pd(x, k(std::f64::consts::FRAC_2_PI)), k(ROUND)),
            k(ROUND),
        );
        let r = _mm_sub_pd(
            _mm_sub_pd(
                _mm_sub_pd(x, _mm_mul_pd(n, k(PIO2_1))),
                _mm_mul_pd(n, k(PIO2_2)),
            ),
            _mm_mul_pd(n, k(PIO2_2T)),
        );
        let z = _mm_mul_pd(r, r);
        let horner = |c: [f64; 6]| {
            let mut p = k(c[5]);
            for ck in c[..5].iter().rev() {
                p = _mm_add_pd(k(*ck), _mm_mul_pd(z, p));
            }
            p
        };
        let ps = horner([S1, S2, S3, S4, S5, S6]);
        let s = _mm_add_pd(r, _mm_mul_pd(_mm_mul_pd(r, z), ps));
        let hz = _mm_mul_pd(k(0.5), z);
        let w = _mm_sub_pd(k(1.0), hz);
        let pc = horner([C1, C2, C3, C4, C5, C6]);
        let c = _mm_add_pd(
            w,
            _mm_add_pd(
                _mm_sub_pd(_mm_sub_pd(k(1.0), w), hz),
                _mm_mul_pd(_mm_mul_pd(z, z), pc),
            ),
        );
        // quadrant n mod 4 in both halves of each 64-bit lane
        let n32 = _mm_cvtpd_epi32(n);
        let n64 = _mm_unpacklo_epi32(n32, n32);
        let one = _mm_set1_epi64x(1);
        let two = _mm_set1_epi64x(2);
        // odd quadrant: sin and cos swap
        // (both 32-bit halves of a lane compared, so the mask fills the lane)
        let one32 = _mm_set1_epi32(1);
        let odd = _mm_castsi128_pd(_mm_cmpeq_epi32(_mm_and_si128(n64, one32), one32));
        let sin = _mm_or_pd(_mm_and_pd(odd, c), _mm_andnot_pd(odd, s));
        let cos = _mm_or_pd(_mm_and_pd(odd, s), _mm_andnot_pd(odd, c));
        // sin is negated in quadrants 2, 3; cos in quadrants 1, 2 (bit 1 of n and of n + 1)
        let sin = _mm_xor_pd(
            sin,
            _mm_castsi128_pd(_mm_slli_epi64(_mm_and_si128(n64, two), 62)),
        );
        let cos = _mm_xor_pd(
            cos,
            _mm_castsi128_pd(_mm_slli_epi64(
                _mm_and_si128(_mm_add_epi64(n64, one), two),
                62,
            )),
        );
        let lanes = |v: __m128d| [_mm_cvtsd_f64(v), _mm_cvtsd_f64(_mm_unpackhi_pd(v, v))];
        (lanes(sin), lanes(cos))
    }
}

#[cfg(target_arch = "x86_64")]
mod avx2 {
    //! Four angles in the lanes of a `ymm` register; the callers check for AVX2 at run time.
    use super::{C1, C2, C3, C4, C5, C6, PIO2_1, PIO2_2, PIO2_2T, S1, S2, S3, S4, S5, S6};
    use std::arch::x86_64::{
        __m256d, _mm256_add_epi64, _mm256_add_pd, _mm256_and_pd, _mm256_and_si256,
        _mm256_andnot_pd, _mm256_castsi256_pd, _mm256_cmp_pd, _mm256_cmpeq_epi64,
        _mm256_cvtepi32_epi64, _mm256_cvtpd_epi32, _mm256_movemask_pd, _mm256_mul_pd, _mm256_or_pd,
        _mm256_set1_epi64x, _mm256_set1_pd, _mm256_set_pd, _mm256_slli_epi64, _mm256_storeu_pd,
        _mm256_sub_pd, _mm256_xor_pd, _CMP_LT_OQ,
    };

    /// [`super::sin_cos_at`], four at a time, then by pairs.
    #[target_feature(enable = "avx2")]
    pub(super) fn sin_cos_at(q: &[f64], at: &[usize], out: &mut [[f64; 2]]) {
        let mut quads = at.chunks_exact(4);
        for k in quads.by_ref() {
            let x = [q[k[0]], q[k[1]], q[k[2]], q[k[3]]];
            let (s, c) = sin_cos_4(x).unwrap_or_else(|| {
                let sc = x.map(super::sin_cos);
                (sc.map(|t| t.0), sc.map(|t| t.1))
            });
            for t in 0..4 {
                out[k[t]] = [s[t], c[t]];
            }
        }
        super::sin_cos_pairs(q, quads.remainder(), out);
    }

    #[inline]
    #[target_feature(enable = "avx2")]
    fn k(x: f64) -> __m256d {
        _mm256_set1_pd(x)
    }

    #[inline]
    #[target_feature(enable = "avx2")]
    fn lanes(v: __m256d) -> [f64; 4] {
        let mut out = [0.0; 4];
        // SAFETY: `out` holds four f64 (an unaligned store).
        unsafe { _mm256_storeu_pd(out.as_mut_ptr(), v) };
        out
    }

    /// The steps of [`super::sin_cos`] in four lanes, or `None` unless every `|q| < 10⁵` (one
    /// vector comparison; NaN is out).
    #[inline]
    #[target_feature(enable = "avx2")]
    fn sin_cos_4(q: [f64; 4]) -> Option<([f64; 4], [f64; 4])> {
        const ROUND: f64 = 6_755_399_441_055_744.0;
        let x = _mm256_set_pd(q[3], q[2], q[1], q[0]);
        let abs = _mm256_andnot_pd(k(-0.0), x);
        if _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(abs, k(1e5))) != 0b1111 {
            return None;
        }
        let n = _mm256_sub_pd(
            _mm256_add_pd(_mm256_mul_pd(x, k(std::f64::consts::FRAC_2_PI)), k(ROUND)),
            k(ROUND),
        );
        let r = _mm256_sub_pd(
            _mm256_sub_pd(
                _mm256_sub_pd(x, _mm256_mul_pd(n, k(PIO2_1))),
                _mm256_mul_pd(n, k(PIO2_2)),
            ),
            _mm256_mul_pd(n, k(PIO2_2T)),
        );
        let z = _mm256_mul_pd(r, r);
        let mut ps = k(S6);
        for ck in [S5, S4, S3, S2, S1] {
            ps = _mm256_add_pd(k(ck), _mm256_mul_pd(z, ps));
        }
        let s = _mm256_add_pd(r, _mm256_mul_pd(_mm256_mul_pd(r, z), ps));
        let hz = _mm256_mul_pd(k(0.5), z);
        let w = _mm256_sub_pd(k(1.0), hz);
        let mut pc = k(C6);
        for ck in [C5, C4, C3, C2, C1] {
            pc = _mm256_add_pd(k(ck), _mm256_mul_pd(z, pc));
        }
        let c = _mm256_add_pd(
            w,
            _mm256_add_pd(
                _mm256_sub_pd(_mm256_sub_pd(k(1.0), w), hz),
                _mm256_mul_pd(_mm256_mul_pd(z, z), pc),
            ),
        );
        // the quadrant n mod 4 as a 64-bit integer per lane
        let n = _mm256_cvtepi32_epi64(_mm256_cvtpd_epi32(n));
        let one = _mm256_set1_epi64x(1);
        let two = _mm256_set1_epi64x(2);
        let odd = _mm256_castsi256_pd(_mm256_cmpeq_epi64(_mm256_and_si256(n, one), one));
        let sin = _mm256_or_pd(_mm256_and_pd(odd, c), _mm256_andnot_pd(odd, s));
        let cos = _mm256_or_pd(_mm256_and_pd(odd, s), _mm256_andnot_pd(odd, c));
        // sin is negated in quadrants 2, 3; cos in quadrants 1, 2 (bit 1 of n and of n + 1)
        let sin = _mm256_xor_pd(
            sin,
            _mm256_castsi256_pd(_mm256_slli_epi64(_mm256_and_si256(n, two), 62)),
        );
        let cos = _mm256_xor_pd(
            cos,
            _mm256_castsi256_pd(_mm256_slli_epi64(
                _mm256_and_si256(_mm256_add_epi64(n, one), two),
                62,
            )),
        );
        Some((lanes(sin), lanes(cos)))
    }
}

#[cfg(target_arch = "x86_64")]
mod avx512 {
    //! Eight angles in the lanes of a `zmm` register; the caller checks for AVX-512F at run time.
    use super::{C1, C2, C3, C4, C5, C6, PIO2_1, PIO2_2, PIO2_2T, S1, S2, S3, S4, S5, S6};
    use std::arch::x86_64::{
        __m512d, __m512i, _mm512_abs_pd, _mm512_add_epi64, _mm512_add_pd, _mm512_and_si512,
        _mm512_castpd_si512, _mm512_castsi512_pd, _mm512_cmp_pd_mask, _mm512_cvtepi32_epi64,
        _mm512_cvtpd_epi32, _mm512_loadu_pd, _mm512_mask_blend_pd, _mm512_mul_pd,
        _mm512_set1_epi64, _mm512_set1_pd, _mm512_slli_epi64, _mm512_storeu_pd, _mm512_sub_pd,
        _mm512_test_epi64_mask, _mm512_xor_si512, _CMP_LT_OQ,
    };

    #[inline]
    #[target_feature(enable = "avx512f")]
    fn k(x: f64) -> __m512d {
        _mm512_set1_pd(x)
    }

    /// The steps of [`super::sin_cos`] in eight lanes, or `None` unless every `|q| < 10⁵` (one
    /// vector comparison; NaN is out), as [`super::avx2`]'s four: the same operations, the
    /// quadrant `n mod 4` from the integer `n`, an odd one swapping sine and cosine, bit 1 of `n`
    /// (of `n + 1`) negating the sine (the cosine).
    #[inline]
    #[target_feature(enable = "avx512f")]
    pub(super) fn sin_cos_8(q: [f64; 8]) -> Option<([f64; 8], [f64; 8])> {
        const ROUND: f64 = 6_755_399_441_055_744.0;
        // SAFETY: `q` holds eight f64 (an unaligned load).
        let x = unsafe { _mm512_loadu_pd(q.as_ptr()) };
        if _mm512_cmp_pd_mask::<_CMP_LT_OQ>(_mm512_abs_pd(x), k(1e5)) != 0xff {
            return None;
        }
        let n = _mm512_sub_pd(
            _mm512_add_pd(_mm512_mul_pd(x, k(std::f64::consts::FRAC_2_PI)), k(ROUND)),
            k(ROUND),
        );
        let r = _mm512_sub_pd(
            _mm512_sub_pd(
                _mm512_sub_pd(x, _mm512_mul_pd(n, k(PIO2_1))),
                _mm512_mul_pd(n, k(PIO2_2)),
            ),
            _mm512_mul_pd(n, k(PIO2_2T)),
        );
        let z = _mm512_mul_pd(r, r);
        let mut ps = k(S6);
        for ck in [S5, S4, S3, S2, S1] {
            ps = _mm512_add_pd(k(ck), _mm512_mul_pd(z, ps));
        }
        let s = _mm512_add_pd(r, _mm512_mul_pd(_mm512_mul_pd(r, z), ps));
        let hz = _mm512_mul_pd(k(0.5), z);
        let w = _mm512_sub_pd(k(1.0), hz);
        let mut pc = k(C6);
        for ck in [C5, C4, C3, C2, C1] {
            pc = _mm512_add_pd(k(ck), _mm512_mul_pd(z, pc));
        }
        let c = _mm512_add_pd(
            w,
            _mm512_add_pd(
                _mm512_sub_pd(_mm512_sub_pd(k(1.0), w), hz),
                _mm512_mul_pd(_mm512_mul_pd(z, z), pc),
            ),
        );
        let n = _mm512_cvtepi32_epi64(_mm512_cvtpd_epi32(n));
        let (one, two) = (_mm512_set1_epi64(1), _mm512_set1_epi64(2));
        let odd = _mm512_test_epi64_mask(n, one);
        // v with its sign flipped where bit 1 of n is set
        let sign = |v: __m512d, n: __m512i| {
            _mm512_castsi512_pd(_mm512_xor_si512(
                _mm512_castpd_si512(v),
                _mm512_slli_epi64(_mm512_and_si512(n, two), 62),
            ))
        };
        let sin = sign(_mm512_mask_blend_pd(odd, s, c), n);
        let cos = sign(_mm512_mask_blend_pd(odd, c, s), _mm512_add_epi64(n, one));
        let (mut so, mut co) = ([0.0; 8], [0.0; 8]);
        // SAFETY: `so` and `co` hold eight f64 each (unaligned stores).
        unsafe {
            _mm512_storeu_pd(so.as_mut_ptr(), sin);
            _mm512_storeu_pd(co.as_mut_ptr(), cos);
        }
        Some((so, co))
    }
}

#[cfg(test)]
mod tests {
    use super::sin_cos;

    #[test]
    fn sin_cos_matches_the_standard_library_to_an_ulp() {
        let mut worst: f64 = 0.0;
        for k in -200_000..=200_000 {
            let q = k as f64 * 1.2345e-4 + 0.5e-9 * (k % 7) as f64;
            let (s, c) = sin_cos(q);
            let (s0, c0) = q.sin_cos();
            worst = worst.max((s - s0).abs()).max((c - c0).abs());
        }
        assert!(worst <= 2.3e-16, "worst error {worst:e}");
        for q in [0.0, -0.0, 1e-300, 7.0e4, -9.9e4, 1e6] {
            let (s, c) = sin_cos(q);
            let (s0, c0) = q.sin_cos();
            assert!((s - s0).abs() <= 1e-11 && (c - c0).abs() <= 1e-11, "{q}");
        }
        assert!(sin_cos(f64::NAN).0.is_nan() && sin_cos(f64::INFINITY).1.is_nan());
    }

    /// `sin_cos_lanes` gives `sin_cos` bit for bit in 2, 4 and 8 lanes (8 in AVX-512F
    /// intrinsics where the CPU has them, the rest in the portable loops), in every quadrant and
    /// lane, and falls back for large or non-finite angles.
    #[test]
    fn sin_cos_lanes_equals_sin_cos_bit_for_bit() {
        fn check<const W: usize>(qs: &[f64]) {
            for chunk in qs.chunks(W) {
                let mut q = [0.25; W];
                q[..chunk.len()].copy_from_slice(chunk);
                let (s, c) = super::sin_cos_lanes(q);
                for i in 0..W {
                    let (s1, c1) = sin_cos(q[i]);
                    assert_eq!(s[i].to_bits(), s1.to_bits(), "W {W}: sin {}", q[i]);
                    assert_eq!(c[i].to_bits(), c1.to_bits(), "W {W}: cos {}", q[i]);
                }
            }
        }
        let special = [
            0.0,
            -0.0,
            0.3,
            -0.3,
            1.0,
            2.5,
            -2.5,
            3.2,
            -3.9,
            7.1,
            100.0,
            -99_999.0,
            1e6,
            f64::NAN,
            std::f64::consts::FRAC_PI_2,
            -3.0 * std::f64::consts::FRAC_PI_2,
            std::f64::consts::TAU,
        ];
        // every quadrant in every lane: a sweep over ±20 rad, all in the vector path's range
        let sweep: Vec<f64> = (-541..=541).map(|k| k as f64 * 0.037).collect();
        for qs in [&special[..], &sweep] {
            check::<2>(qs);
            check::<4>(qs);
            check::<8>(qs);
        }
    }

    /// `avx512::sin_cos_8` itself, where the CPU has AVX-512F: `Some` (and `sin_cos` bit for bit)
    /// when every lane is inside `|q| < 10⁵`, up to ±99 999.9; `None` when any one lane holds
    /// NaN, ±∞ or ±10⁵, whichever lane it is.
    #[test]
    #[cfg(target_arch = "x86_64")]
    fn sin_cos_8_is_exact_inside_its_range_and_refuses_the_rest() {
        if !std::arch::is_x86_feature_detected!("avx512f") {
            return;
        }
        let q = [-99_999.9, -3.0, -0.0, 0.0, 1.0, 2.0, 4.0, 99_999.9];
        // SAFETY: the CPU has AVX-512F (checked above).
        let (s, c) = unsafe { super::avx512::sin_cos_8(q) }.expect("all inside the range");
        for i in 0..8 {
            let (s1, c1) = sin_cos(q[i]);
            assert_eq!(
                (s[i].to_bits(), c[i].to_bits()),
                (s1.to_bits(), c1.to_bits()),
                "{}",
                q[i]
            );
        }
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e5, -1e5] {
            for lane in 0..8 {
                let mut q = [0.5; 8];
                q[lane] = bad;
                // SAFETY: as above.
                assert!(
                    unsafe { super::avx512::sin_cos_8(q) }.is_none(),
                    "{bad} in lane {lane}"
                );
            }
        }
    }

    #[test]
    fn sin_cos_at_equals_sin_cos_bit_for_bit() {
        let q: Vec<f64> = (-40_001..=40_001)
            .map(|k| k as f64 * 7.77e-4 + 1e-10 * (k % 5) as f64)
            .chain([1e6, -3.0, f64::NAN, 2.0, f64::INFINITY, 0.5, -0.0])
            .collect();
        // all at once (four lanes where the CPU has AVX2), and in threes (two lanes, then one)
        let mut out = vec![[0.0; 2]; q.len()];
        let at: Vec<usize> = (0..q.len()).rev().collect();
        super::sin_cos_at(&q, &at, &mut out);
        let mut out3 = vec![[0.0; 2]; q.len()];
        for at in at.chunks(3) {
            super::sin_cos_at(&q, at, &mut out3);
        }
        for (x, o) in q.iter().chain(&q).zip(out.iter().chain(&out3)) {
            let (s, c) = sin_cos(*x);
            assert!(
                s.to_bits() == o[0].to_bits() && c.to_bits() == o[1].to_bits()
                    || x.is_nan()
                    || x.is_infinite(),
                "{x}: {o:?} against {s}, {c}"
            );
            if !x.is_finite() {
                assert!(o[0].is_nan() && o[1].is_nan());
            }
        }
    }
}
