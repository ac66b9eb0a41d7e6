//! Operations on configurations: `q ⊕ v dt`, `q1 ⊖ q0`, neutral, random and normalised
//! configurations, joint by joint (Lie-group operations of each joint's configuration space).

use super::{check_q, check_v, Model, MultibodyError};
use crate::error::DimensionError;
use crate::spatial::Mat6;
use nalgebra::DMatrix;

/// A small deterministic random generator (SplitMix64), enough for random configurations and
/// tests without a dependency.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed.
    #[must_use]
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }
    /// The next 64 random bits (SplitMix64, Steele, Lea & Flood 2014).
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in `[0, 1)`.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
    /// Standard normal (Box-Muller).
    pub fn normal(&mut self) -> f64 {
        let u1 = 1.0 - self.next_f64();
        let u2 = self.next_f64();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

/// `q_out = q ⊕ v dt`, joint by joint (see [`JointType::integrate`](super::JointType::integrate)).
///
/// # Errors
/// Wrong lengths, non-finite input or a non-unit quaternion in `q`.
///
/// ```
/// use rigid::mass::SpatialInertia;
/// use rigid::multibody::{integrate, neutral, JointType, ModelBuilder};
/// use rigid::spatial::{Transform, Vec3};
/// let mut b = ModelBuilder::new("floating");
/// b.add_joint(None, "base", JointType::FreeFlyer, Transform::identity(), SpatialInertia::zero())?;
/// let model = b.build()?;
/// let q = neutral(&model);
/// let mut q1 = vec![0.0; 7];
/// // body twist: ω = π/2 about z, v = 1 m/s along body x, for 1 s: a quarter circle
/// integrate(&model, &q, &[0.0, 0.0, std::f64::consts::FRAC_PI_2, 1.0, 0.0, 0.0], 1.0, &mut q1)?;
/// let r = 2.0 / std::f64::consts::PI;
/// assert!((q1[0] - r).abs() < 1e-12 && (q1[1] - r).abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn integrate(
    model: &Model,
    q: &[f64],
    v: &[f64],
    dt: f64,
    q_out: &mut [f64],
) -> Result<(), MultibodyError> {
    check_q(model, q)?;
    check_v(model, "v", v)?;
    DimensionError::check("q_out", model.nq, q_out.len())?;
    for j in model.joints() {
        let (iq, iv) = (j.idx_q..j.idx_q + j.nq, j.idx_v..j.idx_v + j.nv);
        j.kind.integrate(&q[iq.clone()], &v[iv], dt, &mut q_out[iq]);
    }
    Ok(())
}

/// `q_out = q ⊕ h v` with every free-flyer stepped in world-aligned axes, its part of `carry`
/// turned to its new body axes ([`JointType::integrate_world_aligned`]); the time-stepping
/// scheme's configuration update. Lengths are the caller's (unchecked).
pub(crate) fn integrate_world_aligned(
    model: &Model,
    q: &[f64],
    v: &[f64],
    h: f64,
    q_out: &mut [f64],
    carry: &mut [f64],
) {
    for j in model.joints() {
        let (iq, iv) = (j.idx_q..j.idx_q + j.nq, j.idx_v..j.idx_v + j.nv);
        j.kind.integrate_world_aligned(
            &q[iq.clone()],
            &v[iv.clone()],
            h,
            &mut q_out[iq],
            &mut carry[iv],
        );
    }
}

/// The frame's turning over `h` of every joint stepped in world-aligned axes, added to `dv`
/// ([`JointType::world_aligned_turn`]).
pub(crate) fn world_aligned_turn(model: &Model, v: &[f64], h: f64, dv: &mut [f64]) {
    for j in model.joints() {
        let iv = j.idx_v..j.idx_v + j.nv;
        j.kind.world_aligned_turn(&v[iv.clone()], h, &mut dv[iv]);
    }
}

/// `v_out = q1 ⊖ q0`, the velocity with `q0 ⊕ v_out = q1` (dt = 1).
///
/// # Errors
/// Wrong lengths, non-finite input or a non-unit quaternion.
pub fn difference(
    model: &Model,
    q0: &[f64],
    q1: &[f64],
    v_out: &mut [f64],
) -> Result<(), MultibodyError> {
    check_q(model, q0)?;
    check_q(model, q1)?;
    DimensionError::check("v_out", model.nv, v_out.len())?;
    for j in model.joints() {
        let (iq, iv) = (j.idx_q..j.idx_q + j.nq, j.idx_v..j.idx_v + j.nv);
        j.kind.difference(&q0[iq.clone()], &q1[iq], &mut v_out[iv]);
    }
    Ok(())
}

