//! Proven bounds on the magnitude of a monomial of the tables over the joint ranges.
//!
//! A variable `φ = Σ ε_l θ_{j_l}` ranges over the sum of its joints' intervals (the joint limits,
//! shifted by the angle offsets), or over the whole circle when a joint has no finite limits or
//! the sum spans `2π`. On an interval, `|cos^c φ sin^s φ|` is largest at an end or at a
//! stationary point inside (`tan² φ = s/c`, or where `|sin|` or `|cos|` is 1), so the maximum over
//! those candidates is the supremum; a monomial's bound is the product of its variables'
//! suprema (the variables range over a box that contains their joint range), times `1 + 1e-12`
//! against round-off. A prismatic variable's `|q^s|` is bounded by its limits, or not at all.

use super::paper::{Monomial, Var};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// The interval of a variable, or `None` for the whole circle (or an unbounded displacement).
pub(crate) fn var_range(var: &Var, ranges: &[Option<(f64, f64)>]) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = (0.0, 0.0);
    for &(j, e) in &var.joints {
        let (a, b) = ranges[j]?;
        if e > 0 {
            lo += a;
            hi += b;
        } else {
            lo -= b;
            hi -= a;
        }
    }
    if !var.prismatic && hi - lo >= TAU {
        return None;
    }
    Some((lo, hi))
}

/// `sup |cos^c x sin^s x|` over `[lo, hi]` (`None`: all x).
pub(crate) fn trig_sup(c: u8, s: u8, range: Option<(f64, f64)>) -> f64 {
    let f = |x: f64| x.cos().abs().powi(i32::from(c)) * x.sin().abs().powi(i32::from(s));
    let (c_f, s_f) = (f64::from(c), f64::from(s));
    // stationary points in [0, π): where the maximum over a period is
    let stationary: Vec<f64> = match (c, s) {
        (0, 0) => return 1.0,
        (0, _) => vec![FRAC_PI_2],
        (_, 0) => vec![0.0],
        _ => {
            let x = (s_f / c_f).sqrt().atan();
            vec![x, PI - x]
        }
    };
    let Some((lo, hi)) = range else {
        return stationary.iter().map(|&x| f(x)).fold(0.0, f64::max) * (1.0 + 1e-12);
    };
    let mut best = f(lo).max(f(hi));
    for &x0 in &stationary {
        // x0 + kπ inside [lo, hi]
        let mut k = ((lo - x0) / PI).ceil();
        while x0 + k * PI <= hi {
            best = best.max(f(x0 + k * PI));
            k += 1.0;
        }
    }
    best * (1.0 + 1e-12)
}

/// A bound on `|m|` over the joint ranges (`f64::INFINITY` if a displacement is unbounded).
pub(crate) fn monomial_sup(m: &Monomial, vars: &[Var], ranges: &[Option<(f64, f64)>]) -> f64 {
    m.iter()
        .map(|&(v, (c, s))| {
            let var = &vars[v];
            let r = var_range(var, ranges);
            if var.prismatic {
                r.map_or(f64::INFINITY, |(lo, hi)| {
                    lo.abs().max(hi.abs()).powi(i32::from(s)) * (1.0 + 1e-12)
                })
            } else {
                trig_sup(c, s, r)
            }
        })
        .product()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn trig_suprema_are_attained_and_not_exceeded() {
        // SC over the circle: 1/2; SS: 1; C S²: 2/(3√3)
        assert!((trig_sup(1, 1, None) - 0.5).abs() < 1e-11);
        assert!((trig_sup(0, 2, None) - 1.0).abs() < 1e-11);
        assert!((trig_sup(1, 2, None) - 2.0 / (3.0 * 3f64.sqrt())).abs() < 1e-11);
        // sin on [0.1, 0.5]: at the end; cos on [-0.2, 0.3]: 1 at 0
        assert!((trig_sup(0, 1, Some((0.1, 0.5))) - 0.5f64.sin()).abs() < 1e-11);
        assert!((trig_sup(1, 0, Some((-0.2, 0.3))) - 1.0).abs() < 1e-11);
        // dense sampling never exceeds the bound
        for (c, s) in [(1, 0), (0, 1), (1, 1), (0, 2), (1, 2), (0, 3)] {
            for (lo, hi) in [(-0.3, 0.9), (1.0, 2.5), (-3.0, -1.2), (2.0, 7.0)] {
                let b = trig_sup(c, s, Some((lo, hi)));
                let mut m: f64 = 0.0;
                for i in 0..=2000 {
                    let x = lo + (hi - lo) * f64::from(i) / 2000.0;
                    m = m.max(x.cos().abs().powi(i32::from(c)) * x.sin().abs().powi(i32::from(s)));
                }
                assert!(
                    m <= b && m > b * (1.0 - 1e-5),
                    "{c} {s} [{lo}, {hi}]: {m} vs {b}"
                );
            }
        }
    }
}
