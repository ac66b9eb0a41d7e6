//! Rigid-body configurations `T = (R, p) ∈ SE(3)` and their action on points, twists and wrenches.

use super::{mat3_tr_vec, mat3_vec, skew, so3, Mat3, Mat6, Twist, Vec3, Wrench};
use std::ops::Mul;

/// A rigid transformation `T_ab = (R, p)`: the pose of frame {b} seen from frame {a}.
///
/// A point with coordinates `x_b` in {b} has coordinates `x_a = R x_b + p` in {a}, and
/// `T_ab * T_bc = T_ac`. The rotation is a plain `Matrix3`, kept orthonormal by every operation
/// here (composition, inverse, exp), which is what the algorithms multiply with.
///
/// ```
/// use rigid::spatial::{so3, Transform, Vec3};
/// let t_ab = Transform::new(so3::from_rpy(0.0, 0.0, 0.5), Vec3::new(1.0, 2.0, 3.0));
/// let t_ba = t_ab.inverse();
/// assert!((t_ab * t_ba).is_identity(1e-15));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Transform {
    /// The rotation `R_ab` (columns: the axes of {b} in {a}).
    #[cfg_attr(feature = "serde", serde(with = "super::wire::mat3"))]
    pub rotation: Mat3,
    /// The translation `p_ab` (the origin of {b} in {a}).
    #[cfg_attr(feature = "serde", serde(with = "super::wire::vec3"))]
    pub translation: Vec3,
}

impl Default for Transform {
    fn default() -> Self {
        Self::identity()
    }
}

impl Transform {
    /// `T = (R, p)`. The caller guarantees that `R` is a rotation (see [`so3::check`]).
    #[must_use]
    #[inline]
    pub fn new(rotation: Mat3, translation: Vec3) -> Self {
        Self {
            rotation,
            translation,
        }
    }

    /// The identity `(I, 0)`.
    #[must_use]
    #[inline]
    pub fn identity() -> Self {
        Self::new(Mat3::identity(), Vec3::zeros())
    }

    /// A pure translation `(I, p)`.
    #[must_use]
    #[inline]
    pub fn from_translation(p: Vec3) -> Self {
        Self::new(Mat3::identity(), p)
    }

    /// A pure rotation `(R, 0)`.
    #[must_use]
    #[inline]
    pub fn from_rotation(r: Mat3) -> Self {
        Self::new(r, Vec3::zeros())
    }

    /// The URDF `<origin xyz rpy>` transform.
    #[must_use]
    pub fn from_xyz_rpy(xyz: [f64; 3], rpy: [f64; 3]) -> Self {
        Self::new(so3::from_rpy(rpy[0], rpy[1], rpy[2]), Vec3::from(xyz))
    }

    /// The 4x4 homogeneous matrix `[[R, p], [0, 1]]`.
    #[must_use]
    pub fn to_homogeneous(&self) -> nalgebra::Matrix4<f64> {
        let mut m = nalgebra::Matrix4::identity();
        m.fixed_view_mut::<3, 3>(0, 0).copy_from(&self.rotation);
        m.fixed_view_mut::<3, 1>(0, 3).copy_from(&self.translation);
        m
    }

    /// `T⁻¹ = (Rᵀ, -Rᵀ p)`.
    #[must_use]
    #[inline]
    pub fn inverse(&self) -> Self {
        let rt = self.rotation.transpose();
        Self::new(rt, -(rt * self.translation))
    }

    /// Whether `T` is the identity to within `tol` in every entry.
    #[must_use]
    pub fn is_identity(&self, tol: f64) -> bool {
        (self.rotation - Mat3::identity()).amax() <= tol && self.translation.amax() <= tol
    }

    /// The point `x_a = R x_b + p`.
    #[must_use]
    #[inline]
    pub fn act_point(&self, x_b: &Vec3) -> Vec3 {
        mat3_vec(&self.rotation, x_b) + self.translation
    }

    /// The point `x_b = Rᵀ (x_a - p)`.
    #[must_use]
    #[inline]
    pub fn inv_act_point(&self, x_a: &Vec3) -> Vec3 {
        mat3_tr_vec(&self.rotation, &(x_a - self.translation))
    }

    /// `[Ad_T] = [[R, 0], [[p]R, R]]` (Lynch & Park, Def. 3.20), the 6x6 matrix with
    /// `V_a = [Ad_{T_ab}] V_b`.
    #[must_use]
    pub fn adjoint(&self) -> Mat6 {
        let r = &self.rotation;
        let mut ad = Mat6::zeros();
        ad.fixed_view_mut::<3, 3>(0, 0).copy_from(r);
        ad.fixed_view_mut::<3, 3>(3, 3).copy_from(r);
        ad.fixed_view_mut::<3, 3>(3, 0)
            .copy_from(&(skew(&self.translation) * r));
        ad
    }

