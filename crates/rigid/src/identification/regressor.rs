//! The joint-torque regressor `Y(q, v, a)`: `τ = Y π` with `π` the ten inertial parameters of
//! every body (Atkeson, An & Hollerbach 1986; Khalil & Dombre 2002, §12.3; Pinocchio's
//! `computeJointTorqueRegressor`).

use crate::error::DimensionError;
use crate::mass::SpatialInertia;
use crate::multibody::{rnea, Data, Model, MultibodyError};
use crate::spatial::{Twist, Vec3, Wrench};
use nalgebra::{DMatrix, DVector};

/// The body regressor `Φ(V, A)` (6 x 10, as ten wrench columns): the wrench
/// `F = G A − [ad_V]ᵀ G V` of a body with twist `V = (ω, v)` and acceleration `A = (ω̇, v̇)` (both
/// in its frame, gravity included in `A`) is `F = Φ(V, A) π` for its parameters `π` about the
/// frame's origin ([`SpatialInertia::to_parameters`]). With `ã = v̇ + ω × v` (the acceleration
/// of the origin) and `B_c` the symmetric basis matrix of `Ī`'s entry `c`:
///
/// - `m`: `(0, ã)`;
/// - `h = m c` along `e`: `(e × ã, ω̇ × e + ω × (ω × e))`;
/// - `Ī` entry: `(B_c ω̇ + ω × B_c ω, 0)`.
///
/// ```
/// use rigid::identification::body_regressor;
/// use rigid::mass::{RotationalInertia, SpatialInertia};
/// use rigid::spatial::{Twist, Vec3};
/// let g = SpatialInertia::from_com(1.5, Vec3::new(0.1, -0.2, 0.3), RotationalInertia::new(0.3, 0.2, 0.25, 0.01, -0.02, 0.03));
/// let (v, a) = (Twist::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(-1.0, 0.5, 0.2)), Twist::new(Vec3::new(0.3, -0.4, 0.5), Vec3::new(0.0, 1.0, 9.81)));
/// let f = g.momentum(&a) - v.ad_transpose(&g.momentum(&v));
/// let phi = body_regressor(&v, &a);
/// let p = g.to_parameters();
/// let mut y = rigid::spatial::Wrench::zero();
/// for c in 0..10 { y += phi[c] * p[c]; }
/// assert!((y - f).norm() < 1e-13);
/// ```
#[must_use]
pub fn body_regressor(V: &Twist, A: &Twist) -> [Wrench; 10] {
    let (w, dw) = (V.w, A.w);
    let acc = A.v + w.cross(&V.v);
    let mut phi = [Wrench::zero(); 10];
    phi[0] = Wrench::new(Vec3::zeros(), acc);
    for (c, e) in [Vec3::x(), Vec3::y(), Vec3::z()].iter().enumerate() {
        phi[1 + c] = Wrench::new(e.cross(&acc), dw.cross(e) + w.cross(&w.cross(e)));
    }
    // B_c x for the entries (Ixx, Ixy, Iyy, Ixz, Iyz, Izz) of a symmetric Ī
    let b = |c: usize, x: &Vec3| match c {
        0 => Vec3::new(x.x, 0.0, 0.0),
        1 => Vec3::new(x.y, x.x, 0.0),
        2 => Vec3::new(0.0, x.y, 0.0),
        3 => Vec3::new(x.z, 0.0, x.x),
        4 => Vec3::new(0.0, x.z, x.y),
        _ => Vec3::new(0.0, 0.0, x.z),
    };
    for c in 0..6 {
        phi[4 + c] = Wrench::new(b(c, &dw) + w.cross(&b(c, &w)), Vec3::zeros());
    }
    phi
}

