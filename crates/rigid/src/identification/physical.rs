//! The physically consistent estimate: least squares subject to every body's pseudo-inertia
//! being positive definite, a semidefinite program (Wensing, Kim & Slotine 2017), solved by the
//! interior-point conic solver Clarabel (Goulart & Chen 2024).

use super::estimate::{Estimate, Identification};
use super::IdentificationError;
#[cfg(feature = "sdp")]
use crate::mass::SpatialInertia;
#[cfg(feature = "sdp")]
use clarabel::algebra::CscMatrix;
#[cfg(feature = "sdp")]
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, PSDTriangleConeT,
    SolverStatus, SupportedConeT,
};
#[cfg(feature = "sdp")]
use nalgebra::{DMatrix, DVector};

/// Options of [`Identification::physically_consistent`].
#[derive(Clone, Debug, PartialEq)]
pub struct PhysicalOptions {
    /// `λ`, the weight of the pull towards the model's (URDF's) values: the objective is
    /// `‖W π − τ‖² + λ Σ_j d_j² (π_j − π⁰_j)²` with `d_j` the norm of parameter `j`'s column of
    /// `W`, floored at `10⁻³` of their RMS (so that a parameter the torques do not see at all
    /// stays at its model value). `λ = 10⁻⁴` costs a change of one parameter by `δ` as much as
    /// a residual of `10⁻² δ ‖w_j‖`: the well-excited combinations follow the data, the
    /// unidentifiable ones keep the model's values.
    pub regularization: f64,
    /// Optional bounds `(lower, upper)` on each body's mass (kg), indexed by body.
    pub mass_bounds: Option<Vec<(f64, f64)>>,
    /// The margin `ε` of `J ⪰ ε 1`, relative to the trace of the model's `J` of each body
    /// (`10⁻⁹` kg when that trace is zero): strictly positive definite.
    pub margin: f64,
}

impl PhysicalOptions {
    /// Mass bounds `((1 − f) m_i, (1 + f) m_i)` around each body's mass in `model` (`f = 0.2`:
    /// ±20 %), for [`Self::mass_bounds`].
    ///
    /// ```
    /// use rigid::identification::PhysicalOptions;
    /// let model = rigid::multibody::builtin("double_pendulum").unwrap();
    /// let b = PhysicalOptions::mass_bounds_within(&model, 0.2);
    /// let m = model.inertias()[0].mass();
    /// assert_eq!(b[0], (0.8 * m, 1.2 * m));
    /// ```
    #[must_use]
    pub fn mass_bounds_within(model: &crate::multibody::Model, fraction: f64) -> Vec<(f64, f64)> {
        model
            .inertias()
            .iter()
            .map(|g| ((1.0 - fraction) * g.mass(), (1.0 + fraction) * g.mass()))
            .collect()
    }
}

impl Default for PhysicalOptions {
    fn default() -> Self {
        Self {
            regularization: 1e-4,
            mass_bounds: None,
            margin: 1e-6,
        }
    }
}

#[cfg(feature = "sdp")]
/// `svec` of a symmetric 4x4 matrix in Clarabel's order: the upper triangle column by column,
/// off-diagonal entries times `√2`.
fn svec(j: &crate::mass::Mat4) -> [f64; 10] {
    let mut out = [0.0; 10];
    let mut k = 0;
    for c in 0..4 {
        for r in 0..=c {
            out[k] = if r == c {
                j[(r, c)]
            } else {
                std::f64::consts::SQRT_2 * 0.5 * (j[(r, c)] + j[(c, r)])
            };
            k += 1;
        }
    }
    out
}

#[cfg(feature = "sdp")]
/// The pseudo-inertia of the parameters `p` ([`SpatialInertia::pseudo_inertia`], linear in `p`).
fn pseudo(p: &[f64]) -> crate::mass::Mat4 {
    SpatialInertia::from_parameters(p.try_into().expect("ten parameters")).pseudo_inertia()
}

