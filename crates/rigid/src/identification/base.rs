//! The parameters of an identification (the ten inertial parameters of every body, then the
//! optional joint terms: viscous and Coulomb friction, rotor inertia) and the base parameters:
//! the combinations of them that joint torques determine.

use super::regressor::Regressor;
use crate::mass::{SpatialInertia, PARAMETER_NAMES};
use crate::multibody::{random_configuration, Model, MultibodyError, Rng};
use nalgebra::{DMatrix, DVector};
use std::fmt;

/// Which joint terms join the ten inertial parameters of each body. Each is one parameter per
/// degree of freedom of the 1-dof joints (revolute, continuous, prismatic):
/// - `friction`: viscous `f_v` and Coulomb `f_c`, `τ_k += f_v,k v_k + f_c,k sign(v_k)`;
/// - `rotor_inertia`: the reflected rotor inertia (armature) `I_a`, `τ_k += I_a,k a_k`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct JointTerms {
    /// Viscous and Coulomb friction per joint.
    pub friction: bool,
    /// Rotor inertia (armature) per joint.
    pub rotor_inertia: bool,
}

/// The layout of the full parameter vector `π`: `10 n` inertial parameters (body `j` at
/// `10 j`, [`crate::mass::SpatialInertia::to_parameters`] order), then, for each degree of
/// freedom of a 1-dof joint in order, `f_v` and `f_c` (with friction), then `I_a` (with rotor
/// inertia).
#[derive(Clone, Debug, PartialEq)]
pub struct ParameterLayout {
    /// The joint terms.
    pub terms: JointTerms,
    /// Number of bodies.
    pub bodies: usize,
    /// The degrees of freedom that carry joint terms.
    pub dofs: Vec<usize>,
}

impl ParameterLayout {
    /// The layout for `model` with `terms`.
    #[must_use]
    pub fn new(model: &Model, terms: JointTerms) -> Self {
        let dofs = model
            .joints()
            .iter()
            .filter(|j| j.nv == 1 && j.nq == 1)
            .map(|j| j.idx_v)
            .collect();
        Self {
            terms,
            bodies: model.njoints(),
            dofs,
        }
    }

    /// Number of parameters.
    #[must_use]
    pub fn len(&self) -> usize {
        10 * self.bodies
            + self.dofs.len()
                * (2 * usize::from(self.terms.friction) + usize::from(self.terms.rotor_inertia))
    }

    /// `true` for a model without bodies.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The spatial inertia of each body from the parameters `pi` in this layout: its first
    /// `10 n` entries, ten per body (the joint terms after them are not bodies).
    ///
    /// ```
    /// use rigid::identification::{model_parameters, JointTerms, ParameterLayout};
    /// let model = rigid::multibody::builtin("puma560").unwrap();
    /// let layout = ParameterLayout::new(&model, JointTerms { friction: true, rotor_inertia: true });
    /// let mut pi = model_parameters(&model).as_slice().to_vec();
    /// pi.resize(layout.len(), 0.0); // 60 inertial parameters, then 3 x 6 joint terms
    /// assert_eq!(layout.body_inertias(&pi), model.inertias());
    /// ```
    ///
    /// # Panics
    /// If `pi` has fewer than `10 n` entries.
    #[must_use]
    pub fn body_inertias(&self, pi: &[f64]) -> Vec<SpatialInertia> {
        pi[..10 * self.bodies]
            .chunks_exact(10)
            .map(|p| SpatialInertia::from_parameters(p.try_into().expect("chunks of ten")))
            .collect()
    }

    /// Index of the first friction parameter (`f_v` of the first dof; `f_c` follows it).
    #[must_use]
    pub fn friction_start(&self) -> Option<usize> {
        self.terms.friction.then_some(10 * self.bodies)
    }

    /// Index of the first rotor inertia parameter.
    #[must_use]
    pub fn rotor_start(&self) -> Option<usize> {
        self.terms
            .rotor_inertia
            .then(|| 10 * self.bodies + 2 * self.dofs.len() * usize::from(self.terms.friction))
    }

