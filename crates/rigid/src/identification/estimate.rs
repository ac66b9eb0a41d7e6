//! Least-squares identification of the base parameters from samples, on the triangular factor
//! of the stacked regressor (computed block by block: memory `O(p²)` whatever the number of
//! samples).

use super::base::{BaseParameters, JointTerms, ParameterLayout};
use super::regressor::Regressor;
use super::samples::Samples;
use super::IdentificationError;
use crate::multibody::Model;
use nalgebra::{DMatrix, DVector};

/// Samples per block of the incremental QR factorisation.
const BLOCK: usize = 256;

/// How the rows of the least-squares problem are weighted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Weighting {
    /// Ordinary least squares.
    #[default]
    None,
    /// Weighted least squares, each joint's rows divided by the standard deviation of its
    /// ordinary least-squares residual (Gautier & Khalil 1990, "Direct calculation of minimum
    /// set of inertial parameters of serial robots"; Gautier 1997): joints measured with
    /// different noise levels count equally.
    PerJoint,
}

/// One estimate of the parameters, with what tells how good it is.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// The full parameters `π` ([`ParameterLayout`]). From least squares only the base
    /// parameters are determined: the full vector is the one closest to the model's values that
    /// has them ([`BaseParameters::lift`]).
    pub parameters: DVector<f64>,
    /// The base parameters `β` ([`BaseParameters`]).
    pub base: DVector<f64>,
    /// Standard deviation of each base parameter, `σ √((W_Bᵀ W_B)⁻¹)_ii` with
    /// `σ² = ‖r‖² / (rows − |β|)` (weighted rows when weighted).
    pub base_std: DVector<f64>,
    /// RMS of the torque residual `τ − W π` over all rows (N·m or N).
    pub residual_rms: f64,
    /// RMS of the residual per degree of freedom.
    pub residual_rms_per_dof: Vec<f64>,
    /// `‖τ − W π‖ / ‖τ‖`.
    pub relative_residual: f64,
    /// Condition number of the (weighted) base regressor `W_B`, `σ_max / σ_min`.
    pub condition_number: f64,
}

/// An identification problem: a model, the parameter layout, the base parameters and the
/// samples, reduced to the triangular factor of `[W τ]`.
#[derive(Clone, Debug)]
pub struct Identification {
    model: Model,
    samples: Samples,
    /// The layout of the full parameters.
    pub layout: ParameterLayout,
    /// The base parameters.
    pub base: BaseParameters,
    /// The model's values of the parameters (the prior).
    pub prior: DVector<f64>,
    /// `R` of `[W τ] = Q R` (`p + 1` square), unweighted.
    r: DMatrix<f64>,
    /// Rows of `W` (`N nv`).
    rows: usize,
}

impl Identification {
    /// The problem of identifying `model`'s parameters (and `terms`) from `samples`; the base
    /// parameters are those of [`BaseParameters::of_model`] (seed 1).
    ///
    /// # Errors
    /// [`IdentificationError::TooFewSamples`] when the samples give fewer equations than base
    /// parameters (plus one, for the residual's variance);
    /// [`IdentificationError::RankDeficient`] when the motion does not excite every base
    /// parameter; a sample the algorithms refuse (a bad quaternion, a wrong length).
    pub fn new(
        model: &Model,
        samples: &Samples,
        terms: JointTerms,
    ) -> Result<Self, IdentificationError> {
        let layout = ParameterLayout::new(model, terms);
        let base = BaseParameters::of_model(model, terms, 1)?;
        let (nq, nv, n) = (model.nq(), model.nv(), samples.len());
        for (what, len, width) in [
            ("q", samples.q.len(), nq),
            ("v", samples.v.len(), nv),
            ("a", samples.a.len(), nv),
            ("tau", samples.tau.len(), nv),
        ] {
            if len != n * width {
                return Err(IdentificationError::Invalid(format!(
                    "samples: {what} has {len} numbers for {n} samples of {width}"
                )));
            }
        }
        let rows = n * nv;
        if rows <= base.len() {
            return Err(IdentificationError::TooFewSamples {
                samples: n,
                equations: rows,
                base: base.len(),
                needed: (base.len() + 1).div_ceil(nv.max(1)),
            });
        }
        let prior = layout.model_values(model);
        let mut id = Self {
            model: model.clone(),
            samples: samples.clone(),
            layout,
            base,
            prior,
            r: DMatrix::zeros(0, 0),
            rows,
        };
        id.r = id.factor(None)?;
        id.check_rank(&id.r)?;
        Ok(id)
    }

    /// The model.
    #[must_use]
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Number of samples.
    #[must_use]
    pub fn samples(&self) -> usize {
        self.samples.len()
    }

