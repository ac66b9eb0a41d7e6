//! The rotational inertia matrix `I = ∫ρ [r]ᵀ[r] dV` of a body (Lynch & Park §8.2.1; the notes
//! 000 and 002): in rotated frames, at other points (Steiner), principal axes, validity.

use crate::error::InertiaError;
use crate::spatial::{skew, Mat3, Vec3};
use std::ops::{Add, Mul, Sub};

/// A symmetric 3x3 rotational inertia matrix (kg·m²).
///
/// Entries follow the notes: `I_xx = ∫(y² + z²) dm` on the diagonal and the products of inertia
/// **with their minus sign inside the entry**, `I_xy = -∫ x y dm`. The type can only hold a
/// symmetric matrix; whether it is physical (positive semi-definite, triangle inequality) is
/// checked by [`RotationalInertia::validate`].
///
/// ```
/// use rigid::mass::RotationalInertia;
/// use rigid::spatial::Vec3;
/// // Two 1 kg points at ±1 m on x: I = diag(0, 2, 2).
/// let i = RotationalInertia::from_point_masses(&[(1.0, Vec3::x()), (1.0, -Vec3::x())]);
/// assert_eq!(*i.matrix(), rigid::spatial::Mat3::from_diagonal(&Vec3::new(0.0, 2.0, 2.0)));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RotationalInertia(Mat3);

/// Relative tolerance used by [`RotationalInertia::validate`] (scaled by the largest moment).
pub const DEFAULT_INERTIA_TOLERANCE: f64 = 1e-9;

impl RotationalInertia {
    /// The zero inertia.
    #[must_use]
    pub fn zero() -> Self {
        Self(Mat3::zeros())
    }

    /// From the six independent entries; `ixy`, `ixz`, `iyz` are matrix entries (URDF's
    /// `<inertia ixy=...>` is the same convention).
    #[must_use]
    pub fn new(ixx: f64, iyy: f64, izz: f64, ixy: f64, ixz: f64, iyz: f64) -> Self {
        Self(Mat3::new(ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz))
    }

    /// The diagonal inertia `diag(a, b, c)` (principal axes along the frame axes).
    #[must_use]
    pub fn diagonal(a: f64, b: f64, c: f64) -> Self {
        Self(Mat3::from_diagonal(&Vec3::new(a, b, c)))
    }

    /// From a matrix that must be symmetric to within `1e-9` relative; it is symmetrised.
    ///
    /// # Errors
    /// [`InertiaError::NonFinite`] or [`InertiaError::NotSymmetric`].
    pub fn from_matrix(m: &Mat3) -> Result<Self, InertiaError> {
        if m.iter().any(|x| !x.is_finite()) {
            return Err(InertiaError::NonFinite);
        }
        let asym = (m - m.transpose()).amax();
        if asym > 1e-9 * m.amax().max(f64::MIN_POSITIVE) {
            return Err(InertiaError::NotSymmetric { asymmetry: asym });
        }
        Ok(Self::from_matrix_unchecked(m))
    }

    /// From any matrix, keeping its symmetric part `(m + mᵀ)/2`.
    #[must_use]
    pub fn from_matrix_unchecked(m: &Mat3) -> Self {
        Self((m + m.transpose()) * 0.5)
    }

    /// `Σ m_i [r_i]ᵀ[r_i] = Σ m_i (|r_i|² 1 - r_i r_iᵀ)` about the frame origin.
    #[must_use]
    pub fn from_point_masses(points: &[(f64, Vec3)]) -> Self {
        let mut i = Mat3::zeros();
        for (m, r) in points {
            i += (Mat3::identity() * r.norm_squared() - r * r.transpose()) * *m;
        }
        Self(i)
    }

    /// The matrix.
    #[must_use]
    #[inline]
    pub fn matrix(&self) -> &Mat3 {
        &self.0
    }

    /// Row-major nested arrays (the JSON layout).
    #[must_use]
    pub fn to_rows(&self) -> [[f64; 3]; 3] {
        let m = &self.0;
        [0, 1, 2].map(|r| [m[(r, 0)], m[(r, 1)], m[(r, 2)]])
    }

    /// The six independent entries `ixx, iyy, izz, ixy, ixz, iyz`: the order of URDF's
    /// `<inertia>` attributes and of MJCF's `fullinertia`.
    #[must_use]
    pub fn entries(&self) -> [f64; 6] {
        let m = &self.0;
        [
            m[(0, 0)],
            m[(1, 1)],
            m[(2, 2)],
            m[(0, 1)],
            m[(0, 2)],
            m[(1, 2)],
        ]
    }

    /// `I ω`.
    #[must_use]
    #[inline]
    pub fn mul_vec(&self, w: &Vec3) -> Vec3 {
        self.0 * w
    }

    /// The same inertia expressed in frame {c}, rotated by `R_bc` from this frame {b}:
    /// `I_c = R_bcᵀ I_b R_bc` (notes 000, "inertia in a rotated frame").
    #[must_use]
    pub fn in_rotated_frame(&self, r_bc: &Mat3) -> Self {
        Self::from_matrix_unchecked(&(r_bc.transpose() * self.0 * r_bc))
    }