    /// The name of every parameter: `m3`, `mx3`, `Izz3` (body 3, counted from 1: the body moved
    /// by the third joint), `fv2`, `fc2`, `Ia2` (the second degree of freedom, counted from 1).
    #[must_use]
    pub fn names(&self) -> Vec<String> {
        let mut names = Vec::with_capacity(self.len());
        for b in 1..=self.bodies {
            names.extend(PARAMETER_NAMES.iter().map(|p| format!("{p}{b}")));
        }
        if self.terms.friction {
            for k in &self.dofs {
                names.push(format!("fv{}", k + 1));
                names.push(format!("fc{}", k + 1));
            }
        }
        if self.terms.rotor_inertia {
            names.extend(self.dofs.iter().map(|k| format!("Ia{}", k + 1)));
        }
        names
    }

    /// The model's own values of the parameters: its inertias, the URDF's `<dynamics damping
    /// friction>` as `f_v`, `f_c`, its armature as `I_a`.
    #[must_use]
    pub fn model_values(&self, model: &Model) -> DVector<f64> {
        let mut p = DVector::zeros(self.len());
        p.rows_mut(0, 10 * self.bodies)
            .copy_from(&super::model_parameters(model));
        if let Some(s) = self.friction_start() {
            for (i, &k) in self.dofs.iter().enumerate() {
                p[s + 2 * i] = model.damping()[k];
                p[s + 2 * i + 1] = model.friction()[k];
            }
        }
        if let Some(s) = self.rotor_start() {
            for (i, &k) in self.dofs.iter().enumerate() {
                p[s + i] = model.armature()[k];
            }
        }
        p
    }

    /// Writes the rows of one sample into `out` (`nv` rows, `len()` columns): the inertial
    /// regressor `y` and the joint-term columns `v_k`, `sign(v_k)`, `a_k`.
    pub fn fill_rows(
        &self,
        y: &DMatrix<f64>,
        v: &[f64],
        a: &[f64],
        mut out: nalgebra::DMatrixViewMut<'_, f64>,
    ) {
        let n = 10 * self.bodies;
        out.columns_mut(0, n).copy_from(y);
        if self.len() == n {
            return;
        }
        out.columns_mut(n, self.len() - n).fill(0.0);
        if let Some(s) = self.friction_start() {
            for (i, &k) in self.dofs.iter().enumerate() {
                out[(k, s + 2 * i)] = v[k];
                out[(k, s + 2 * i + 1)] = sign(v[k]);
            }
        }
        if let Some(s) = self.rotor_start() {
            for (i, &k) in self.dofs.iter().enumerate() {
                out[(k, s + i)] = a[k];
            }
        }
    }
}

/// `sign(x)` with `sign(0) = 0` (Coulomb friction at rest is undetermined: it takes no part).
pub(crate) fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// The base parameters: a set of independent parameters `π_B` and the grouping
/// `β = π_B + K π_D` of the dependent ones `π_D` into them, such that the stacked regressor of
/// any motion satisfies `W π = W_B β` (Gautier 1990, "Numerical calculation of the base inertial
/// parameters of robots").
///
/// Found numerically: the regressor of random states is stacked, and its columns are taken left
/// to right, each kept when it is not in the span of those kept before (Gram-Schmidt with
/// re-orthogonalisation, relative tolerance [`BaseParameters::TOLERANCE`]), so that each base
/// parameter is represented by its lowest-numbered parameter and the ones of the bodies further
/// out are grouped into it (`Izz3 + Iyy4 + …`, `m5 + m6`, as by Khalil's grouping rules).
/// Columns that are zero (parameters that never act on a joint, as `m1` of a robot whose first
/// joint turns about the vertical) belong to no base parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct BaseParameters {
    /// The names of all parameters.
    pub names: Vec<String>,
    /// The independent parameters `B` (indices into the full vector, ascending).
    pub independent: Vec<usize>,
    /// The dependent parameters `D` with a non-zero column.
    pub dependent: Vec<usize>,
    /// `K` (`|B| x |D|`): `β = π_B + K π_D`.
    pub grouping: DMatrix<f64>,
}

