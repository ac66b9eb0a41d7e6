//! Physical consistency of a body's ten inertial parameters `(m, h = m c, Ī)`, and the nearest
//! consistent body.
//!
//! A rigid body's parameters are *physically consistent* when some mass distribution `ρ ≥ 0`
//! produces them. Wensing, Kim & Slotine ("Linear matrix inequalities for physically consistent
//! inertial parameter identification", IEEE RA-L 2017) show that this holds exactly when the 4x4
//! **pseudo-inertia**
//!
//! `J = ∫ [r; 1][r; 1]ᵀ dm = [[Σ, h], [hᵀ, m]]`, with `Σ = ∫ r rᵀ dm = ½ tr(Ī) 1 − Ī`
//!
//! is positive definite (positive semi-definite for the limits: a point, a rod, a plate). Here `Ī`
//! is the rotational inertia about the frame origin (`I_O` of [`SpatialInertia`]) and `Σ` the
//! second moment of the mass; `Ī = tr(Σ) 1 − Σ` inverts the map. About the CoM,
//! `J_c = diag(Σ_c, m)` with `Σ_c = ½ tr(I_c) 1 − I_c`, whose eigenvalues are
//! `(λ_j + λ_k − λ_i)/2` for the principal moments `λ`: `J ≻ 0` is `m > 0` with the strict
//! triangle inequalities, which imply `I_c ≻ 0` (notes 002).
//!
//! Checks come with a **round-off allowance**: an eigenvalue below zero by no more than
//! [`ROUND_OFF_ULPS`] ulps of `tr(Ī_O)` (the scale of the numbers the inertia about the CoM was
//! computed from by Steiner's theorem) is rounding, not a defect. iCub's head, an inertia of zeros
//! but for `ixz = 2.4e-35` with its CoM 0.11 m from the link origin, is such a case.

use super::{RotationalInertia, SpatialInertia};
use crate::spatial::{Mat3, Vec3};
use nalgebra::Matrix4;

/// A 4x4 matrix of `f64` (the pseudo-inertia).
pub type Mat4 = Matrix4<f64>;

/// Round-off allowance in ulps of `tr(Ī_O)`.
pub const ROUND_OFF_ULPS: f64 = 16.0;

impl SpatialInertia {
    /// The pseudo-inertia `J = [[Σ, h], [hᵀ, m]]` with `Σ = ½ tr(Ī) 1 − Ī` about this frame's
    /// origin (Wensing, Kim & Slotine 2017, eq. 6).
    ///
    /// ```
    /// use rigid::mass::{RotationalInertia, SpatialInertia};
    /// use rigid::spatial::Vec3;
    /// // a 2 kg point at (0, 0, 1): J = m [r; 1][r; 1]ᵀ
    /// let g = SpatialInertia::from_com(2.0, Vec3::z(), RotationalInertia::zero());
    /// let j = g.pseudo_inertia();
    /// assert_eq!((j[(2, 2)], j[(2, 3)], j[(3, 3)], j[(0, 0)]), (2.0, 2.0, 2.0, 0.0));
    /// assert!((SpatialInertia::from_pseudo_inertia(&j).matrix() - g.matrix()).norm() < 1e-15);
    /// ```
    #[must_use]
    pub fn pseudo_inertia(&self) -> Mat4 {
        let i = self.inertia_origin_matrix();
        let sigma = Mat3::identity() * (0.5 * i.trace()) - i;
        let h = self.first_moment();
        let mut j = Mat4::zeros();
        j.fixed_view_mut::<3, 3>(0, 0).copy_from(&sigma);
        j.fixed_view_mut::<3, 1>(0, 3).copy_from(&h);
        j.fixed_view_mut::<1, 3>(3, 0).copy_from(&h.transpose());
        j[(3, 3)] = self.mass();
        j
    }