    /// The inverse operation: given this inertia in {c}, express it in {b}: `R_bc I_c R_bcᵀ`.
    #[must_use]
    pub fn rotated_by(&self, r_bc: &Mat3) -> Self {
        Self::from_matrix_unchecked(&(r_bc * self.0 * r_bc.transpose()))
    }

    /// Steiner's theorem: the inertia about the point `q` (same axes) of a body of mass `m` whose
    /// CoM is at the origin and whose inertia about the CoM is `self`:
    /// `I_q = I_b + m (qᵀq 1 - q qᵀ) = I_b + m [q]ᵀ[q]`.
    #[must_use]
    pub fn steiner_from_com(&self, m: f64, q: &Vec3) -> Self {
        let k = skew(q);
        Self::from_matrix_unchecked(&(self.0 - k * k * m))
    }

    /// The inverse of [`steiner_from_com`](Self::steiner_from_com): `self` is `I_q`, the inertia
    /// about a point at `q` from the CoM (same axes); returns `I_b = I_q - m [q]ᵀ[q]`.
    #[must_use]
    pub fn steiner_to_com(&self, m: f64, q: &Vec3) -> Self {
        let k = skew(q);
        Self::from_matrix_unchecked(&(self.0 + k * k * m))
    }

    /// The principal moments in ascending order and the principal axes as the columns of a
    /// right-handed rotation `R` (`e3 = e1 × e2`), with `I = R diag(λ) Rᵀ`.
    ///
    /// When moments repeat, any orthonormal basis of their eigenspace is principal; the frame
    /// axes are preferred when they are principal, so an axisymmetric or isotropic body gets
    /// axes aligned with its frame.
    ///
    /// ```
    /// use rigid::mass::RotationalInertia;
    /// let i = RotationalInertia::new(2.0, 2.0, 1.0, 0.5, 0.0, 0.0);
    /// let (l, r) = i.principal();
    /// assert!((l - nalgebra::Vector3::new(1.0, 1.5, 2.5)).norm() < 1e-12);
    /// assert!((r * nalgebra::Matrix3::from_diagonal(&l) * r.transpose() - i.matrix()).norm() < 1e-12);
    /// ```
    #[must_use]
    pub fn principal(&self) -> (Vec3, Mat3) {
        let m = &self.0;
        let scale = m.amax();
        let off = m[(0, 1)].abs().max(m[(0, 2)].abs()).max(m[(1, 2)].abs());
        // Already diagonal: keep the frame axes (sorted), exact.
        let (vals, vecs) = if off <= 1e-15 * scale {
            (m.diagonal(), Mat3::identity())
        } else {
            let e = m.symmetric_eigen();
            (e.eigenvalues, e.eigenvectors)
        };
        let mut idx = [0usize, 1, 2];
        idx.sort_by(|&a, &b| vals[a].total_cmp(&vals[b]));
        let lambda = Vec3::new(vals[idx[0]], vals[idx[1]], vals[idx[2]]);
        let mut axes = Mat3::zeros();
        for (k, &i) in idx.iter().enumerate() {
            let mut c = vecs.column(i).normalize();
            // Deterministic sign: the largest-magnitude component positive.
            if c[c.iamax()] < 0.0 {
                c = -c;
            }
            axes.set_column(k, &c);
        }
        let e3 = axes.column(0).cross(&axes.column(1));
        axes.set_column(2, &e3);
        (lambda, axes)
    }

    /// The principal moments in ascending order.
    #[must_use]
    pub fn principal_moments(&self) -> Vec3 {
        self.principal().0
    }

    /// Checks that the inertia is physical: finite, positive semi-definite and satisfying the
    /// triangle inequality `λ1 + λ2 ≥ λ3` of its principal moments (notes 002), each to within
    /// `tol` times the largest moment.
    ///
    /// # Errors
    /// The first test that fails.
    pub fn validate(&self, tol: f64) -> Result<(), InertiaError> {
        self.validate_scaled(tol, 0.0)
    }

    /// As [`validate`](Self::validate), with the tolerance `tol × max(λ3, scale)`. Use `scale`
    /// for the size of the numbers this inertia was computed from: an inertia about the CoM
    /// obtained as `I_O - m[c]ᵀ[c]` carries rounding errors of order `ε |I_O|`, which for a point
    /// mass (`I_c = 0`) would otherwise read as a negative moment.
    ///
    /// # Errors
    /// The first test that fails.
    pub fn validate_scaled(&self, tol: f64, scale: f64) -> Result<(), InertiaError> {
        if self.0.iter().any(|x| !x.is_finite()) {
            return Err(InertiaError::NonFinite);
        }
        let l = self.principal_moments();
        let eps = tol * l[2].abs().max(scale.abs()).max(f64::MIN_POSITIVE);
        if l[0] < -eps {
            return Err(InertiaError::NotPositiveSemiDefinite { moment: l[0] });
        }
        if l[0] + l[1] < l[2] - eps {
            return Err(InertiaError::TriangleInequality {
                small_sum: l[0] + l[1],
                largest: l[2],
            });
        }
        Ok(())
    }
}

impl Add for RotationalInertia {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self(self.0 + o.0)
    }
}

impl Sub for RotationalInertia {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self(self.0 - o.0)
    }
}

impl Mul<f64> for RotationalInertia {
    type Output = Self;
    fn mul(self, s: f64) -> Self {
        Self(self.0 * s)
    }
}