impl BaseParameters {
    /// Relative tolerance of the independence test: a column is dependent when its component
    /// outside the span of the columns kept before is below `TOLERANCE` times its norm.
    pub const TOLERANCE: f64 = 1e-8;

    /// The base parameters of `model` with joint terms `terms`, from the regressor of random
    /// states (random configurations within the limits, velocities and accelerations uniform in
    /// `[-1, 1]`; `seed` fixes them).
    ///
    /// ```
    /// use rigid::identification::{BaseParameters, JointTerms};
    /// let model = rigid::multibody::builtin("puma560").unwrap();
    /// let base = BaseParameters::of_model(&model, JointTerms::default(), 1)?;
    /// assert_eq!(base.len(), 36); // 60 inertial parameters, 36 combinations identifiable
    /// // the first joint sees the inertia of everything about its axis: Izz1 only in a sum
    /// assert!(base.expression(0).starts_with("Izz1 + "));
    /// # Ok::<(), rigid::multibody::MultibodyError>(())
    /// ```
    ///
    /// # Errors
    /// A model whose random states the algorithms refuse (none that the builder accepts).
    pub fn of_model(model: &Model, terms: JointTerms, seed: u64) -> Result<Self, MultibodyError> {
        let layout = ParameterLayout::new(model, terms);
        let (nv, p) = (model.nv(), layout.len());
        let samples = if nv == 0 {
            0
        } else {
            (3 * p).div_ceil(nv).max(20)
        };
        let mut rng = Rng::new(seed);
        let mut reg = Regressor::new(model);
        let mut w = DMatrix::zeros(samples * nv, p);
        for s in 0..samples {
            let q = random_configuration(model, &mut rng);
            let v: Vec<f64> = (0..nv).map(|_| rng.uniform(-1.0, 1.0)).collect();
            let a: Vec<f64> = (0..nv).map(|_| rng.uniform(-1.0, 1.0)).collect();
            let y = reg.compute(model, &q, &v, &a)?;
            layout.fill_rows(y, &v, &a, w.rows_mut(s * nv, nv));
        }
        Ok(Self::from_regressor(&w, layout.names()))
    }

    /// The base parameters of the stacked regressor `w` (one column per parameter, `names`).
    #[must_use]
    pub fn from_regressor(w: &DMatrix<f64>, names: Vec<String>) -> Self {
        let norms: Vec<f64> = w.column_iter().map(|c| c.norm()).collect();
        let largest = norms.iter().copied().fold(0.0, f64::max);
        let mut q: Vec<DVector<f64>> = Vec::new();
        // R of the kept columns (column j of W_B = Σ_i R[i][j] q_i), and the coefficients of
        // each dependent column in the basis q
        let mut r: Vec<Vec<f64>> = Vec::new();
        let (mut independent, mut dependent, mut coeffs) = (Vec::new(), Vec::new(), Vec::new());
        for (j, col) in w.column_iter().enumerate() {
            if norms[j] <= 1e-12 * largest {
                continue;
            }
            let mut x: DVector<f64> = col.into();
            let mut c = vec![0.0; q.len()];
            for _ in 0..2 {
                for (i, qi) in q.iter().enumerate() {
                    let d = qi.dot(&x);
                    c[i] += d;
                    x.axpy(-d, qi, 1.0);
                }
            }
            let rest = x.norm();
            if rest > Self::TOLERANCE * norms[j] {
                c.push(rest);
                q.push(x / rest);
                independent.push(j);
                r.push(c);
            } else {
                dependent.push(j);
                coeffs.push(c);
            }
        }
        let nb = independent.len();
        let mut rm = DMatrix::zeros(nb, nb);
        for (j, col) in r.iter().enumerate() {
            for (i, x) in col.iter().enumerate() {
                rm[(i, j)] = *x;
            }
        }
        let mut c = DMatrix::zeros(nb, dependent.len());
        for (d, col) in coeffs.iter().enumerate() {
            for (i, x) in col.iter().enumerate() {
                c[(i, d)] = *x;
            }
        }
        let grouping = rm
            .solve_upper_triangular(&c)
            .unwrap_or_else(|| DMatrix::zeros(nb, dependent.len()));
        Self {
            names,
            independent,
            dependent,
            grouping,
        }
    }

