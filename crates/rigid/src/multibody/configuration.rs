//! Operations on configurations: `q ⊕ v dt`, `q1 ⊖ q0`, neutral, random and normalised
//! configurations, joint by joint (Lie-group operations of each joint's configuration space).

use super::{check_q, check_v, Model, MultibodyError};
use crate::error::DimensionError;

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
    for j in &model.joints {
        let (iq, iv) = (j.idx_q..j.idx_q + j.nq, j.idx_v..j.idx_v + j.nv);
        j.kind.integrate(&q[iq.clone()], &v[iv], dt, &mut q_out[iq]);
    }
    Ok(())
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
    for j in &model.joints {
        let (iq, iv) = (j.idx_q..j.idx_q + j.nq, j.idx_v..j.idx_v + j.nv);
        j.kind.difference(&q0[iq.clone()], &q1[iq], &mut v_out[iv]);
    }
    Ok(())
}

/// The neutral configuration (zeros, identity quaternions).
#[must_use]
pub fn neutral(model: &Model) -> Vec<f64> {
    let mut q = vec![0.0; model.nq];
    for j in &model.joints {
        j.kind.neutral(&mut q[j.idx_q..j.idx_q + j.nq]);
    }
    q
}

/// A random configuration within the position limits (angles in `[-π, π]` and translations in
/// `[-1, 1]` m where a limit is infinite; uniform quaternions).
#[must_use]
pub fn random_configuration(model: &Model, rng: &mut Rng) -> Vec<f64> {
    let mut q = vec![0.0; model.nq];
    for j in &model.joints {
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

/// Normalise the quaternions in `q` (with `w ≥ 0`); other coordinates are left alone.
///
/// # Errors
/// Wrong length.
pub fn normalize(model: &Model, q: &mut [f64]) -> Result<(), MultibodyError> {
    DimensionError::check("q", model.nq, q.len())?;
    for j in &model.joints {
        j.kind.normalize(&mut q[j.idx_q..j.idx_q + j.nq]);
    }
    Ok(())
}