/// The inertial parameters of every moving body of `model`, `π = (π_1, …, π_n)` (length
/// `10 n`, bodies in joint order, each about its joint frame's origin): the `π` of
/// [`Regressor`]'s `τ = Y π`. Links welded by fixed joints are merged into their body, so a
/// body's parameters are those of the composite.
///
/// ```
/// use rigid::identification::model_parameters;
/// let model = rigid::multibody::builtin("pendulum").unwrap(); // 1 kg, 1 m rod
/// let pi = model_parameters(&model);
/// assert_eq!(pi.len(), 10);
/// assert_eq!(pi[0], model.inertias()[0].mass());
/// ```
#[must_use]
pub fn model_parameters(model: &Model) -> DVector<f64> {
    let mut pi = DVector::zeros(10 * model.njoints());
    for (i, g) in model.inertias().iter().enumerate() {
        pi.rows_mut(10 * i, 10)
            .copy_from_slice(&SpatialInertia::to_parameters(g));
    }
    pi
}

/// A copy of `model` whose body inertias are the parameters `pi` (length `10 n`, as
/// [`model_parameters`]), taken as they are: no check (see
/// [`Consistency`](crate::mass::Consistency)).
///
/// # Errors
/// `pi` of the wrong length.
///
/// ```
/// use rigid::identification::{model_parameters, model_with_parameters};
/// let model = rigid::multibody::builtin("double_pendulum").unwrap();
/// let mut pi = model_parameters(&model);
/// pi[10] *= 2.0; // twice the mass of the second body, same first moment and inertia
/// let heavier = model_with_parameters(&model, pi.as_slice())?;
/// assert_eq!(heavier.inertias()[1].mass(), 2.0 * model.inertias()[1].mass());
/// # Ok::<(), rigid::error::DimensionError>(())
/// ```
pub fn model_with_parameters(model: &Model, pi: &[f64]) -> Result<Model, DimensionError> {
    DimensionError::check("pi", 10 * model.njoints(), pi.len())?;
    let inertias: Vec<SpatialInertia> = pi
        .chunks_exact(10)
        .map(|p| SpatialInertia::from_parameters(p.try_into().expect("chunks of 10")))
        .collect();
    let mut m = model.clone();
    m.replace_inertias(inertias);
    Ok(m)
}

/// The joint-torque regressor of a model, with its workspace: [`compute`](Self::compute) fills
/// `Y(q, v, a)` (nv x 10 n) such that `τ = Y π` for the inertial parameters `π` of
/// [`model_parameters`] (rigid's `rnea` adds the joint armature, `τ = Y π + armature ∘ a`).
///
/// Columns: body `j`'s ten parameters `(m, m cx, m cy, m cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz)` about
/// its joint frame's origin at `10 j..10 j + 10`, Pinocchio's `computeJointTorqueRegressor`
/// order; rows: rigid's `τ` (a free-flyer's rows are angular first, where Pinocchio's are
/// linear first). Algorithm: the forward pass of RNEA gives each body's `V_j` and `A_j`
/// (gravity as a base acceleration), [`body_regressor`] its wrench columns `Φ_j`, which are
/// carried up to the root, `Φ ← [Ad_{liMi⁻¹}]ᵀ Φ`, filling row `k` of each ancestor's
/// (and its own) degrees of freedom with `S_kᵀ Φ`. O(n · depth); no allocation after
/// [`new`](Self::new).
///
/// ```
/// use rigid::identification::{model_parameters, Regressor};
/// use rigid::multibody::{builtin, rnea, Data};
/// let model = builtin("puma560").unwrap();
/// let (q, v, a) = ([0.1, -0.4, 0.3, 0.2, 0.5, -0.1], [0.5; 6], [-1.0; 6]);
/// let mut reg = Regressor::new(&model);
/// let y = reg.compute(&model, &q, &v, &a)?;
/// let mut data = Data::new(&model);
/// let tau = rnea(&model, &mut data, &q, &v, &a)?;
/// assert!((y * model_parameters(&model) - tau).norm() < 1e-12 * tau.norm());
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Regressor {
    data: Data,
    y: DMatrix<f64>,
}

impl Regressor {
    /// The workspace and the `nv x 10 n` matrix for `model`.
    #[must_use]
    pub fn new(model: &Model) -> Self {
        Self {
            data: Data::new(model),
            y: DMatrix::zeros(model.nv, 10 * model.njoints()),
        }
    }