    /// Rows of the stacked regressor (`samples × nv`).
    #[must_use]
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Calls `f(s, W_s, τ_s)` for each sample `s` with its rows of the full regressor.
    pub(crate) fn for_each_sample(
        &self,
        mut f: impl FnMut(usize, &DMatrix<f64>, &[f64]),
    ) -> Result<(), IdentificationError> {
        let (nq, nv) = (self.model.nq(), self.model.nv());
        let mut reg = Regressor::new(&self.model);
        let mut w = DMatrix::zeros(nv, self.layout.len());
        let s = &self.samples;
        for k in 0..s.len() {
            let (v, a) = (&s.v[k * nv..(k + 1) * nv], &s.a[k * nv..(k + 1) * nv]);
            let y = reg.compute(&self.model, &s.q[k * nq..(k + 1) * nq], v, a)?;
            self.layout.fill_rows(y, v, a, w.rows_mut(0, nv));
            f(k, &w, &s.tau[k * nv..(k + 1) * nv]);
        }
        Ok(())
    }

    /// `R` of the QR factorisation of `[W τ]` with each row of dof `k` divided by
    /// `sigma[k]`, block by block: `R ← qr([R; block]).R`.
    fn factor(&self, sigma: Option<&[f64]>) -> Result<DMatrix<f64>, IdentificationError> {
        let (nv, p) = (self.model.nv(), self.layout.len());
        let mut r = DMatrix::<f64>::zeros(0, p + 1);
        let mut block = DMatrix::<f64>::zeros(BLOCK * nv, p + 1);
        let mut filled = 0;
        let flush = |r: &mut DMatrix<f64>, block: &DMatrix<f64>, rows: usize| {
            let mut stacked = DMatrix::zeros(r.nrows() + rows, p + 1);
            stacked.rows_mut(0, r.nrows()).copy_from(r);
            stacked
                .rows_mut(r.nrows(), rows)
                .copy_from(&block.rows(0, rows));
            let qr = stacked.qr();
            let rr = qr.r();
            *r = rr;
        };
        self.for_each_sample(|_, w, tau| {
            for k in 0..nv {
                let s = sigma.map_or(1.0, |s| 1.0 / s[k]);
                let row = filled * nv + k;
                for c in 0..p {
                    block[(row, c)] = w[(k, c)] * s;
                }
                block[(row, p)] = tau[k] * s;
            }
            filled += 1;
            if filled == BLOCK {
                flush(&mut r, &block, BLOCK * nv);
                filled = 0;
            }
        })?;
        if filled > 0 {
            flush(&mut r, &block, filled * nv);
        }
        // square it up: rows beyond p + 1 are zero; fewer rows are padded with zeros
        let mut out = DMatrix::zeros(p + 1, p + 1);
        let n = r.nrows().min(p + 1);
        out.rows_mut(0, n).copy_from(&r.rows(0, n));
        Ok(out)
    }

    /// `(R_B, z)`: the base columns of `R` and its last column, so that
    /// `‖W_B β − τ‖² = ‖R_B β − z‖²`.
    fn base_system(&self, r: &DMatrix<f64>) -> (DMatrix<f64>, DVector<f64>) {
        let p = self.layout.len();
        (self.base.columns(r), r.column(p).into())
    }

    /// The singular values of `R_B`, descending, with the right singular vectors.
    fn svd(&self, r: &DMatrix<f64>) -> (DVector<f64>, DMatrix<f64>) {
        let (rb, _) = self.base_system(r);
        let svd = rb.svd(false, true);
        let mut order: Vec<usize> = (0..svd.singular_values.len()).collect();
        order.sort_by(|&a, &b| svd.singular_values[b].total_cmp(&svd.singular_values[a]));
        let vt = svd.v_t.expect("asked for");
        let s = DVector::from_iterator(order.len(), order.iter().map(|&i| svd.singular_values[i]));
        let v = DMatrix::from_fn(vt.ncols(), order.len(), |r, c| vt[(order[c], r)]);
        (s, v)
    }