/// The neutral configuration (zeros, identity quaternions).
#[must_use]
pub fn neutral(model: &Model) -> Vec<f64> {
    let mut q = vec![0.0; model.nq];
    for j in model.joints() {
        j.kind.neutral(&mut q[j.idx_q..j.idx_q + j.nq]);
    }
    q
}

/// A random configuration within the position limits (angles in `[-π, π]` and translations in
/// `[-1, 1]` m where a limit is infinite; uniform quaternions).
#[must_use]
pub fn random_configuration(model: &Model, rng: &mut Rng) -> Vec<f64> {
    let mut q = vec![0.0; model.nq];
    for j in model.joints() {
        let iq = j.idx_q..j.idx_q + j.nq;
        j.kind.random(
            rng,
            &model.lower[iq.clone()],
            &model.upper[iq.clone()],
            &mut q[iq],
        );
    }
    q
}

/// A random configuration within the bounds `lower`, `upper` (one per configuration coordinate,
/// in place of the model's position limits; Pinocchio's `randomConfiguration(model, lower,
/// upper)`): each revolute, prismatic, helical or planar coordinate uniform in its bounds
/// (angles in `[-π, π]` and translations in `[-1, 1]` m where a bound is infinite), quaternions
/// uniform on SO(3) whatever their bounds.
///
/// # Errors
/// `lower` or `upper` not of length `nq`, a NaN bound, or `lower > upper`
/// ([`MultibodyError::NonFinite`] names the first bad index, in `lower`).
pub fn random_configuration_within(
    model: &Model,
    rng: &mut Rng,
    lower: &[f64],
    upper: &[f64],
) -> Result<Vec<f64>, MultibodyError> {
    DimensionError::check("lower", model.nq, lower.len())?;
    DimensionError::check("upper", model.nq, upper.len())?;
    if let Some(index) = lower
        .iter()
        .zip(upper)
        .position(|(l, u)| l.is_nan() || u.is_nan() || l > u)
    {
        return Err(MultibodyError::NonFinite {
            what: "lower",
            index,
        });
    }
    let mut q = vec![0.0; model.nq];
    for j in model.joints() {
        let iq = j.idx_q..j.idx_q + j.nq;
        j.kind
            .random(rng, &lower[iq.clone()], &upper[iq.clone()], &mut q[iq]);
    }
    Ok(q)
}

/// Normalise the quaternions in `q` (with `w ≥ 0`); other coordinates are left alone.
///
/// # Errors
/// Wrong length.
pub fn normalize(model: &Model, q: &mut [f64]) -> Result<(), MultibodyError> {
    DimensionError::check("q", model.nq, q.len())?;
    for j in model.joints() {
        j.kind.normalize(&mut q[j.idx_q..j.idx_q + j.nq]);
    }
    Ok(())
}

fn check_square(what: &'static str, model: &Model, m: &DMatrix<f64>) -> Result<(), MultibodyError> {
    DimensionError::check(what, model.nv() * model.nv(), m.nrows() * m.ncols())?;
    DimensionError::check(what, model.nv(), m.nrows())?;
    Ok(())
}