    /// `V_a = [Ad_{T_ab}] V_b`: `ω_a = R ω_b`, `v_a = R v_b + p × R ω_b`.
    #[must_use]
    #[inline]
    pub fn act_twist(&self, v_b: &Twist) -> Twist {
        let w = mat3_vec(&self.rotation, &v_b.w);
        Twist::new(
            w,
            mat3_vec(&self.rotation, &v_b.v) + self.translation.cross(&w),
        )
    }

    /// `V_b = [Ad_{T_ab}]⁻¹ V_a = [Ad_{T_ba}] V_a`: `ω_b = Rᵀ ω_a`, `v_b = Rᵀ (v_a - p × ω_a)`.
    #[must_use]
    #[inline]
    pub fn inv_act_twist(&self, v_a: &Twist) -> Twist {
        let r = &self.rotation;
        Twist::new(
            mat3_tr_vec(r, &v_a.w),
            mat3_tr_vec(r, &(v_a.v - self.translation.cross(&v_a.w))),
        )
    }

    /// `F_a = [Ad_{T_ab}]⁻ᵀ F_b = [Ad_{T_ba}]ᵀ F_b`: `f_a = R f_b`, `m_a = R m_b + p × R f_b`
    /// (the same wrench, expressed in {a} and taken about its origin).
    #[must_use]
    #[inline]
    pub fn act_wrench(&self, f_b: &Wrench) -> Wrench {
        let f = mat3_vec(&self.rotation, &f_b.f);
        Wrench::new(
            mat3_vec(&self.rotation, &f_b.m) + self.translation.cross(&f),
            f,
        )
    }

    /// `F_b = [Ad_{T_ab}]ᵀ F_a`: `f_b = Rᵀ f_a`, `m_b = Rᵀ (m_a - p × f_a)`.
    #[must_use]
    #[inline]
    pub fn inv_act_wrench(&self, f_a: &Wrench) -> Wrench {
        let r = &self.rotation;
        Wrench::new(
            mat3_tr_vec(r, &(f_a.m - self.translation.cross(&f_a.f))),
            mat3_tr_vec(r, &f_a.f),
        )
    }

    /// `exp([S]θ)` of the twist `S θ = (ω, v)` (Lynch & Park, Prop. 3.25):
    /// `R = exp([ω])`, `p = (I + (1 - cos θ)/θ² [ω] + (θ - sin θ)/θ³ [ω]²) v`, with `θ = |ω|`.
    ///
    /// ```
    /// use rigid::spatial::{Transform, Twist, Vec3};
    /// let s = Twist::new(Vec3::new(0.1, 0.2, -0.3), Vec3::new(1.0, 0.0, 2.0));
    /// let t = Transform::exp(&s);
    /// assert!((t.log() - s).norm() < 1e-12);
    /// ```
    #[must_use]
    pub fn exp(s: &Twist) -> Self {
        let theta2 = s.w.norm_squared();
        let theta = theta2.sqrt();
        let (b, c) = if theta < 1e-4 {
            (0.5 - theta2 / 24.0, 1.0 / 6.0 - theta2 / 120.0)
        } else {
            (
                (1.0 - theta.cos()) / theta2,
                (theta - theta.sin()) / (theta2 * theta),
            )
        };
        let k = skew(&s.w);
        let kv = k * s.v;
        let p = s.v + kv * b + k * kv * c;
        Self::new(so3::exp(&s.w), p)
    }

    /// `log T`: the twist `S θ` with `exp([S]θ) = T` and `|ω| ≤ π` (Lynch & Park, Alg. 3.2):
    /// `ω = log R`, `v = (I - ½[ω] + (1/θ² - (1 + cos θ)/(2θ sin θ)) [ω]²) p`.
    #[must_use]
    pub fn log(&self) -> Twist {
        let w = so3::log(&self.rotation);
        let theta2 = w.norm_squared();
        let theta = theta2.sqrt();
        let c = if theta < 1e-4 {
            1.0 / 12.0 + theta2 / 720.0
        } else {
            // (1 + cos θ)/(2 θ sin θ) = cot(θ/2) / (2θ), finite up to θ = π.
            1.0 / theta2 - 1.0 / ((theta * 0.5).tan() * 2.0 * theta)
        };
        let k = skew(&w);
        let kp = k * self.translation;
        Twist::new(w, self.translation - kp * 0.5 + k * kp * c)
    }
}

impl Mul for Transform {
    type Output = Transform;
    /// `T_ab * T_bc = T_ac = (R_ab R_bc, R_ab p_bc + p_ab)`.
    #[inline]
    fn mul(self, rhs: Transform) -> Transform {
        Transform::new(
            self.rotation * rhs.rotation,
            self.rotation * rhs.translation + self.translation,
        )
    }
}

impl Mul<&Transform> for &Transform {
    type Output = Transform;
    #[inline]
    fn mul(self, rhs: &Transform) -> Transform {
        *self * *rhs
    }
}
