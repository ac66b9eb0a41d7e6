//! Measured motion: samples `(t, q, v, a, τ)` read from CSV, with velocities and accelerations
//! from a Savitzky–Golay differentiator when the file has only positions (or no accelerations).

use super::IdentificationError;
use crate::multibody::{column_names, Model};

/// Samples of a motion, one per time, each row-major: `q` is `n x nq`, `v`, `a`, `tau` are
/// `n x nv`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Samples {
    /// Times (s), increasing.
    pub t: Vec<f64>,
    /// Configurations.
    pub q: Vec<f64>,
    /// Velocities.
    pub v: Vec<f64>,
    /// Accelerations.
    pub a: Vec<f64>,
    /// Joint torques (forces).
    pub tau: Vec<f64>,
}

/// The columns a CSV file of samples has after `t`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CsvLayout {
    /// `q, v, a, tau`: nothing to differentiate.
    Full,
    /// `q, v, tau` (the layout of `rigid simulate --csv`): `a` from `v`.
    Velocities,
    /// `q, tau`: `v` and `a` from `q` (only for models whose joints all have one degree of
    /// freedom, where `v = q̇`).
    Positions,
}

/// The Savitzky–Golay differentiator (Savitzky & Golay 1964): at each sample, a polynomial of
/// degree `order` fitted by least squares to the `2 m + 1` samples around it, differentiated at
/// the centre. The derivatives are linear filters of the samples, exact for polynomials up to
/// `order`; the first and last `m` samples, which have no full window, are dropped. Needs
/// uniform sampling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SavitzkyGolay {
    /// `m`: samples each side of the centre.
    pub half_window: usize,
    /// Degree of the fitted polynomial (at least 2, for the second derivative).
    pub order: usize,
}

impl SavitzkyGolay {
    /// Degree 4 over a window of about `window` seconds at sampling period `dt`, at least
    /// `order + 1` samples each side.
    #[must_use]
    pub fn for_window(window: f64, dt: f64) -> Self {
        let order = 4;
        let m = (0.5 * window / dt).round();
        let m = if m.is_finite() { m as usize } else { 0 };
        Self {
            half_window: m.clamp(order / 2 + 1, 10_000),
            order,
        }
    }

    /// The filter weights of the first and second derivative at the centre, for a unit
    /// sampling period: `ẋ(0) ≈ Σ w1_i x_i`, `ẍ(0) ≈ Σ w2_i x_i`, `i = -m..=m`.
    ///
    /// ```
    /// use rigid::identification::SavitzkyGolay;
    /// let sg = SavitzkyGolay { half_window: 3, order: 4 };
    /// let (w1, w2) = sg.weights();
    /// // exact on x(t) = t³ - 2t² at t = 0.5 (samples t = 0.5 + i)
    /// let x: Vec<f64> = (-3..=3).map(|i| { let t = 0.5 + i as f64; t * t * t - 2.0 * t * t }).collect();
    /// let d1: f64 = w1.iter().zip(&x).map(|(w, x)| w * x).sum();
    /// let d2: f64 = w2.iter().zip(&x).map(|(w, x)| w * x).sum();
    /// assert!((d1 - (0.75 - 2.0)).abs() < 1e-12 && (d2 - (3.0 - 4.0)).abs() < 1e-12);
    /// ```
    #[must_use]
    pub fn weights(&self) -> (Vec<f64>, Vec<f64>) {
        let m = self.half_window as i64;
        let d = self.order.max(2);
        let rows = (2 * m + 1) as usize;
        let a =
            nalgebra::DMatrix::from_fn(rows, d + 1, |r, c| ((r as i64 - m) as f64).powi(c as i32));
        // (AᵀA)⁻¹ Aᵀ: row c gives the polynomial's coefficient c; x'(0) = c1, x''(0) = 2 c2
        let ata = a.transpose() * &a;
        let pinv = ata
            .cholesky()
            .map(|c| c.solve(&a.transpose()))
            .unwrap_or_else(|| nalgebra::DMatrix::zeros(d + 1, rows));
        let w1 = pinv.row(1).iter().copied().collect();
        let w2 = pinv.row(2).iter().map(|x| 2.0 * x).collect();
        (w1, w2)
    }
}