impl Identification {
    /// The physically consistent estimate: the full parameters `π` minimising
    /// `‖W π − τ‖² + λ Σ_j d_j² (π_j − π⁰_j)²` ([`PhysicalOptions::regularization`]) subject to
    /// - every body's pseudo-inertia `J(π_i) ⪰ ε_i 1` (positive definite: a mass distribution
    ///   exists; Wensing, Kim & Slotine 2017, eq. 6),
    /// - the mass bounds, if given,
    /// - `f_v, f_c, I_a ≥ 0` for the joint terms.
    ///
    /// The variables are scaled, `π = π⁰ + diag(1/d) y`, and the problem, a quadratic objective
    /// with one 4x4 semidefinite cone per body, is solved by Clarabel's interior-point method.
    /// The result satisfies the constraints as solved: nothing is clipped afterwards.
    ///
    /// Needs the crate feature `sdp` (Clarabel's semidefinite cone links OpenBLAS from the
    /// system): without it the options are checked and [`IdentificationError::NotBuilt`] says
    /// how to build it.
    ///
    /// # Errors
    /// [`IdentificationError::Solver`] when Clarabel does not report a solution (infeasible
    /// mass bounds, numerical failure), [`IdentificationError::Invalid`] for bad options,
    /// [`IdentificationError::NotBuilt`] without the feature `sdp`.
    pub fn physically_consistent(
        &self,
        opts: &PhysicalOptions,
    ) -> Result<Estimate, IdentificationError> {
        let nb = self.layout.bodies;
        if !(opts.regularization.is_finite() && opts.regularization >= 0.0) {
            return Err(IdentificationError::Invalid(format!(
                "the regularization weight must be finite and non-negative, got {}",
                opts.regularization
            )));
        }
        if let Some(b) = &opts.mass_bounds {
            if b.len() != nb {
                return Err(IdentificationError::Invalid(format!(
                    "{} mass bounds for {nb} bodies",
                    b.len()
                )));
            }
            if let Some(i) = b
                .iter()
                .position(|(l, u)| !(l.is_finite() && u.is_finite() && l <= u))
            {
                return Err(IdentificationError::Invalid(format!(
                    "mass bounds of body {} ({}): need finite lower <= upper",
                    i + 1,
                    self.model().joints()[i].name
                )));
            }
        }
        #[cfg(feature = "sdp")]
        return self.solve_sdp(opts);
        #[cfg(not(feature = "sdp"))]
        Err(IdentificationError::NotBuilt(
            "the physically consistent estimate (a semidefinite program) needs rigid built with \
             the feature `sdp`, which links OpenBLAS: install it (Debian: `apt-get install \
             libopenblas-dev libgfortran-12-dev pkg-config`), then build with `--features sdp` \
             (the CLI: `cargo install --path crates/rigid-cli --features sdp`)"
                .into(),
        ))
    }

