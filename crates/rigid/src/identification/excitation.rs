//! Exciting trajectories: a finite Fourier series per joint (Swevers, Ganseman, Tükel, De
//! Schutter & Van Brussel 1997, "Optimal robot excitation and identification"), within the
//! joint position and velocity limits, its coefficients chosen to minimise the condition number
//! of the stacked base regressor.
//!
//! `q_k(t) = c_k + Σ_{l=1..L} a_kl/(l ω) sin(l ω t) − b_kl/(l ω) cos(l ω t)`, so that
//! `q̇_k = Σ a_kl cos(l ω t) + b_kl sin(l ω t)`; with `Σ_l a_kl = 0` and `Σ_l l b_kl = 0` the
//! motion starts and ends (it is periodic, `ω = 2π / duration`) at rest.

use super::base::{BaseParameters, JointTerms, ParameterLayout};
use super::regressor::Regressor;
use super::samples::Samples;
use super::IdentificationError;
use crate::multibody::{rnea, Data, Model, Rng};
use nalgebra::DMatrix;
use std::f64::consts::PI;

/// Options of [`optimize`].
#[derive(Clone, Debug, PartialEq)]
pub struct ExcitationOptions {
    /// Duration (s): one period of the series.
    pub duration: f64,
    /// Harmonics `L` per joint.
    pub harmonics: usize,
    /// Times (evenly spaced over the period) at which the regressor is evaluated for the
    /// condition number.
    pub points: usize,
    /// Evaluations of the condition number by the optimiser.
    pub iterations: usize,
    /// Fraction of each joint's range (and velocity limit) kept free at each side.
    pub margin: f64,
    /// The joint terms whose base parameters are to be excited too.
    pub terms: JointTerms,
    /// Seed of the random start and search.
    pub seed: u64,
}

impl Default for ExcitationOptions {
    fn default() -> Self {
        Self {
            duration: 10.0,
            harmonics: 5,
            points: 100,
            iterations: 300,
            margin: 0.05,
            terms: JointTerms::default(),
            seed: 1,
        }
    }
}

/// A Fourier-series trajectory of every joint (all of one degree of freedom).
#[derive(Clone, Debug, PartialEq)]
pub struct FourierTrajectory {
    /// `ω` (rad/s).
    pub omega: f64,
    /// Offsets `c_k`.
    pub offsets: Vec<f64>,
    /// `a_kl`, row-major (`nv x L`).
    pub a: Vec<f64>,
    /// `b_kl`, row-major.
    pub b: Vec<f64>,
    /// `L`.
    pub harmonics: usize,
}

impl FourierTrajectory {
    /// `(q, q̇, q̈)` at time `t`.
    pub fn sample(&self, t: f64, q: &mut [f64], v: &mut [f64], a: &mut [f64]) {
        let (w, n) = (self.omega, self.harmonics);
        for k in 0..self.offsets.len() {
            let (mut x, mut dx, mut ddx) = (self.offsets[k], 0.0, 0.0);
            for l in 1..=n {
                let (al, bl) = (self.a[k * n + l - 1], self.b[k * n + l - 1]);
                let wl = w * l as f64;
                let (s, c) = (wl * t).sin_cos();
                x += al / wl * s - bl / wl * c;
                dx += al * c + bl * s;
                ddx += -al * wl * s + bl * wl * c;
            }
            q[k] = x;
            v[k] = dx;
            a[k] = ddx;
        }
    }

    /// The duration of one period, `2π / ω`.
    #[must_use]
    pub fn period(&self) -> f64 {
        2.0 * PI / self.omega
    }

    /// Samples every `dt` seconds over one period (both ends included), with the torques the
    /// model predicts (`τ = rnea(q, q̇, q̈)`, to be replaced by measurements).
    ///
    /// # Errors
    /// A configuration the model refuses (none for a trajectory made for it).
    pub fn samples(&self, model: &Model, dt: f64) -> Result<Samples, IdentificationError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(IdentificationError::Invalid(format!(
                "the sampling period must be positive, got {dt}"
            )));
        }
        let nv = model.nv();
        let n = (self.period() / dt).round() as usize + 1;
        let mut data = Data::new(model);
        let (mut q, mut v, mut a) = (vec![0.0; nv], vec![0.0; nv], vec![0.0; nv]);
        let mut s = Samples::default();
        for i in 0..n {
            let t = i as f64 * dt;
            self.sample(t, &mut q, &mut v, &mut a);
            s.t.push(t);
            s.tau.extend(rnea(model, &mut data, &q, &v, &a)?.iter());
            s.q.extend_from_slice(&q);
            s.v.extend_from_slice(&v);
            s.a.extend_from_slice(&a);
        }
        Ok(s)
    }
}