impl Samples {
    /// Number of samples.
    #[must_use]
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// `true` without samples.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }

    /// The CSV text: a header `t, q_…, v_…, a_…, tau_…` ([`column_names`]) and one row per
    /// sample.
    #[must_use]
    pub fn to_csv(&self, model: &Model) -> String {
        let (nq, nv) = (model.nq(), model.nv());
        let mut out = String::from("t,");
        out += &column_names(model, &["q", "v", "a", "tau"]).join(",");
        out.push('\n');
        for s in 0..self.len() {
            out += &format!("{}", self.t[s]);
            let rows = [
                &self.q[s * nq..(s + 1) * nq],
                &self.v[s * nv..(s + 1) * nv],
                &self.a[s * nv..(s + 1) * nv],
                &self.tau[s * nv..(s + 1) * nv],
            ];
            for x in rows.iter().flat_map(|r| r.iter()) {
                out += &format!(",{x}");
            }
            out.push('\n');
        }
        out
    }

    /// Samples from CSV text: an optional header line, then rows `t, q…, v…, a…, tau…`,
    /// `t, q…, v…, tau…` or `t, q…, tau…` (the layout is told by the number of columns).
    /// Missing velocities and accelerations are computed by a Savitzky–Golay differentiator of
    /// degree 4 over `window` seconds ([`SavitzkyGolay::for_window`] at the file's time step;
    /// `None`: 0.05 s), which drops the samples at both ends.
    ///
    /// A header whose column names start with `q_`, `v_`, `a_` or `tau_` must name the
    /// coordinates in rigid's order ([`column_names`]); other names are not checked.
    ///
    /// # Errors
    /// [`IdentificationError::Csv`] naming the line, and the column when there is one: a cell
    /// that is not a finite number, a row whose column count is not one of the layouts (or
    /// differs from the first row), times that do not increase, a header naming another
    /// coordinate, uneven time steps or a model with multi-dof joints where differentiation is
    /// needed, no samples.
    ///
    /// ```
    /// use rigid::identification::Samples;
    /// let model = rigid::multibody::builtin("pendulum").unwrap();
    /// let s = Samples::from_csv(&model, "t,q_joint1,v_joint1,a_joint1,tau_joint1\n0,0.1,0,0,0.5\n", None)?;
    /// assert_eq!((s.len(), s.tau[0]), (1, 0.5));
    /// let bad = Samples::from_csv(&model, "0,0.1,0,0,0.5\n0.1,0.2,nan,0,0.5\n", None).unwrap_err();
    /// assert!(bad.to_string().contains("line 2, column 3 (v_joint1)"));
    /// # Ok::<(), rigid::identification::IdentificationError>(())
    /// ```
    pub fn from_csv(
        model: &Model,
        text: &str,
        window: Option<f64>,
    ) -> Result<Self, IdentificationError> {
        let (nq, nv) = (model.nq(), model.nv());
        let widths = [
            (1 + nq + 3 * nv, CsvLayout::Full),
            (1 + nq + 2 * nv, CsvLayout::Velocities),
            (1 + nq + nv, CsvLayout::Positions),
        ];
        let err = |line: usize, column: Option<usize>, names: &[String], message: String| {
            IdentificationError::Csv {
                line,
                column: column.map(|c| (c + 1, names.get(c).cloned().unwrap_or_default())),
                message,
            }
        };
        let mut layout: Option<(CsvLayout, Vec<String>)> = None;
        let mut rows: Vec<Vec<f64>> = Vec::new();
        let mut header: Option<(usize, Vec<String>)> = None;
        for (i, raw) in text.lines().enumerate() {
            let line = i + 1;
            let cells: Vec<&str> = raw.split(',').map(str::trim).collect();
            if raw.trim().is_empty() || raw.trim_start().starts_with('#') {
                continue;
            }
            let width = cells.len();
            let (kind, names) = match &layout {
                Some(l) => l.clone(),
                None => {
                    let Some(&(_, kind)) = widths.iter().find(|(w, _)| *w == width) else {
                        return Err(err(
                            line,
                            None,
                            &[],
                            format!(
                                "{width} columns; {} (nq = {nq}, nv = {nv}) needs {} (t, q, v, a, \
                                 tau), {} (t, q, v, tau) or {} (t, q, tau): check the model and \
                                 the file's columns",
                                model.name(),
                                widths[0].0,
                                widths[1].0,
                                widths[2].0
                            ),
                        ));
                    };
                    let prefixes: &[&str] = match kind {
                        CsvLayout::Full => &["q", "v", "a", "tau"],
                        CsvLayout::Velocities => &["q", "v", "tau"],
                        CsvLayout::Positions => &["q", "tau"],
                    };
                    let mut names = vec!["t".to_string()];
                    names.extend(column_names(model, prefixes));
                    layout = Some((kind, names.clone()));
                    (kind, names)
                }
            };
            let _ = kind;
            if width != names.len() {
                return Err(err(
                    line,
                    None,
                    &names,
                    format!(
                        "{width} columns, but the first row has {}; every row needs the same \
                         columns",
                        names.len()
                    ),
                ));
            }
            let is_header = rows.is_empty()
                && header.is_none()
                && cells.iter().any(|c| c.parse::<f64>().is_err());
            if is_header {
                for (c, cell) in cells.iter().enumerate() {
                    let claims = ["q_", "v_", "a_", "tau_"]
                        .iter()
                        .any(|p| cell.starts_with(p));
                    if claims && *cell != names[c] {
                        return Err(err(
                            line,
                            Some(c),
                            &names,
                            format!(
                                "the header says \"{cell}\" where rigid's order has \"{}\": put \
                                 the columns in the model's joint order",
                                names[c]
                            ),
                        ));
                    }
                }
                header = Some((line, cells.iter().map(|c| (*c).to_string()).collect()));
                continue;
            }
            let mut row = Vec::with_capacity(width);
            for (c, cell) in cells.iter().enumerate() {
                match cell.parse::<f64>() {
                    Ok(x) if x.is_finite() => row.push(x),
                    Ok(x) => {
                        return Err(err(
                            line,
                            Some(c),
                            &names,
                            format!("{x} is not a finite number; remove the row or fill the gap"),
                        ))
                    }
                    Err(_) => {
                        return Err(err(
                            line,
                            Some(c),
                            &names,
                            format!("\"{cell}\" is not a number; remove the row or fill the gap"),
                        ))
                    }
                }
            }
            if let Some(prev) = rows.last() {
                if row[0] <= prev[0] {
                    return Err(err(
                        line,
                        Some(0),
                        &names,
                        format!(
                            "time {} does not increase (previous {}); sort the rows by time",
                            row[0], prev[0]
                        ),
                    ));
                }
            }
            rows.push(row);
            let _ = i;
        }
        let Some((kind, names)) = layout.filter(|_| !rows.is_empty()) else {
            return Err(IdentificationError::Csv {
                line: text.lines().count().max(1),
                column: None,
                message: "no samples in the file".into(),
            });
        };
        let first_line = header.map_or(1, |h| h.0 + 1);
        let mut s = Self::default();
        for r in &rows {
            s.t.push(r[0]);
            s.q.extend_from_slice(&r[1..1 + nq]);
        }
        match kind {
            CsvLayout::Full => {
                for r in &rows {
                    let o = 1 + nq;
                    s.v.extend_from_slice(&r[o..o + nv]);
                    s.a.extend_from_slice(&r[o + nv..o + 2 * nv]);
                    s.tau.extend_from_slice(&r[o + 2 * nv..o + 3 * nv]);
                }
                return Ok(s);
            }
            CsvLayout::Velocities => {
                for r in &rows {
                    s.v.extend_from_slice(&r[1 + nq..1 + nq + nv]);
                    s.tau.extend_from_slice(&r[1 + nq + nv..1 + nq + 2 * nv]);
                }
            }
            CsvLayout::Positions => {
                if let Some(j) = model.joints().iter().find(|j| j.nq != 1 || j.nv != 1) {
                    return Err(err(
                        first_line,
                        None,
                        &names,
                        format!(
                            "joint \"{}\" ({}) has no scalar velocity to differentiate from q: \
                             give the velocities too (t, q, v, tau or t, q, v, a, tau)",
                            j.name,
                            j.kind.name()
                        ),
                    ));
                }
                s.v.extend_from_slice(&s.q);
                for r in &rows {
                    s.tau.extend_from_slice(&r[1 + nq..1 + nq + nv]);
                }
            }
        }
        let dt = uniform_step(&s.t).map_err(|(k, step, median)| {
            err(
                first_line + k,
                Some(0),
                &names,
                format!(
                    "time step {step} s differs from the median {median} s by more than 1 %; \
                     the differentiator needs uniform sampling (resample, or give v and a)"
                ),
            )
        })?;
        let sg = SavitzkyGolay::for_window(window.unwrap_or(0.05), dt);
        s.differentiate(nq, nv, kind, &sg, dt)
            .map_err(|needed| err(first_line, None, &names, needed))?;
        Ok(s)
    }

