//! The 6x6 spatial inertia `G` of a rigid body (Lynch & Park §8.2.2; notes 000 and 002).

use super::RotationalInertia;
use crate::error::InertiaError;
use crate::spatial::{mat3_mul, mat3_vec, skew, Mat3, Mat6, Transform, Twist, Vec3, Wrench};
use std::ops::{Add, AddAssign};

/// The spatial inertia `G` of a rigid body in some frame {O}, angular block first:
///
/// `G_O = [[I_c + m[c]ᵀ[c], m[c]], [m[c]ᵀ, m 1]]`
///
/// where `m` is the mass, `c` the CoM in {O} and `I_c` the rotational inertia about the CoM in
/// {O}'s axes. At the CoM it is `diag(I_c, m 1)`. It maps a twist to the spatial momentum
/// `P = G V` and gives the kinetic energy `½ Vᵀ G V`.
///
/// Stored as `(m, h = m c, I_O)` with `I_O` the inertia about the origin, so that adding two
/// inertias in one frame is adding their parts, and `G V` costs two cross products and a 3x3
/// product.
///
/// ```
/// use rigid::mass::{RotationalInertia, SpatialInertia};
/// use rigid::spatial::{Transform, Twist, Vec3};
/// let g_b = SpatialInertia::from_com(2.0, Vec3::zeros(), RotationalInertia::diagonal(1.0, 2.0, 3.0));
/// let t_ba = Transform::from_translation(Vec3::new(0.0, 0.0, -1.0)); // {a} is 1 m above the CoM
/// let g_a = g_b.transformed(&t_ba.inverse()); // G_a = Ad_{T_ba}ᵀ G_b Ad_{T_ba}
/// let ad = t_ba.adjoint();
/// assert!((g_a.matrix() - ad.transpose() * g_b.matrix() * ad).norm() < 1e-12);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SpatialInertia {
    mass: f64,
    #[cfg_attr(
        feature = "serde",
        serde(rename = "first_moment", with = "crate::spatial::wire::vec3")
    )]
    h: Vec3,
    #[cfg_attr(
        feature = "serde",
        serde(rename = "inertia_origin", with = "crate::spatial::wire::mat3")
    )]
    inertia: Mat3,
}

impl SpatialInertia {
    /// The zero inertia (a massless body).
    #[must_use]
    pub fn zero() -> Self {
        Self {
            mass: 0.0,
            h: Vec3::zeros(),
            inertia: Mat3::zeros(),
        }
    }

    /// From the mass `m`, the CoM `c` in this frame and the inertia `I_c` about the CoM in this
    /// frame's axes: `G = [[I_c + m[c]ᵀ[c], m[c]], [m[c]ᵀ, m 1]]`.
    #[must_use]
    pub fn from_com(mass: f64, com: Vec3, inertia_com: RotationalInertia) -> Self {
        let k = skew(&com);
        Self {
            mass,
            h: com * mass,
            inertia: inertia_com.matrix() - k * k * mass,
        }
    }

    /// From the mass, first moment `h = m c` and rotational inertia `I_O` about the frame origin.
    #[must_use]
    pub fn from_parts(mass: f64, h: Vec3, inertia_origin: RotationalInertia) -> Self {
        Self {
            mass,
            h,
            inertia: *inertia_origin.matrix(),
        }
    }

    /// From a symmetric 6x6 matrix of the form above.
    ///
    /// # Errors
    /// If the matrix has a non-finite entry, is not symmetric, or its blocks do not have the form
    /// of a spatial inertia (lower-right `m 1`, off-diagonal `m[c]` skew).
    pub fn from_matrix(g: &Mat6) -> Result<Self, InertiaError> {
        if g.iter().any(|x| !x.is_finite()) {
            return Err(InertiaError::NonFinite);
        }
        let asym = (g - g.transpose()).amax();
        let tol = 1e-9 * g.amax().max(f64::MIN_POSITIVE);
        if asym > tol {
            return Err(InertiaError::NotSymmetric { asymmetry: asym });
        }
        let m = g[(3, 3)];
        let lower: Mat3 = g.fixed_view::<3, 3>(3, 3).into();
        let off: Mat3 = g.fixed_view::<3, 3>(0, 3).into();
        let bad_lower = (lower - Mat3::identity() * m).amax() > tol;
        let bad_off = (off + off.transpose()).amax() > tol;
        if bad_lower || bad_off {
            return Err(InertiaError::NotSymmetric { asymmetry: tol });
        }
        let i: Mat3 = g.fixed_view::<3, 3>(0, 0).into();
        Ok(Self::from_parts(
            m,
            crate::spatial::unskew(&off),
            RotationalInertia::from_matrix_unchecked(&i),
        ))
    }