    /// [`Self::physically_consistent`] once its options are checked: Clarabel.
    #[cfg(feature = "sdp")]
    fn solve_sdp(&self, opts: &PhysicalOptions) -> Result<Estimate, IdentificationError> {
        let p = self.layout.len();
        let nb = self.layout.bodies;
        let r = self.factor_r();
        let rp = r.columns(0, p);
        let z = r.column(p);
        let x0 = &self.prior;
        // scaling: d_j = ‖w_j‖ floored at 1e-3 of their RMS
        let d: Vec<f64> = (0..p).map(|j| rp.column(j).norm()).collect();
        let rms = (d.iter().map(|x| x * x).sum::<f64>() / p.max(1) as f64).sqrt();
        let floor = if rms > 0.0 { 1e-3 * rms } else { 1.0 };
        let s: Vec<f64> = d.iter().map(|x| 1.0 / x.max(floor)).collect();
        let m = DMatrix::from_fn(p + 1, p, |i, j| rp[(i, j)] * s[j]);
        let e = z - rp * x0;
        let scale = (m.norm_squared() / p.max(1) as f64).max(f64::MIN_POSITIVE);
        let mut pm = m.transpose() * &m;
        for i in 0..p {
            pm[(i, i)] += opts.regularization;
        }
        pm *= 2.0 / scale;
        let q: Vec<f64> = (m.transpose() * &e * (-2.0 / scale))
            .iter()
            .copied()
            .collect();
        let P = upper_csc(&pm);

        // constraints: s = b - A y in the cones
        let (mut ai, mut aj, mut av, mut b) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut cones: Vec<SupportedConeT<f64>> = Vec::new();
        let mut row = 0;
        for i in 0..nb {
            let o = 10 * i;
            let j0 = pseudo(&x0.as_slice()[o..o + 10]);
            let tr = j0.trace();
            let eps = if tr > 0.0 { opts.margin * tr } else { 1e-9 };
            let mut b_i = svec(&j0);
            for diag in [0, 2, 5, 9] {
                b_i[diag] -= eps;
            }
            b.extend_from_slice(&b_i);
            for c in 0..10 {
                let mut unit = [0.0; 10];
                unit[c] = 1.0;
                for (k, x) in svec(&pseudo(&unit)).iter().enumerate() {
                    if *x != 0.0 {
                        ai.push(row + k);
                        aj.push(o + c);
                        av.push(-x * s[o + c]);
                    }
                }
            }
            row += 10;
            cones.push(PSDTriangleConeT(4));
        }
        let mut nonneg = 0;
        let mut bound = |col: usize, sign: f64, rhs: f64, row: &mut usize| {
            // s = rhs - sign * S_col y >= 0
            ai.push(*row);
            aj.push(col);
            av.push(sign * s[col]);
            b.push(rhs);
            *row += 1;
            nonneg += 1;
        };
        if let Some(bounds) = &opts.mass_bounds {
            for (i, (lo, hi)) in bounds.iter().enumerate() {
                let c = 10 * i;
                bound(c, 1.0, hi - x0[c], &mut row); // m <= hi
                bound(c, -1.0, x0[c] - lo, &mut row); // m >= lo
            }
        }
        for c in 10 * nb..p {
            bound(c, -1.0, x0[c], &mut row); // f_v, f_c, I_a >= 0
        }
        if nonneg > 0 {
            cones.push(NonnegativeConeT(nonneg));
        }
        let A = CscMatrix::new_from_triplets(row, p, ai, aj, av);
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .max_iter(200)
            .build()
            .map_err(|e| IdentificationError::Solver(format!("settings: {e}")))?;
        let mut solver = DefaultSolver::new(&P, &q, &A, &b, &cones, settings)
            .map_err(|e| IdentificationError::Solver(format!("{e:?}")))?;
        solver.solve();
        let status = solver.solution.status;
        if !matches!(status, SolverStatus::Solved | SolverStatus::AlmostSolved) {
            return Err(IdentificationError::Solver(format!(
                "the semidefinite program was not solved ({status:?}){}",
                if opts.mass_bounds.is_some() {
                    ": the mass bounds may be infeasible"
                } else {
                    ""
                }
            )));
        }
        let y = &solver.solution.x;
        let pi = DVector::from_iterator(p, (0..p).map(|j| x0[j] + s[j] * y[j]));
        self.report(&pi, r)
    }
}

#[cfg(feature = "sdp")]
/// The upper triangle of a symmetric matrix in compressed-column form.
fn upper_csc(m: &DMatrix<f64>) -> CscMatrix<f64> {
    let n = m.ncols();
    let (mut colptr, mut rowval, mut nzval) = (vec![0], Vec::new(), Vec::new());
    for c in 0..n {
        for r in 0..=c {
            let x = 0.5 * (m[(r, c)] + m[(c, r)]);
            if x != 0.0 {
                rowval.push(r);
                nzval.push(x);
            }
        }
        colptr.push(rowval.len());
    }
    CscMatrix::new(n, n, colptr, rowval, nzval)
}