    /// Number of base parameters.
    #[must_use]
    pub fn len(&self) -> usize {
        self.independent.len()
    }

    /// `true` when no parameter acts on the joints.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.independent.is_empty()
    }

    /// The base parameters `β = π_B + K π_D` of the full parameters `pi`.
    #[must_use]
    pub fn project(&self, pi: &DVector<f64>) -> DVector<f64> {
        let pb = DVector::from_iterator(self.len(), self.independent.iter().map(|&j| pi[j]));
        let pd =
            DVector::from_iterator(self.dependent.len(), self.dependent.iter().map(|&j| pi[j]));
        pb + &self.grouping * pd
    }

    /// The base regressor `W_B` (the independent columns of `w`): `W π = W_B β`.
    #[must_use]
    pub fn columns(&self, w: &DMatrix<f64>) -> DMatrix<f64> {
        w.select_columns(&self.independent)
    }

    /// The full parameters closest to `prior` (least change, in the Euclidean norm) whose base
    /// parameters are `beta`: `π = prior + Aᵀ (A Aᵀ)⁻¹ (β − β(prior))` with `A = [1 K]` on
    /// `(π_B, π_D)`; the parameters in no base parameter keep their prior values.
    #[must_use]
    pub fn lift(&self, beta: &DVector<f64>, prior: &DVector<f64>) -> DVector<f64> {
        let delta = beta - self.project(prior);
        let k = &self.grouping;
        let aat = DMatrix::identity(self.len(), self.len()) + k * k.transpose();
        let y = aat
            .cholesky()
            .map_or_else(|| delta.clone(), |c| c.solve(&delta));
        let mut pi = prior.clone();
        for (i, &j) in self.independent.iter().enumerate() {
            pi[j] += y[i];
        }
        let yd = k.transpose() * y;
        for (i, &j) in self.dependent.iter().enumerate() {
            pi[j] += yd[i];
        }
        pi
    }

    /// Base parameter `i` written out: `Izz3 + Iyy4 + 0.4318 m4 − 0.0203 mx5`, the coefficients
    /// to six significant digits (those below `10⁻⁹` in magnitude left out).
    #[must_use]
    pub fn expression(&self, i: usize) -> String {
        let mut s = self.names[self.independent[i]].clone();
        for (d, &j) in self.dependent.iter().enumerate() {
            let c = self.grouping[(i, d)];
            if c.abs() < 1e-9 {
                continue;
            }
            let sign = if c < 0.0 { " - " } else { " + " };
            let mag = c.abs();
            if (mag - 1.0).abs() < 1e-9 {
                s += &format!("{sign}{}", self.names[j]);
            } else {
                s += &format!("{sign}{} {}", significant(mag, 6), self.names[j]);
            }
        }
        s
    }
}

/// `x` to `digits` significant digits, without trailing zeros.
pub(crate) fn significant(x: f64, digits: i32) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let e = x.abs().log10().floor() as i32;
    if !(-4..=6).contains(&e) {
        return format!("{:.*e}", (digits - 1) as usize, x);
    }
    let decimals = (digits - 1 - e).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

impl fmt::Display for BaseParameters {
    /// One base parameter a line: `β1 = Izz1 + Iyy2 + Iyy3`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for i in 0..self.len() {
            writeln!(f, "β{} = {}", i + 1, self.expression(i))?;
        }
        Ok(())
    }
}