    /// From the parts `(m, h, I_O)` without symmetrising `I_O` (for the multibody algorithms,
    /// whose products keep it symmetric).
    #[inline]
    pub(crate) fn from_raw_parts(mass: f64, h: Vec3, inertia_origin: Mat3) -> Self {
        Self {
            mass,
            h,
            inertia: inertia_origin,
        }
    }

    /// The rotational inertia about the frame origin as a matrix, without a copy.
    #[inline]
    pub(crate) fn inertia_origin_matrix(&self) -> &Mat3 {
        &self.inertia
    }

    /// The mass `m` (kg).
    #[must_use]
    #[inline]
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// The first moment of mass `h = m c` (kg·m).
    #[must_use]
    #[inline]
    pub fn first_moment(&self) -> Vec3 {
        self.h
    }

    /// The centre of mass `c` in this frame (zero for a massless body).
    #[must_use]
    #[inline]
    pub fn com(&self) -> Vec3 {
        if self.mass > 0.0 {
            self.h / self.mass
        } else {
            Vec3::zeros()
        }
    }

    /// The rotational inertia about the frame origin, `I_O = I_c + m[c]ᵀ[c]`.
    #[must_use]
    #[inline]
    pub fn inertia_origin(&self) -> RotationalInertia {
        RotationalInertia::from_matrix_unchecked(&self.inertia)
    }

    /// The rotational inertia about the CoM in this frame's axes, `I_c = I_O - m[c]ᵀ[c]`.
    #[must_use]
    pub fn inertia_com(&self) -> RotationalInertia {
        let c = self.com();
        let k = skew(&c);
        RotationalInertia::from_matrix_unchecked(&(self.inertia + k * k * self.mass))
    }

