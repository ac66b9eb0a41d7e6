//! Lagrange's equations from energies, by automatic differentiation.
//!
//! Write the kinetic energy `K(q, q̇)` and the potential energy `U(q)` once, generically over the
//! scalar type ([`Lagrangian`]); the equations of motion
//!
//! `M(q) q̈ + c(q, q̇) + g(q) = τ`
//!
//! follow from `L = K - U` (Lynch & Park §8.1; notes 002): `M = ∂²K/∂q̇²` (the Hessian of `K` in
//! `q̇`; `K` is quadratic in `q̇`), `c = (∂²K/∂q̇∂q) q̇ - ∂K/∂q` (Coriolis and centrifugal terms,
//! from `d/dt ∂K/∂q̇ = M q̈ + (∂²K/∂q̇∂q) q̇`), `g = ∂U/∂q`. The derivatives are exact: second
//! derivatives by hyper-dual numbers ([`num_dual::HyperDual64`]: `ε₁ ε₂` carries the mixed
//! second derivative), first derivatives by dual numbers ([`num_dual::Dual64`]).

mod rod;

pub use rod::RodOnPivot;

use super::BodyError;
use nalgebra::{SMatrix, SVector};
use num_dual::{Dual64, DualNum, HyperDual64};

/// The scalar types the energies are written over: `f64` and the dual numbers of `num-dual`.
pub trait Scalar: DualNum<Primitive = f64> + Copy {}
impl<T: DualNum<Primitive = f64> + Copy> Scalar for T {}

/// A mechanical system with `N` generalized coordinates, given by its energies.
pub trait Lagrangian<const N: usize> {
    /// Kinetic energy `K(q, q̇)` (J), quadratic in `q̇`.
    fn kinetic_energy<D: Scalar>(&self, q: &[D; N], qd: &[D; N]) -> D;
    /// Potential energy `U(q)` (J).
    fn potential_energy<D: Scalar>(&self, q: &[D; N]) -> D;
}

/// The terms of `M(q) q̈ + c(q, q̇) + g(q) = τ` at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EquationsOfMotion<const N: usize> {
    /// `M(q) = ∂²K/∂q̇²`, symmetric.
    pub mass_matrix: SMatrix<f64, N, N>,
    /// `c(q, q̇) = (∂²K/∂q̇∂q) q̇ - ∂K/∂q`.
    pub coriolis: SVector<f64, N>,
    /// `g(q) = ∂U/∂q`.
    pub gravity: SVector<f64, N>,
}

impl<const N: usize> EquationsOfMotion<N> {
    /// The generalized force `τ = M q̈ + c + g` that produces `q̈`.
    #[must_use]
    pub fn force(&self, qdd: &SVector<f64, N>) -> SVector<f64, N> {
        self.mass_matrix * qdd + self.coriolis + self.gravity
    }

    /// `q̈ = M⁻¹ (τ - c - g)`, by Cholesky.
    ///
    /// # Errors
    /// [`BodyError::SingularMassMatrix`] if `M` is not positive definite.
    pub fn acceleration(&self, tau: &SVector<f64, N>) -> Result<SVector<f64, N>, BodyError> {
        let chol = self
            .mass_matrix
            .cholesky()
            .ok_or(BodyError::SingularMassMatrix)?;
        Ok(chol.solve(&(tau - self.coriolis - self.gravity)))
    }
}

fn real<D: Scalar, const N: usize>(x: &SVector<f64, N>) -> [D; N] {
    std::array::from_fn(|i| D::from(x[i]))
}

