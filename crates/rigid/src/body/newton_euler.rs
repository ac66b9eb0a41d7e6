//! Newton-Euler equations of one rigid body, both directions, and Euler's equations.
//!
//! In a frame {b} fixed to the body, with spatial inertia `G_b`, body twist `V_b` and the wrench
//! `F_b` applied to the body (all angular first), the Newton-Euler equations read
//! (Lynch & Park eq. 8.41, notes 000):
//!
//! `F_b = G_b V̇_b - [ad_{V_b}]ᵀ G_b V_b`.
//!
//! The form is the same in every body-fixed frame: with `G_a = [Ad_{T_ba}]ᵀ G_b [Ad_{T_ba}]`,
//! `V_a = [Ad_{T_ab}] V_b` and `F_a = [Ad_{T_ba}]ᵀ F_b` the equation holds in {a} as well.

use super::BodyError;
use crate::mass::{RotationalInertia, SpatialInertia, DEFAULT_INERTIA_TOLERANCE};
use crate::spatial::{Mat3, Transform, Twist, Vec3, Wrench};
use nalgebra::Cholesky;

/// Below this ratio of smallest to largest principal moment an inertia counts as singular.
const SINGULAR_RATIO: f64 = 1e-14;

/// Inverse dynamics: the wrench `F = G V̇ - [ad_V]ᵀ G V` that gives the body twist `V` the
/// acceleration `V̇` (Lynch & Park eq. 8.41). At the CoM this is `m = I ω̇ + ω × I ω`,
/// `f = m (v̇ + ω × v)` (eqs. 8.25, 8.26).
///
/// ```
/// use rigid::body::inverse_dynamics;
/// use rigid::mass::{RotationalInertia, SpatialInertia};
/// use rigid::spatial::{Twist, Vec3};
/// let g = SpatialInertia::from_com(2.0, Vec3::zeros(), RotationalInertia::diagonal(1.0, 2.0, 3.0));
/// let v = Twist::new(Vec3::new(1.0, 1.0, 0.0), Vec3::zeros());
/// let f = inverse_dynamics(&g, &v, &Twist::zero());
/// // ω × I ω = (1, 1, 0) × (1, 2, 0) = (0, 0, 1)
/// assert!((f.m - Vec3::new(0.0, 0.0, 1.0)).norm() < 1e-15);
/// ```
#[must_use]
#[inline]
pub fn inverse_dynamics(g: &SpatialInertia, v: &Twist, vdot: &Twist) -> Wrench {
    g.momentum(vdot) - v.ad_transpose(&g.momentum(v))
}

/// Forward dynamics: `V̇ = G⁻¹ (F + [ad_V]ᵀ G V)`. Factorises `G` at each call; a simulator
/// that calls it repeatedly keeps an [`InverseInertia`].
///
/// # Errors
/// As [`InverseInertia::new`]: if the body is not physical or its CoM inertia is singular.
pub fn forward_dynamics(g: &SpatialInertia, v: &Twist, f: &Wrench) -> Result<Twist, BodyError> {
    Ok(InverseInertia::new(g)?.forward_dynamics(v, f))
}

/// The inverse `I⁻¹` of a positive-definite rotational inertia, computed once by Cholesky.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InverseRotationalInertia {
    inverse: Mat3,
}

impl InverseRotationalInertia {
    /// Factorises `I = L Lᵀ` and stores `I⁻¹`.
    ///
    /// # Errors
    /// [`BodyError::Inertia`] if `I` is not physical (non-finite, not positive semi-definite,
    /// triangle inequality), [`BodyError::SingularInertia`] if its smallest principal moment is
    /// below `1e-14` times the largest; `what` names the inertia in the message.
    pub fn new(inertia: &RotationalInertia, what: &'static str) -> Result<Self, BodyError> {
        inertia.validate(DEFAULT_INERTIA_TOLERANCE)?;
        let l = inertia.principal_moments();
        let singular = || BodyError::SingularInertia {
            what,
            smallest: l[0],
            largest: l[2],
        };
        if l[0].is_nan() || l[0] <= SINGULAR_RATIO * l[2] {
            return Err(singular());
        }
        let chol = Cholesky::new(*inertia.matrix()).ok_or_else(singular)?;
        let inv = chol.inverse();
        Ok(Self {
            inverse: (inv + inv.transpose()) * 0.5,
        })
    }

    /// `I⁻¹ x`.
    #[must_use]
    #[inline]
    pub fn solve(&self, x: &Vec3) -> Vec3 {
        self.inverse * x
    }

    /// The matrix `I⁻¹`.
    #[must_use]
    #[inline]
    pub fn matrix(&self) -> &Mat3 {
        &self.inverse
    }
}