    /// The inverse of [`pseudo_inertia`](Self::pseudo_inertia): `m = J₃₃`, `h = J₀..₃,₃`,
    /// `Ī = tr(Σ) 1 − Σ` (the symmetric part of `J` is used).
    #[must_use]
    pub fn from_pseudo_inertia(j: &Mat4) -> Self {
        let s: Mat3 = j.fixed_view::<3, 3>(0, 0).into();
        let sigma = (s + s.transpose()) * 0.5;
        let h = (j.fixed_view::<3, 1>(0, 3) + j.fixed_view::<1, 3>(3, 0).transpose()) * 0.5;
        let i = Mat3::identity() * sigma.trace() - sigma;
        Self::from_parts(
            j[(3, 3)],
            Vec3::from(h),
            RotationalInertia::from_matrix_unchecked(&i),
        )
    }

    /// The second moment of the mass about the CoM, `Σ_c = ∫ r rᵀ dm = ½ tr(I_c) 1 − I_c`.
    #[must_use]
    pub fn second_moment_com(&self) -> Mat3 {
        let i = *self.inertia_com().matrix();
        Mat3::identity() * (0.5 * i.trace()) - i
    }

    /// The round-off allowance of this body's checks: [`ROUND_OFF_ULPS`] ulps of `tr(Ī_O)`.
    #[must_use]
    pub fn round_off(&self) -> f64 {
        ROUND_OFF_ULPS * f64::EPSILON * self.inertia_origin_matrix().trace().abs()
    }
}

/// The consistency tests of one body, with the numbers that decide them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Consistency {
    /// The mass `m`.
    pub mass: f64,
    /// The principal moments of the inertia about the CoM, ascending (`λ1 ≤ λ2 ≤ λ3`).
    pub principal_moments: Vec3,
    /// The eigenvalues of `Σ_c`, ascending: `(λ1 + λ2 − λ3)/2` first; `J ≻ 0` iff `m > 0` and
    /// the first is `> 0`.
    pub second_moments: Vec3,
    /// The round-off allowance ([`SpatialInertia::round_off`]).
    pub round_off: f64,
    /// Every parameter finite.
    pub finite: bool,
}

/// One verdict of [`Consistency::verdict`], worst first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Verdict {
    /// A NaN or infinite parameter.
    NonFinite,
    /// `m < 0` (or `m = 0` with a non-zero inertia or first moment).
    BadMass,
    /// The inertia about the CoM has a negative principal moment (beyond round-off).
    NotPositiveSemiDefinite,
    /// The principal moments violate `λ1 + λ2 ≥ λ3` (beyond round-off): `J` is not PSD.
    TriangleInequality,
    /// `J` is positive semi-definite but singular beyond round-off: the mass lies on a point, a
    /// line or a plane. Attainable only in the limit; a warning.
    Degenerate,
    /// The tests fail by no more than the round-off allowance.
    RoundOff,
    /// `J ≻ 0`: physically consistent.
    Consistent,
    /// `m = 0` and nothing else: a massless frame (valid, carries nothing).
    Massless,
}

impl Consistency {
    /// The tests of `g`.
    #[must_use]
    pub fn of(g: &SpatialInertia) -> Self {
        let finite = g.mass().is_finite()
            && g.first_moment().iter().all(|x| x.is_finite())
            && g.inertia_origin_matrix().iter().all(|x| x.is_finite());
        if !finite {
            return Self {
                mass: g.mass(),
                principal_moments: Vec3::repeat(f64::NAN),
                second_moments: Vec3::repeat(f64::NAN),
                round_off: 0.0,
                finite,
            };
        }
        let l = if g.mass() > 0.0 {
            g.inertia_com().principal_moments()
        } else {
            g.inertia_origin().principal_moments()
        };
        Self {
            mass: g.mass(),
            principal_moments: l,
            second_moments: Vec3::new(
                0.5 * (l[0] + l[1] - l[2]),
                0.5 * (l[0] + l[2] - l[1]),
                0.5 * (l[1] + l[2] - l[0]),
            ),
            round_off: g.round_off(),
            finite,
        }
    }