    /// The 6x6 matrix `[[I_O, [h]], [[h]ᵀ, m 1]]`.
    #[must_use]
    pub fn matrix(&self) -> Mat6 {
        let k = skew(&self.h);
        let mut g = Mat6::zeros();
        g.fixed_view_mut::<3, 3>(0, 0).copy_from(&self.inertia);
        g.fixed_view_mut::<3, 3>(0, 3).copy_from(&k);
        g.fixed_view_mut::<3, 3>(3, 0).copy_from(&k.transpose());
        g.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&(Mat3::identity() * self.mass));
        g
    }

    /// The spatial momentum `P = G V`: `(I_O ω + h × v, m v - h × ω)`.
    #[must_use]
    #[inline]
    pub fn momentum(&self, v: &Twist) -> Wrench {
        Wrench::new(
            mat3_vec(&self.inertia, &v.w) + self.h.cross(&v.v),
            v.v * self.mass - self.h.cross(&v.w),
        )
    }

    /// The angular momentum about the point `q` (coordinates in this frame) of the body moving
    /// with the twist `V = (ω, v)` expressed in this frame: with `P = G V = (L_O, p)`, moving the
    /// moment to `q` gives `L_q = L_O - q × p`.
    #[must_use]
    pub fn angular_momentum_about(&self, v: &Twist, q: &Vec3) -> Vec3 {
        let p = self.momentum(v);
        p.m - q.cross(&p.f)
    }

    /// The angular momentum about the CoM, `L_c = I_c ω` (it does not depend on `v`).
    #[must_use]
    pub fn angular_momentum_com(&self, v: &Twist) -> Vec3 {
        self.inertia_com().mul_vec(&v.w)
    }

    /// The kinetic energy `½ Vᵀ G V` (J).
    #[must_use]
    #[inline]
    pub fn kinetic_energy(&self, v: &Twist) -> f64 {
        0.5 * v.dot(&self.momentum(v))
    }

    /// This inertia `G_b` expressed in frame {a}, where `t_ab = (R, p)` is the pose of this frame
    /// {b} in {a}: `G_a = [Ad_{T_ba}]ᵀ G_b [Ad_{T_ba}]` (notes 000; Featherstone 2008 eq. 2.66).
    /// With `h' = R h_b` and `c_a = R c_b + p`: `h_a = h' + m p` and
    /// `I_a = R I_b Rᵀ - [h'][p] - [p][h'] - m [p]²`
    /// `= R I_b Rᵀ + 2(g·p) 1 - (p gᵀ + g pᵀ)` with `g = h' + ½ m p` (from
    /// `[x][y] = y xᵀ - (x·y) 1`), written out on the storage: the one implementation of the
    /// congruence for a spatial inertia, used by every algorithm (its specialised variant for
    /// bodies with a principal form is [`PrincipalForm::transformed`](super::PrincipalForm::transformed)).
    #[must_use]
    #[inline]
    pub fn transformed(&self, t_ab: &Transform) -> Self {
        let R = &t_ab.rotation;
        let p = &t_ab.translation;
        let m = self.mass;
        let h = mat3_vec(R, &self.h);
        let RI = mat3_mul(R, &self.inertia);
        let g = h + p * (0.5 * m);
        let d = 2.0 * g.dot(p);
        let (r, ri) = (R.as_slice(), RI.as_slice()); // column-major
        let (p, g) = ([p.x, p.y, p.z], [g.x, g.y, g.z]);
        let mut out = [0.0; 9];
        for i in 0..3 {
            for j in i..3 {
                // (R I Rᵀ)_ij = Σ_k (RI)_ik R_jk
                let rir = ri[i] * r[j] + ri[3 + i] * r[3 + j] + ri[6 + i] * r[6 + j];
                let x = rir - p[i] * g[j] - g[i] * p[j];
                out[j * 3 + i] = x;
                out[i * 3 + j] = x;
            }
            out[i * 4] += d;
        }
        Self {
            mass: m,
            h: h + t_ab.translation * m,
            inertia: Mat3::from_column_slice(&out),
        }
    }

    /// The inverse of [`transformed`](Self::transformed): this inertia is `G_a`, and `t_ab` the
    /// pose of {b} in {a}; returns `G_b = [Ad_{T_ab}]ᵀ G_a [Ad_{T_ab}]`.
    #[must_use]
    pub fn inv_transformed(&self, t_ab: &Transform) -> Self {
        self.transformed(&t_ab.inverse())
    }

    /// Checks that the body is physical: finite, mass `> 0`, and an inertia about the CoM that is
    /// positive semi-definite and satisfies the triangle inequality (relative tolerance `tol`,
    /// scaled by the largest entry of `I_O` as well, since `I_c = I_O - m[c]ᵀ[c]` is computed by
    /// a subtraction: a point mass away from the origin is valid).
    ///
    /// # Errors
    /// The first test that fails.
    pub fn validate(&self, tol: f64) -> Result<(), InertiaError> {
        if !self.mass.is_finite() || self.h.iter().any(|x| !x.is_finite()) {
            return Err(InertiaError::NonFinite);
        }
        if self.mass <= 0.0 {
            return Err(InertiaError::BadMass { mass: self.mass });
        }
        self.inertia_com().validate_scaled(tol, self.inertia.amax())
    }
}

impl Add for SpatialInertia {
    type Output = Self;
    /// The inertia of two bodies rigidly joined, both expressed in the same frame.
    #[inline]
    fn add(self, o: Self) -> Self {
        Self {
            mass: self.mass + o.mass,
            h: self.h + o.h,
            inertia: self.inertia + o.inertia,
        }
    }
}

impl AddAssign for SpatialInertia {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        self.mass += o.mass;
        self.h += o.h;
        self.inertia += o.inertia;
    }
}