/// `G⁻¹` of a spatial inertia, by the Schur complement of its mass block.
///
/// With `G = [[I_O, m[c]], [m[c]ᵀ, m 1]]`, solving `G (α, β) = (n, f)` gives
/// `α = I_c⁻¹ (n - c × f)` and `β = f/m + c × α`, where `I_c = I_O - m[c]ᵀ[c]` is the inertia
/// about the CoM: the Schur complement of `m 1` is the CoM inertia. So `G` is positive definite
/// exactly when `m > 0` and `I_c` is, and one 3x3 Cholesky factorisation does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InverseInertia {
    inertia: SpatialInertia,
    mass: f64,
    com: Vec3,
    inv_ic: InverseRotationalInertia,
}

impl InverseInertia {
    /// Factorises `G`.
    ///
    /// # Errors
    /// [`BodyError::Inertia`] if the body is not physical (mass not positive, non-finite,
    /// CoM inertia not positive semi-definite); [`BodyError::SingularInertia`] if the CoM
    /// inertia is singular.
    pub fn new(g: &SpatialInertia) -> Result<Self, BodyError> {
        g.validate(DEFAULT_INERTIA_TOLERANCE)?;
        Ok(Self {
            inertia: *g,
            mass: g.mass(),
            com: g.com(),
            inv_ic: InverseRotationalInertia::new(&g.inertia_com(), "inertia about the CoM")?,
        })
    }

    /// The factorised spatial inertia `G`.
    #[must_use]
    #[inline]
    pub fn inertia(&self) -> &SpatialInertia {
        &self.inertia
    }

    /// `G⁻¹ F`, read as the twist `(α, β)` with `α = I_c⁻¹ (n - c × f)`, `β = f/m + c × α`.
    #[must_use]
    #[inline]
    pub fn solve(&self, f: &Wrench) -> Twist {
        let alpha = self.inv_ic.solve(&(f.m - self.com.cross(&f.f)));
        Twist::new(alpha, f.f / self.mass + self.com.cross(&alpha))
    }

    /// Forward dynamics `V̇ = G⁻¹ (F + [ad_V]ᵀ G V)`.
    #[must_use]
    #[inline]
    pub fn forward_dynamics(&self, v: &Twist, f: &Wrench) -> Twist {
        self.solve(&(*f + v.ad_transpose(&self.inertia.momentum(v))))
    }
}

/// Euler's equations `m = I ω̇ + ω × I ω` (notes 002): the moment about the CoM when `I` is the
/// inertia about the CoM, or the moment about a point fixed both in the body and in the world
/// (a pivot) when `I` is the inertia about that point, `I_O = I_c + m[c]ᵀ[c]`. All in body axes.
#[must_use]
#[inline]
pub fn euler_moment(inertia: &RotationalInertia, w: &Vec3, wdot: &Vec3) -> Vec3 {
    inertia.mul_vec(wdot) + w.cross(&inertia.mul_vec(w))
}

/// Euler's equations solved for the angular acceleration: `ω̇ = I⁻¹ (m - ω × I ω)`, about the
/// CoM or about a fixed point (see [`euler_moment`]).
#[must_use]
#[inline]
pub fn euler_acceleration(
    inertia: &RotationalInertia,
    inverse: &InverseRotationalInertia,
    w: &Vec3,
    moment: &Vec3,
) -> Vec3 {
    inverse.solve(&(moment - w.cross(&inertia.mul_vec(w))))
}

/// The gravity wrench on the body in its own frame {b}: the force `f_b = m R_sbᵀ g_s` applied at
/// the CoM `c_b`, so `F_b = (c_b × f_b, f_b)`. `g_s` is the gravity acceleration in the world
/// (e.g. `[0, 0, -9.81]` m/s²), `pose` is `T_sb`.
#[must_use]
#[inline]
pub fn gravity_wrench(g: &SpatialInertia, pose: &Transform, gravity: &Vec3) -> Wrench {
    Wrench::from_force_at(pose.rotation.tr_mul(gravity) * g.mass(), &g.com())
}

/// The wrench in the body frame {b} of a force `f_s` (world axes) applied at the world point
/// `p_s`: with `f_b = Rᵀ f_s` and `r_b = T_sb⁻¹ p_s`, `F_b = (r_b × f_b, f_b)`.
#[must_use]
#[inline]
pub fn world_force_at_point(pose: &Transform, f_s: &Vec3, p_s: &Vec3) -> Wrench {
    Wrench::from_force_at(pose.rotation.tr_mul(f_s), &pose.inv_act_point(p_s))
}