/// Position range and velocity limit of each degree of freedom, with the margin taken off.
fn limits(model: &Model, margin: f64) -> Result<Vec<(f64, f64, f64)>, IdentificationError> {
    let mut out = Vec::new();
    for j in model.joints() {
        if j.nq != 1 || j.nv != 1 {
            return Err(IdentificationError::Invalid(format!(
                "joint \"{}\" is {}: an exciting trajectory moves joints of one degree of \
                 freedom (a floating base's motion follows from the dynamics); record the motion \
                 of such a robot instead",
                j.name,
                j.kind.name()
            )));
        }
        let (mut lo, mut hi) = (model.lower_limits()[j.idx_q], model.upper_limits()[j.idx_q]);
        if !(lo.is_finite() && hi.is_finite()) {
            (lo, hi) = (-PI, PI);
        }
        let half = 0.5 * (hi - lo) * (1.0 - margin);
        let mid = 0.5 * (hi + lo);
        let vmax = model.velocity_limits()[j.idx_v];
        let vmax = if vmax.is_finite() && vmax > 0.0 {
            vmax * (1.0 - margin)
        } else {
            f64::INFINITY
        };
        out.push((mid - half, mid + half, vmax));
    }
    Ok(out)
}

/// The trajectory of the coefficients `x` (`2 nv L`: all `a`, then all `b`) made to start at
/// rest and fitted into the limits: the last harmonic absorbs `Σ a = 0`, `Σ l b = 0`, then each
/// joint's series is scaled (never enlarged beyond the position range) and centred.
fn shape(x: &[f64], lim: &[(f64, f64, f64)], omega: f64, n: usize) -> FourierTrajectory {
    let nv = lim.len();
    let (mut a, mut b) = (x[..nv * n].to_vec(), x[nv * n..].to_vec());
    for k in 0..nv {
        let r = k * n..(k + 1) * n;
        let sa: f64 = a[r.start..r.end - 1].iter().sum();
        a[r.end - 1] = -sa;
        let sb: f64 = (1..n).map(|l| l as f64 * b[r.start + l - 1]).sum();
        b[r.end - 1] = -sb / n as f64;
    }
    let mut t = FourierTrajectory {
        omega,
        offsets: vec![0.0; nv],
        a,
        b,
        harmonics: n,
    };
    // range and speed of each joint's series over a fine grid
    let grid = 64 * n;
    let (mut q, mut v, mut acc) = (vec![0.0; nv], vec![0.0; nv], vec![0.0; nv]);
    let mut lo = vec![f64::INFINITY; nv];
    let mut hi = vec![f64::NEG_INFINITY; nv];
    let mut vmax = vec![0.0f64; nv];
    for i in 0..grid {
        t.sample(
            i as f64 * t.period() / grid as f64,
            &mut q,
            &mut v,
            &mut acc,
        );
        for k in 0..nv {
            lo[k] = lo[k].min(q[k]);
            hi[k] = hi[k].max(q[k]);
            vmax[k] = vmax[k].max(v[k].abs());
        }
    }
    for k in 0..nv {
        let (qlo, qhi, vlim) = lim[k];
        let span = (hi[k] - lo[k]).max(f64::MIN_POSITIVE);
        // a little inside the margins: the grid may miss the extremes by a hair
        let s = (0.99 * (qhi - qlo) / span).min(0.99 * vlim / vmax[k].max(f64::MIN_POSITIVE));
        for l in 0..n {
            t.a[k * n + l] *= s;
            t.b[k * n + l] *= s;
        }
        t.offsets[k] = 0.5 * (qlo + qhi) - s * 0.5 * (lo[k] + hi[k]);
    }
    t
}