    /// The verdict: the worst test that fails.
    #[must_use]
    pub fn verdict(&self) -> Verdict {
        if !self.finite {
            return Verdict::NonFinite;
        }
        let l = &self.principal_moments;
        if self.mass < 0.0 {
            return Verdict::BadMass;
        }
        if self.mass == 0.0 {
            return if l.iter().all(|x| *x == 0.0) {
                Verdict::Massless
            } else {
                Verdict::BadMass
            };
        }
        let eps = self.round_off;
        if l[0] < -eps {
            return Verdict::NotPositiveSemiDefinite;
        }
        if self.second_moments[0] < -eps {
            return Verdict::TriangleInequality;
        }
        if l[0] < 0.0 || self.second_moments[0] < 0.0 {
            return Verdict::RoundOff;
        }
        // singular beyond round-off: the smallest second moment is no more than the allowance
        if self.second_moments[0] <= eps {
            return Verdict::Degenerate;
        }
        Verdict::Consistent
    }

    /// `J ≻ 0`, or fails only by round-off: usable as it is.
    #[must_use]
    pub fn is_consistent(&self) -> bool {
        matches!(self.verdict(), Verdict::Consistent | Verdict::RoundOff)
    }
}

/// The nearest physically consistent body to `g` with the same mass and CoM: the second moment
/// about the CoM `Σ_c` is projected onto `{Σ ⪰ δ 1}` in the Frobenius norm (eigenvalues below `δ`
/// raised to `δ`, the exact projection), and `I_c = tr(Σ) 1 − Σ`. Keeping `m` and `c` and
/// measuring about the CoM makes the metric invariant to the frame the parameters are written
/// in (a rotation leaves `‖ΔΣ_c‖_F` unchanged; a translation does not change `Σ_c`).
///
/// `min_second_moment` is `δ` (kg·m²): `m ℓ²` for the smallest thickness `ℓ` the body may have;
/// `None` uses `10⁻⁶` of the largest eigenvalue of `Σ_c`, at least `m (10⁻⁴ m)²`.
///
/// Returns `None` when the mass is not positive and finite (no distribution of a non-positive
/// mass exists; a measured mass is needed) or a parameter is not finite.
///
/// ```
/// use rigid::mass::{nearest_consistent, Consistency, RotationalInertia, SpatialInertia, Verdict};
/// use rigid::spatial::Vec3;
/// // principal moments (1, 1, 3) violate λ1 + λ2 ≥ λ3
/// let bad = SpatialInertia::from_com(2.0, Vec3::new(0.1, 0.0, 0.0), RotationalInertia::diagonal(1.0, 1.0, 3.0));
/// assert_eq!(Consistency::of(&bad).verdict(), Verdict::TriangleInequality);
/// let fixed = nearest_consistent(&bad, None).unwrap();
/// assert_eq!(Consistency::of(&fixed).verdict(), Verdict::Consistent);
/// assert!((fixed.com() - bad.com()).norm() < 1e-15 && fixed.mass() == 2.0);
/// ```
#[must_use]
pub fn nearest_consistent(
    g: &SpatialInertia,
    min_second_moment: Option<f64>,
) -> Option<SpatialInertia> {
    let m = g.mass();
    if !(m.is_finite() && m > 0.0 && Consistency::of(g).finite) {
        return None;
    }
    let sigma = g.second_moment_com();
    let e = sigma.symmetric_eigen();
    let top = e.eigenvalues.max().max(0.0);
    let delta = min_second_moment.unwrap_or_else(|| (1e-6 * top).max(m * 1e-8));
    let clamped = e.eigenvalues.map(|x| x.max(delta));
    let s = e.eigenvectors * Mat3::from_diagonal(&clamped) * e.eigenvectors.transpose();
    let i_c = Mat3::identity() * s.trace() - s;
    Some(SpatialInertia::from_com(
        m,
        g.com(),
        RotationalInertia::from_matrix_unchecked(&i_c),
    ))
}