    /// The last regressor computed.
    #[must_use]
    pub fn matrix(&self) -> &DMatrix<f64> {
        &self.y
    }

    /// `Y(q, v, a)`.
    ///
    /// # Errors
    /// As [`rnea`]: wrong lengths, non-finite entries, a non-unit quaternion, or a workspace
    /// made for another model.
    pub fn compute(
        &mut self,
        model: &Model,
        q: &[f64],
        v: &[f64],
        a: &[f64],
    ) -> Result<&DMatrix<f64>, MultibodyError> {
        if self.y.ncols() != 10 * model.njoints() || self.y.nrows() != model.nv {
            return Err(MultibodyError::DataMismatch {
                njoints: self.y.ncols() / 10,
                nq: self.data.sin_cos.len(),
                nv: self.y.nrows(),
            });
        }
        // the forward pass: V_j, A_j (gravity included) and liMi of every body
        rnea(model, &mut self.data, q, v, a)?;
        let Self { data, y } = self;
        y.fill(0.0);
        for j in 0..model.njoints() {
            let mut phi = body_regressor(&data.velocities[j], &data.accelerations_gravity[j]);
            let mut i = j;
            loop {
                let joint = &model.joints()[i];
                for k in joint.idx_v..joint.idx_v + joint.nv {
                    let S = &data.S[k]; // S(q), as RNEA left it
                    for (c, f) in phi.iter().enumerate() {
                        y[(k, 10 * j + c)] = S.dot(f);
                    }
                }
                let Some(p) = joint.parent else { break };
                let X = &data.parent_placements[i];
                for f in &mut phi {
                    *f = X.act_wrench(f);
                }
                i = p.0;
            }
        }
        Ok(&self.y)
    }

    /// The regressors of many samples stacked: rows `nv s..nv (s + 1)` of `out` are
    /// `Y(q_s, v_s, a_s)`, with `q` (`n x nq`), `v` and `a` (`n x nv`) row-major, one sample a
    /// row. `out` must be `n nv x 10 n_bodies`. No allocation.
    ///
    /// # Errors
    /// Lengths that do not match, and the first sample that [`compute`](Self::compute) refuses.
    ///
    /// ```
    /// use rigid::identification::Regressor;
    /// let model = rigid::multibody::builtin("double_pendulum").unwrap();
    /// let (q, v, a) = ([0.1, 0.2, 0.3, 0.4], [1.0; 4], [0.5; 4]); // two samples
    /// let mut w = nalgebra::DMatrix::zeros(4, 20);
    /// let mut reg = Regressor::new(&model);
    /// reg.stack(&model, &q, &v, &a, &mut w)?;
    /// assert_eq!(w.rows(2, 2), *reg.compute(&model, &q[2..], &v[2..], &a[2..])?);
    /// # Ok::<(), rigid::multibody::MultibodyError>(())
    /// ```
    pub fn stack(
        &mut self,
        model: &Model,
        q: &[f64],
        v: &[f64],
        a: &[f64],
        out: &mut DMatrix<f64>,
    ) -> Result<(), MultibodyError> {
        let (nq, nv) = (model.nq, model.nv);
        let n = q.len().checked_div(nq).unwrap_or(0);
        DimensionError::check("q", n * nq, q.len())?;
        DimensionError::check("v", n * nv, v.len())?;
        DimensionError::check("a", n * nv, a.len())?;
        DimensionError::check("stacked regressor rows", n * nv, out.nrows())?;
        DimensionError::check("stacked regressor columns", self.y.ncols(), out.ncols())?;
        for s in 0..n {
            let y = self.compute(
                model,
                &q[s * nq..(s + 1) * nq],
                &v[s * nv..(s + 1) * nv],
                &a[s * nv..(s + 1) * nv],
            )?;
            out.rows_mut(s * nv, nv).copy_from(y);
        }
        Ok(())
    }
}