/// The condition number of the base regressor stacked at `points` times over the period.
fn condition(
    model: &Model,
    layout: &ParameterLayout,
    base: &BaseParameters,
    traj: &FourierTrajectory,
    points: usize,
    reg: &mut Regressor,
) -> f64 {
    let nv = model.nv();
    let mut w = DMatrix::zeros(points * nv, layout.len());
    let (mut q, mut v, mut a) = (vec![0.0; nv], vec![0.0; nv], vec![0.0; nv]);
    for i in 0..points {
        traj.sample(
            (i as f64 + 0.5) * traj.period() / points as f64,
            &mut q,
            &mut v,
            &mut a,
        );
        let Ok(y) = reg.compute(model, &q, &v, &a) else {
            return f64::INFINITY;
        };
        layout.fill_rows(y, &v, &a, w.rows_mut(i * nv, nv));
    }
    let s = base.columns(&w).singular_values();
    let (max, min) = s
        .iter()
        .fold((0.0f64, f64::INFINITY), |(h, l), x| (h.max(*x), l.min(*x)));
    if min > 0.0 {
        max / min
    } else {
        f64::INFINITY
    }
}

/// An exciting trajectory for `model` (every joint of one degree of freedom) and the condition
/// number of its base regressor: random coefficients, then a (1+1) evolution strategy with the
/// one-fifth success rule (Rechenberg) on `log cond(W_B)` of the stacked regressor at
/// [`ExcitationOptions::points`] times.
///
/// ```
/// use rigid::identification::excitation::{optimize, ExcitationOptions};
/// let model = rigid::multibody::builtin("double_pendulum").unwrap();
/// let opts = ExcitationOptions { duration: 4.0, iterations: 20, ..Default::default() };
/// let (traj, cond) = optimize(&model, &opts)?;
/// let (mut q, mut v, mut a) = ([0.0; 2], [0.0; 2], [0.0; 2]);
/// traj.sample(0.0, &mut q, &mut v, &mut a);
/// assert!(v.iter().chain(&a).all(|x| x.abs() < 1e-12)); // starts at rest
/// assert!(cond.is_finite());
/// # Ok::<(), rigid::identification::IdentificationError>(())
/// ```
///
/// # Errors
/// A joint with more than one degree of freedom, or options out of range.
pub fn optimize(
    model: &Model,
    opts: &ExcitationOptions,
) -> Result<(FourierTrajectory, f64), IdentificationError> {
    if !(opts.duration.is_finite() && opts.duration > 0.0) {
        return Err(IdentificationError::Invalid(format!(
            "the duration must be positive and finite, got {}",
            opts.duration
        )));
    }
    if opts.harmonics == 0 || opts.points == 0 || !(0.0..0.5).contains(&opts.margin) {
        return Err(IdentificationError::Invalid(
            "need at least one harmonic and one point, and a margin in [0, 0.5)".into(),
        ));
    }
    let lim = limits(model, opts.margin)?;
    let layout = ParameterLayout::new(model, opts.terms);
    let base = BaseParameters::of_model(model, opts.terms, opts.seed)?;
    let (nv, n) = (model.nv(), opts.harmonics);
    let omega = 2.0 * PI / opts.duration;
    let mut rng = Rng::new(opts.seed);
    let mut reg = Regressor::new(model);
    let mut eval = |x: &[f64]| {
        let t = shape(x, &lim, omega, n);
        let c = condition(model, &layout, &base, &t, opts.points, &mut reg);
        (t, c)
    };
    let mut x: Vec<f64> = (0..2 * nv * n).map(|_| rng.normal()).collect();
    let (mut best, mut cost) = eval(&x);
    let mut step = 0.3;
    for _ in 1..opts.iterations.max(1) {
        let y: Vec<f64> = x.iter().map(|xi| xi + step * rng.normal()).collect();
        let (t, c) = eval(&y);
        if c < cost {
            (x, best, cost) = (y, t, c);
            step *= 1.5;
        } else {
            step *= 1.5f64.powf(-0.25);
        }
        step = step.clamp(1e-3, 3.0);
    }
    Ok((best, cost))
}