/// `M(q)`, `c(q, q̇)` and `g(q)` of `system` by automatic differentiation:
/// `N(N+1)/2 + N` hyper-dual evaluations of `K` and `N` dual evaluations each of `K` and `U`.
#[must_use]
pub fn equations_of_motion<L: Lagrangian<N>, const N: usize>(
    system: &L,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
) -> EquationsOfMotion<N> {
    let mut mass_matrix = SMatrix::<f64, N, N>::zeros();
    let mut coriolis = SVector::<f64, N>::zeros();
    let mut gravity = SVector::<f64, N>::zeros();
    let qh: [HyperDual64; N] = real(q);
    for i in 0..N {
        // M_ij = ∂²K/∂q̇_i∂q̇_j: ε₁ on q̇_i, ε₂ on q̇_j.
        for j in i..N {
            let mut v: [HyperDual64; N] = real(qd);
            v[i].eps1 = 1.0;
            v[j].eps2 = 1.0;
            let k = system.kinetic_energy(&qh, &v).eps1eps2;
            mass_matrix[(i, j)] = k;
            mass_matrix[(j, i)] = k;
        }
        // Σ_k ∂²K/∂q̇_i∂q_k q̇_k: ε₁ on q̇_i, ε₂ on q along the direction q̇.
        let mut v: [HyperDual64; N] = real(qd);
        v[i].eps1 = 1.0;
        let mut qq = qh;
        for (k, qk) in qq.iter_mut().enumerate() {
            qk.eps2 = qd[k];
        }
        let mixed = system.kinetic_energy(&qq, &v).eps1eps2;
        // ∂K/∂q_i and ∂U/∂q_i: ε on q_i.
        let mut qdual: [Dual64; N] = real(q);
        qdual[i].eps = 1.0;
        let dk = system.kinetic_energy(&qdual, &real(qd)).eps;
        coriolis[i] = mixed - dk;
        gravity[i] = system.potential_energy(&qdual).eps;
    }
    EquationsOfMotion {
        mass_matrix,
        coriolis,
        gravity,
    }
}

/// The total energy `K + U` at `(q, q̇)`.
#[must_use]
pub fn energy<L: Lagrangian<N>, const N: usize>(
    system: &L,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
) -> f64 {
    let (q, qd): ([f64; N], [f64; N]) = (real(q), real(qd));
    system.kinetic_energy(&q, &qd) + system.potential_energy(&q)
}

/// `q̈` from `M q̈ + c + g = τ`.
///
/// # Errors
/// [`BodyError::SingularMassMatrix`] at a coordinate singularity.
pub fn acceleration<L: Lagrangian<N>, const N: usize>(
    system: &L,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
    tau: &SVector<f64, N>,
) -> Result<SVector<f64, N>, BodyError> {
    equations_of_motion(system, q, qd).acceleration(tau)
}

/// One classical RK4 step of `q̇ = v`, `v̇ = M⁻¹ (τ(t, q, v) - c - g)` in generalized
/// coordinates; returns `(q, q̇)` at `t + h`.
///
/// # Errors
/// [`BodyError::SingularMassMatrix`] if a stage hits a coordinate singularity,
/// [`BodyError::NonFinite`] if the result is not finite.
pub fn rk4_step<L: Lagrangian<N>, const N: usize>(
    system: &L,
    t: f64,
    q: &SVector<f64, N>,
    qd: &SVector<f64, N>,
    h: f64,
    tau: impl Fn(f64, &SVector<f64, N>, &SVector<f64, N>) -> SVector<f64, N>,
) -> Result<(SVector<f64, N>, SVector<f64, N>), BodyError> {
    let f = |t: f64, q: &SVector<f64, N>, v: &SVector<f64, N>| {
        acceleration(system, q, v, &tau(t, q, v))
    };
    let a1 = f(t, q, qd)?;
    let (q2, v2) = (q + qd * (0.5 * h), qd + a1 * (0.5 * h));
    let a2 = f(t + 0.5 * h, &q2, &v2)?;
    let (q3, v3) = (q + v2 * (0.5 * h), qd + a2 * (0.5 * h));
    let a3 = f(t + 0.5 * h, &q3, &v3)?;
    let (q4, v4) = (q + v3 * h, qd + a3 * h);
    let a4 = f(t + h, &q4, &v4)?;
    let q1 = q + (qd + (v2 + v3) * 2.0 + v4) * (h / 6.0);
    let v1 = qd + (a1 + (a2 + a3) * 2.0 + a4) * (h / 6.0);
    if q1.iter().chain(v1.iter()).all(|x| x.is_finite()) {
        Ok((q1, v1))
    } else {
        Err(BodyError::NonFinite {
            what: "generalized state",
        })
    }
}

/// The zero generalized force, for [`rk4_step`] without actuation.
#[must_use]
pub fn no_force<const N: usize>(
    _t: f64,
    _q: &SVector<f64, N>,
    _qd: &SVector<f64, N>,
) -> SVector<f64, N> {
    SVector::zeros()
}