    fn check_rank(&self, r: &DMatrix<f64>) -> Result<(), IdentificationError> {
        let (s, v) = self.svd(r);
        let top = s.iter().copied().fold(0.0, f64::max);
        let low: Vec<usize> = (0..s.len())
            .filter(|&i| {
                s[i].partial_cmp(&(RANK_TOLERANCE * top)) != Some(std::cmp::Ordering::Greater)
            })
            .collect();
        if low.is_empty() {
            return Ok(());
        }
        let mut unexcited = Vec::new();
        for &i in &low {
            let col = v.column(i);
            let k = col.iamax();
            let e = self.base.expression(k);
            if !unexcited.contains(&e) {
                unexcited.push(e);
            }
        }
        let still: Vec<String> = self
            .model
            .joints()
            .iter()
            .filter(|j| {
                let (nq, s) = (self.model.nq(), &self.samples);
                (j.idx_q..j.idx_q + j.nq).all(|c| {
                    let x = s.q.iter().skip(c).step_by(nq);
                    let (lo, hi) = x.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
                        (l.min(*x), h.max(*x))
                    });
                    hi - lo <= 1e-9
                })
            })
            .map(|j| j.name.clone())
            .collect();
        Err(IdentificationError::RankDeficient {
            rank: s.len() - low.len(),
            base: s.len(),
            unexcited,
            still,
        })
    }

    /// Least squares on the base parameters (ordinary or weighted), with the report.
    ///
    /// # Errors
    /// None in practice (the rank was checked by [`new`](Self::new)); a weighted problem
    /// whose rank is lost.
    pub fn least_squares(&self, weighting: Weighting) -> Result<Estimate, IdentificationError> {
        let r = match weighting {
            Weighting::None => self.r.clone(),
            Weighting::PerJoint => {
                let ols = self.solve_base(&self.r);
                let est = self.report(&self.prior_lifted(&ols), &self.r)?;
                let floor = est.residual_rms * 1e-6 + f64::MIN_POSITIVE;
                let sigma: Vec<f64> = est
                    .residual_rms_per_dof
                    .iter()
                    .map(|s| s.max(floor))
                    .collect();
                let r = self.factor(Some(&sigma))?;
                self.check_rank(&r)?;
                r
            }
        };
        let beta = self.solve_base(&r);
        let pi = self.prior_lifted(&beta);
        self.report(&pi, &r)
    }

    fn prior_lifted(&self, beta: &DVector<f64>) -> DVector<f64> {
        self.base.lift(beta, &self.prior)
    }

    /// `β = argmin ‖R_B β − z‖` (back substitution on the QR of `R_B`).
    fn solve_base(&self, r: &DMatrix<f64>) -> DVector<f64> {
        let (rb, z) = self.base_system(r);
        let qr = rb.qr();
        let qtz = qr.q().transpose() * z;
        qr.r()
            .solve_upper_triangular(&qtz)
            .unwrap_or_else(|| DVector::zeros(self.base.len()))
    }

    /// The report of the full parameters `pi` against the samples; `r` is the (weighted) factor
    /// for the condition number and the standard deviations.
    pub(crate) fn report(
        &self,
        pi: &DVector<f64>,
        r: &DMatrix<f64>,
    ) -> Result<Estimate, IdentificationError> {
        let nv = self.model.nv();
        let mut per_dof = vec![0.0; nv];
        let (mut rss, mut tss) = (0.0, 0.0);
        self.for_each_sample(|_, w, tau| {
            let pred = w * pi;
            for k in 0..nv {
                let e = tau[k] - pred[k];
                per_dof[k] += e * e;
                rss += e * e;
                tss += tau[k] * tau[k];
            }
        })?;
        let n = self.samples.len().max(1) as f64;
        let beta = self.base.project(pi);
        let (rb, z) = self.base_system(r);
        let res = (&rb * &beta - z).norm_squared();
        let dof = (self.rows - self.base.len()).max(1) as f64;
        let sigma2 = res / dof;
        let (s, _) = self.svd(r);
        let qr = rb.qr();
        let rr = qr.r();
        let inv = rr
            .solve_upper_triangular(&DMatrix::identity(rr.nrows(), rr.ncols()))
            .unwrap_or_else(|| DMatrix::from_element(rr.nrows(), rr.ncols(), f64::NAN));
        let std = DVector::from_iterator(
            beta.len(),
            (0..beta.len()).map(|i| (sigma2 * inv.row(i).norm_squared()).sqrt()),
        );
        Ok(Estimate {
            parameters: pi.clone(),
            base: beta,
            base_std: std,
            residual_rms: (rss / (n * nv.max(1) as f64)).sqrt(),
            residual_rms_per_dof: per_dof.iter().map(|e| (e / n).sqrt()).collect(),
            relative_residual: if tss > 0.0 {
                (rss / tss).sqrt()
            } else {
                rss.sqrt()
            },
            condition_number: s[0] / s[s.len() - 1],
        })
    }

    /// The report of any full parameters `pi` ([`ParameterLayout`]) against the samples: the
    /// model's own values (`self.prior`), another estimate, ... (standard deviations and
    /// condition number of the unweighted problem).
    ///
    /// # Errors
    /// A sample the algorithms refuse.
    pub fn evaluate(&self, pi: &DVector<f64>) -> Result<Estimate, IdentificationError> {
        self.report(pi, &self.r)
    }

    /// The unweighted factor `R` of `[W τ]` (for the semidefinite program).
    #[cfg(feature = "sdp")]
    pub(crate) fn factor_r(&self) -> &DMatrix<f64> {
        &self.r
    }

    /// The predicted torques `W π` of every sample (row-major, `N x nv`).
    ///
    /// # Errors
    /// A sample the algorithms refuse.
    pub fn predict(&self, pi: &DVector<f64>) -> Result<Vec<f64>, IdentificationError> {
        let mut out = Vec::with_capacity(self.rows);
        self.for_each_sample(|_, w, _| out.extend((w * pi).iter()))?;
        Ok(out)
    }
}

/// A base regressor whose smallest singular value is below `RANK_TOLERANCE` times its largest
/// (condition number over `10¹⁰`) is taken as rank-deficient: the motion does not tell some base
/// parameters apart.
pub const RANK_TOLERANCE: f64 = 1e-10;