    /// Fills `v` (layout `Positions`: from `q`, which `v` holds on entry) and `a` by `sg`, and
    /// drops the `m` samples at each end.
    fn differentiate(
        &mut self,
        nq: usize,
        nv: usize,
        kind: CsvLayout,
        sg: &SavitzkyGolay,
        dt: f64,
    ) -> Result<(), String> {
        let n = self.len();
        let m = sg.half_window;
        if n < 2 * m + 2 {
            return Err(format!(
                "{n} samples; the differentiator's window takes {} (2 x {m} + 1) and drops {m} at \
                 each end: record more samples or give v and a",
                2 * m + 1
            ));
        }
        let (w1, w2) = sg.weights();
        let keep = m..n - m;
        let filter = |x: &[f64], k: usize, w: &[f64], s: usize, scale: f64| -> f64 {
            w.iter()
                .enumerate()
                .map(|(i, wi)| wi * x[(s + i - m) * nv + k])
                .sum::<f64>()
                * scale
        };
        let (mut v, mut a) = (Vec::new(), Vec::new());
        for s in keep.clone() {
            for k in 0..nv {
                match kind {
                    CsvLayout::Positions => {
                        v.push(filter(&self.v, k, &w1, s, 1.0 / dt));
                        a.push(filter(&self.v, k, &w2, s, 1.0 / (dt * dt)));
                    }
                    _ => {
                        v.push(self.v[s * nv + k]);
                        a.push(filter(&self.v, k, &w1, s, 1.0 / dt));
                    }
                }
            }
        }
        self.t = self.t[keep.clone()].to_vec();
        self.q = self.q[keep.start * nq..keep.end * nq].to_vec();
        self.tau = self.tau[keep.start * nv..keep.end * nv].to_vec();
        self.v = v;
        self.a = a;
        Ok(())
    }
}

/// The median time step, or `(index, step, median)` of the first step that differs from it by
/// more than 1 %.
fn uniform_step(t: &[f64]) -> Result<f64, (usize, f64, f64)> {
    let mut steps: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    if steps.is_empty() {
        return Ok(1.0);
    }
    let raw = steps.clone();
    steps.sort_by(f64::total_cmp);
    let median = steps[steps.len() / 2];
    match raw.iter().position(|s| (s - median).abs() > 0.01 * median) {
        Some(k) => Err((k + 1, raw[k], median)),
        None => Ok(median),
    }
}