/// The Jacobians of `q ⊕ v dt` ([`integrate`](integrate)) with respect to `q`
/// (along `q ⊕ δ`) and to `v`, in the tangent coordinates at the result: column k of `d_dq` is
/// `d/dε ((q ⊕ ε e_k) ⊕ v dt) ⊖ (q ⊕ v dt)`. Block diagonal, one block per joint: vector joints
/// `1` and `dt`; a spherical joint `exp([ω dt])ᵀ` and `J_r(ω dt) dt` (SO(3)); a free-flyer
/// `[Ad_{exp(-ξ dt)}]` and `J_r(ξ dt) dt` (SE(3), angular first); a planar joint the same in
/// SE(2). (`T exp(δ) exp(ξ) = T exp(ξ) exp([Ad_{exp(-ξ)}] δ)` and
/// `exp(ξ + δ) ≈ exp(ξ) exp(J_r(ξ) δ)`.) Pinocchio's `dIntegrate` (`ARG0`, `ARG1`), free-flyer
/// blocks permuted.
///
/// # Errors
/// Wrong lengths (of `q`, `v`, or matrices that are not `nv x nv`), non-finite entries or a
/// non-unit quaternion.
///
/// ```
/// use nalgebra::DMatrix;
/// use rigid::multibody::{integrate_jacobians, pendulum};
/// let model = pendulum();
/// let (mut dq, mut dv) = (DMatrix::zeros(1, 1), DMatrix::zeros(1, 1));
/// integrate_jacobians(&model, &[0.3], &[2.0], 0.1, &mut dq, &mut dv)?;
/// assert_eq!((dq[(0, 0)], dv[(0, 0)]), (1.0, 0.1));
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn integrate_jacobians(
    model: &Model,
    q: &[f64],
    v: &[f64],
    dt: f64,
    d_dq: &mut DMatrix<f64>,
    d_dv: &mut DMatrix<f64>,
) -> Result<(), MultibodyError> {
    check_q(model, q)?;
    check_v(model, "v", v)?;
    check_square("d_dq", model, d_dq)?;
    check_square("d_dv", model, d_dv)?;
    if !dt.is_finite() {
        return Err(MultibodyError::NonFinite {
            what: "dt",
            index: 0,
        });
    }
    d_dq.fill(0.0);
    d_dv.fill(0.0);
    let (mut bq, mut bv) = (Mat6::zeros(), Mat6::zeros());
    for j in model.joints() {
        j.kind
            .integrate_jacobians(&v[j.dofs()], dt, &mut bq, &mut bv);
        let n = j.nv;
        d_dq.view_mut((j.idx_v, j.idx_v), (n, n))
            .copy_from(&bq.view((0, 0), (n, n)));
        d_dv.view_mut((j.idx_v, j.idx_v), (n, n))
            .copy_from(&bv.view((0, 0), (n, n)));
    }
    Ok(())
}

/// The Jacobians of `q₁ ⊖ q₀` ([`difference`](difference)) with respect to
/// `q₀` and `q₁` (each along `q ⊕ δ`). Block diagonal: vector joints `-1` and `1`; for a
/// rotation or rigid motion with `d = log(T₀⁻¹ T₁)`, `-J_r(-d)⁻¹` and `J_r(d)⁻¹` (SO(3) for a
/// spherical joint, SE(3) angular first for a free-flyer, SE(2) for a planar joint), since
/// `log(exp(d) exp(δ)) ≈ d + J_r(d)⁻¹ δ` and `log(exp(-δ) exp(d)) ≈ d - J_l(d)⁻¹ δ`,
/// `J_l(d) = J_r(-d)`. Pinocchio's `dDifference` (`ARG0`, `ARG1`), free-flyer blocks permuted.
///
/// # Errors
/// Wrong lengths (of `q₀`, `q₁`, or matrices that are not `nv x nv`), non-finite entries or a
/// non-unit quaternion.
///
/// ```
/// use nalgebra::DMatrix;
/// use rigid::multibody::{difference_jacobians, pendulum};
/// let model = pendulum();
/// let (mut d0, mut d1) = (DMatrix::zeros(1, 1), DMatrix::zeros(1, 1));
/// difference_jacobians(&model, &[0.3], &[0.5], &mut d0, &mut d1)?;
/// assert_eq!((d0[(0, 0)], d1[(0, 0)]), (-1.0, 1.0));
/// # Ok::<(), rigid::multibody::MultibodyError>(())
/// ```
pub fn difference_jacobians(
    model: &Model,
    q0: &[f64],
    q1: &[f64],
    d_dq0: &mut DMatrix<f64>,
    d_dq1: &mut DMatrix<f64>,
) -> Result<(), MultibodyError> {
    check_q(model, q0)?;
    check_q(model, q1)?;
    check_square("d_dq0", model, d_dq0)?;
    check_square("d_dq1", model, d_dq1)?;
    d_dq0.fill(0.0);
    d_dq1.fill(0.0);
    let (mut b0, mut b1) = (Mat6::zeros(), Mat6::zeros());
    for j in model.joints() {
        let iq = j.coordinates();
        j.kind
            .difference_jacobians(&q0[iq.clone()], &q1[iq], &mut b0, &mut b1);
        let n = j.nv;
        d_dq0
            .view_mut((j.idx_v, j.idx_v), (n, n))
            .copy_from(&b0.view((0, 0), (n, n)));
        d_dq1
            .view_mut((j.idx_v, j.idx_v), (n, n))
            .copy_from(&b1.view((0, 0), (n, n)));
    }
    Ok(())
}

/// `out = dexp_x y` (or `dexp_xᵀ y`) joint by joint ([`JointType::dexp`](super::JointType)),
/// `x` and `y` of length `nv`: the integrators' map from the derivative of the exponential
/// coordinates to the body velocity.
pub(crate) fn dexp(model: &Model, x: &[f64], y: &[f64], transpose: bool, out: &mut [f64]) {
    for j in model.joints() {
        let r = j.dofs();
        j.kind
            .dexp(&x[r.clone()], &y[r.clone()], transpose, &mut out[r]);
    }
}

/// `out = dexp_x⁻¹ y` (or `dexp_x⁻ᵀ y`) joint by joint.
pub(crate) fn dexp_inv(model: &Model, x: &[f64], y: &[f64], transpose: bool, out: &mut [f64]) {
    for j in model.joints() {
        let r = j.dofs();
        j.kind
            .dexp_inv(&x[r.clone()], &y[r.clone()], transpose, &mut out[r]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multibody::JointType;
    use crate::spatial::Vec3;

    /// `d/ds log(q₀⁻¹ (q₀ exp(x) exp(s η)))|₀ = dexp⁻¹_{-x} η`: checked by central differences
    /// through `integrate` and `difference` on every joint type of a free-flyer + spherical +
    /// planar + revolute model.
    #[test]
    fn dexp_matches_finite_differences_of_integrate() {
        use crate::mass::SpatialInertia;
        use crate::multibody::ModelBuilder;
        use crate::spatial::Transform;
        let mut b = ModelBuilder::new("lie");
        let g = SpatialInertia::zero();
        let root = b
            .add_joint(None, "f", JointType::FreeFlyer, Transform::identity(), g)
            .unwrap();
        let s = b
            .add_joint(
                Some(root),
                "s",
                JointType::Spherical,
                Transform::identity(),
                g,
            )
            .unwrap();
        let p = b
            .add_joint(Some(s), "p", JointType::Planar, Transform::identity(), g)
            .unwrap();
        b.add_joint(
            Some(p),
            "r",
            JointType::Revolute { axis: Vec3::z() },
            Transform::identity(),
            g,
        )
        .unwrap();
        let model = b.build().unwrap();
        let mut rng = Rng::new(5);
        let nv = model.nv();
        let q0 = crate::multibody::random_configuration(&model, &mut rng);
        let x: Vec<f64> = (0..nv).map(|_| rng.uniform(-0.8, 0.8)).collect();
        let eta: Vec<f64> = (0..nv).map(|_| rng.uniform(-1.0, 1.0)).collect();
        let mut q1 = vec![0.0; model.nq()];
        integrate(&model, &q0, &x, 1.0, &mut q1).unwrap();
        let eps = 1e-6;
        let (mut qp, mut qm) = (vec![0.0; model.nq()], vec![0.0; model.nq()]);
        integrate(&model, &q1, &eta, eps, &mut qp).unwrap();
        integrate(&model, &q1, &eta, -eps, &mut qm).unwrap();
        let (mut xp, mut xm) = (vec![0.0; nv], vec![0.0; nv]);
        difference(&model, &q0, &qp, &mut xp).unwrap();
        difference(&model, &q0, &qm, &mut xm).unwrap();
        let fd: Vec<f64> = (0..nv).map(|i| (xp[i] - xm[i]) / (2.0 * eps)).collect();
        let minus_x: Vec<f64> = x.iter().map(|v| -v).collect();
        let mut z = vec![0.0; nv];
        dexp_inv(&model, &minus_x, &eta, false, &mut z);
        let err = fd
            .iter()
            .zip(&z)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(
            err < 1e-8,
            "dexp⁻¹ vs finite differences: {err:e}\n{fd:?}\n{z:?}"
        );
        // dexp ∘ dexp⁻¹ = 1, and the transpose pairs: ⟨dexpᵀ μ, η⟩ = ⟨μ, dexp η⟩
        let mut back = vec![0.0; nv];
        dexp(&model, &minus_x, &z, false, &mut back);
        assert!(back.iter().zip(&eta).all(|(a, b)| (a - b).abs() < 1e-14));
        let mu: Vec<f64> = (0..nv).map(|_| rng.uniform(-1.0, 1.0)).collect();
        let (mut a, mut c) = (vec![0.0; nv], vec![0.0; nv]);
        dexp(&model, &x, &mu, true, &mut a);
        dexp(&model, &x, &eta, false, &mut c);
        let lhs: f64 = a.iter().zip(&eta).map(|(a, b)| a * b).sum();
        let rhs: f64 = mu.iter().zip(&c).map(|(a, b)| a * b).sum();
        assert!((lhs - rhs).abs() < 1e-14, "{lhs} {rhs}");
    }
}
