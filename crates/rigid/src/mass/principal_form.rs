//! A spatial inertia stored for cheap re-expression in other frames: mass, centre of mass, and
//! the central inertia through its principal axes as a scalar plus two rank-one terms.

use super::SpatialInertia;
use crate::spatial::{Mat3, ModelVec3, Vec3};

/// `G = (m, c, I_c)` with the central inertia written through its principal moments
/// `λ₁ ≤ λ₂ ≤ λ₃` and axes `a_k` (the spectral theorem, `I_c = Σ λ_k a_k a_kᵀ`, and
/// `Σ a_k a_kᵀ = 1`):
///
/// `I_c = λ₁ 1 + u₂ u₂ᵀ + u₃ u₃ᵀ`,  `u_k = √(λ_k − λ₁) a_k`.
///
/// Rotating it is then two 3-vector rotations and two outer products,
/// `R I_c Rᵀ = λ₁ 1 + (R u₂)(R u₂)ᵀ + (R u₃)(R u₃)ᵀ` (30 multiplications; the 3x3 congruence
/// `(R I) Rᵀ` takes 45, Pinocchio's `Symmetric3::rotate` 34), and Steiner's shift to the new
/// origin needs only the moved centre of mass, `I_O = I_c + m([c]ᵀ[c])`. This is the form CRBA
/// uses to bring every body into its tree's root frame.
///
/// ```
/// use rigid::mass::{PrincipalForm, RotationalInertia, SpatialInertia};
/// use rigid::spatial::{Transform, Vec3};
/// let g = SpatialInertia::from_com(2.0, Vec3::new(0.1, -0.2, 0.3),
///     RotationalInertia::new(0.5, 0.4, 0.3, 0.01, -0.02, 0.03));
/// let t = Transform::new(nalgebra::Rotation3::from_euler_angles(0.3, -1.1, 0.7).into_inner(),
///     Vec3::new(0.4, 0.5, -0.6));
/// let form = PrincipalForm::new(&g).expect("a body with mass");
/// let d = form.transformed(&t).matrix() - g.transformed(&t).matrix();
/// assert!(d.amax() < 1e-14);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipalForm {
    pub(crate) mass: f64,
    pub(crate) com: ModelVec3,
    pub(crate) lambda1: f64,
    pub(crate) u2: ModelVec3,
    pub(crate) u3: ModelVec3,
}

impl PrincipalForm {
    /// The form of `g`; `None` for a body that has none or would lose digits in it (the callers
    /// then move `G` by the adjoint congruence): a non-finite entry, zero mass with a nonzero
    /// first moment `h = m c` (no centre of mass), or `m|c|²` larger than `2 max|I_O|` (a tiny
    /// mass far from the origin, where `I_c = I_O − m[c]ᵀ[c]` would cancel; a physical body
    /// never gets there, since `tr I_O = tr I_c + 2m|c|²` bounds `m|c|²` by `1.5 max|I_O|`).
    #[must_use]
    pub fn new(g: &SpatialInertia) -> Option<Self> {
        let (m, h, io) = (g.mass(), g.first_moment(), g.inertia_origin_matrix());
        let finite = m.is_finite() && h.iter().chain(io.iter()).all(|x| x.is_finite());
        if !finite || (m == 0.0 && h != Vec3::zeros()) {
            return None;
        }
        let com = if m == 0.0 { Vec3::zeros() } else { h / m };
        if (m * com.dot(&com)).abs() > 2.0 * io.amax() {
            return None;
        }
        // I_c = I_O − m[c]ᵀ[c] (for m = 0 and h = 0, I_c = I_O)
        let ic = *g.inertia_origin_matrix()
            - m * (Mat3::identity() * com.dot(&com) - com * com.transpose());
        let (lambda, axes) = super::RotationalInertia::from_matrix_unchecked(&ic).principal();
        let u = |k: usize| axes.column(k) * (lambda[k] - lambda[0]).max(0.0).sqrt();
        let (u2, u3) = (u(1), u(2));
        let finite = [m, lambda[0]].iter().all(|x| x.is_finite())
            && [com, u2, u3]
                .iter()
                .all(|v| v.iter().all(|x| x.is_finite()));
        // an exactly diagonal inertia keeps the frame axes (`RotationalInertia::principal`), so
        // its u₂, u₃ are coordinate axes, as is a centre of mass on one axis
        finite.then_some(Self {
            mass: m,
            com: ModelVec3::new(&com),
            lambda1: lambda[0],
            u2: ModelVec3::new(&u2),
            u3: ModelVec3::new(&u3),
        })
    }

    /// The inertia in a frame where this body's frame has pose `(R, p)`:
    /// `m' = m`, `c' = R c + p`, `h' = m c'`,
    /// `I'_O = λ₁ 1 + (R u₂)(R u₂)ᵀ + (R u₃)(R u₃)ᵀ + (h'·c') 1 − h' c'ᵀ`
    /// (the rotated central inertia plus Steiner's term `m([c']ᵀ[c'])`), about 86 operations.
    #[must_use]
    #[inline(always)]
    pub fn transformed(&self, t: &crate::spatial::Transform) -> SpatialInertia {
        let r = &t.rotation;
        let c = self.com.rotated(r) + t.translation;
        let (a, b) = (self.u2.rotated(r), self.u3.rotated(r));
        let h = c * self.mass;
        let d = self.lambda1 + h.dot(&c);
        let xy = a.x * a.y + b.x * b.y - h.x * c.y;
        let xz = a.x * a.z + b.x * b.z - h.x * c.z;
        let yz = a.y * a.z + b.y * b.z - h.y * c.z;
        let i = Mat3::new(
            d + a.x * a.x + b.x * b.x - h.x * c.x,
            xy,
            xz,
            xy,
            d + a.y * a.y + b.y * b.y - h.y * c.y,
            yz,
            xz,
            yz,
            d + a.z * a.z + b.z * b.z - h.z * c.z,
        );
        SpatialInertia::from_raw_parts(self.mass, h, i)
    }
}

#[cfg(test)]
mod tests {
    use super::PrincipalForm;
    use crate::mass::{RotationalInertia, SpatialInertia};
    use crate::spatial::{Transform, Vec3};
    use proptest::prelude::*;

    fn rotation(a: f64, b: f64, c: f64) -> crate::spatial::Mat3 {
        nalgebra::Rotation3::from_euler_angles(a, b, c).into_inner()
    }

    proptest! {
        /// The principal form moved by `(R, p)` equals the spatial inertia moved by
        /// `[Ad_{T⁻¹}]ᵀ G [Ad_{T⁻¹}]`, for random bodies (any mass sign, physical or not) and poses.
        #[test]
        fn transformed_equals_the_adjoint_congruence(
            m in -3.0..5.0f64, c in prop::array::uniform3(-1.0..1.0f64),
            d in prop::array::uniform3(0.0..2.0f64), o in prop::array::uniform3(-0.5..0.5f64),
            e in prop::array::uniform3(-3.2..3.2f64), p in prop::array::uniform3(-2.0..2.0f64),
        ) {
            let g = SpatialInertia::from_com(m, Vec3::from(c),
                RotationalInertia::new(d[0], d[1], d[2], o[0], o[1], o[2]));
            let t = Transform::new(rotation(e[0], e[1], e[2]), Vec3::from(p));
            let want = g.transformed(&t).matrix();
            let Some(form) = PrincipalForm::new(&g) else {
                // only a body whose m|c|² outweighs its inertia about the origin goes without
                let (mc2, io) = (m * Vec3::from(c).norm_squared(), g.inertia_origin().matrix().amax());
                prop_assert!(mc2.abs() > 2.0 * io, "no form for m = {m}, c = {c:?}");
                return Ok(());
            };
            let got = form.transformed(&t).matrix();
            let scale = 1.0 + want.amax();
            prop_assert!((got - want).amax() < 1e-13 * scale, "{got} vs {want}");
        }
    }

    proptest! {
        /// Tiny masses far from the origin (identified, non-physical parameters): either no form
        /// (the callers fall back to the adjoint congruence) or one as accurate as that.
        #[test]
        fn tiny_masses_keep_their_digits(
            m in 1e-12..1e-6f64, h in prop::array::uniform3(-1e-3..1e-3f64),
            d in prop::array::uniform3(0.01..0.2f64), e in prop::array::uniform3(-3.2..3.2f64),
        ) {
            let g = SpatialInertia::from_parts(m, Vec3::from(h), RotationalInertia::diagonal(d[0], d[1], d[2]));
            let t = Transform::new(rotation(e[0], e[1], e[2]), Vec3::new(0.2, -0.1, 0.3));
            if let Some(f) = PrincipalForm::new(&g) {
                let want = g.transformed(&t).matrix();
                prop_assert!((f.transformed(&t).matrix() - want).amax() < 1e-13 * (1.0 + want.amax()));
            }
        }
    }

    /// Non-finite entries have no form (a NaN is carried by the adjoint congruence, not lost in
    /// an eigen-decomposition).
    #[test]
    fn non_finite_bodies_have_no_form() {
        let nan = SpatialInertia::from_parts(
            1.0,
            Vec3::zeros(),
            RotationalInertia::new(1.0, 1.0, 1.0, f64::NAN, 0.0, 0.0),
        );
        assert!(PrincipalForm::new(&nan).is_none());
        let inf = SpatialInertia::from_parts(
            f64::INFINITY,
            Vec3::zeros(),
            RotationalInertia::diagonal(1.0, 1.0, 1.0),
        );
        assert!(PrincipalForm::new(&inf).is_none());
    }

    /// A diagonal inertia with the centre of mass on an axis (the usual URDF body) takes the
    /// coordinate-axis path of every vector, and still equals the adjoint congruence.
    #[test]
    fn axis_aligned_bodies_equal_the_adjoint_congruence() {
        use crate::spatial::ModelVec3;
        let t = Transform::new(rotation(0.7, -0.4, 2.1), Vec3::new(0.3, -0.2, 0.5));
        for (k, com) in [
            Vec3::zeros(),
            Vec3::new(0.0, -0.3, 0.0),
            Vec3::new(0.0, 0.0, 0.25),
        ]
        .iter()
        .enumerate()
        {
            let g =
                SpatialInertia::from_com(1.5, *com, RotationalInertia::diagonal(0.2, 0.05, 0.21));
            let f = PrincipalForm::new(&g).expect("a form");
            assert!(matches!(f.com, ModelVec3::Axis(..)), "case {k}");
            assert!(matches!(f.u2, ModelVec3::Axis(..)) && matches!(f.u3, ModelVec3::Axis(..)));
            let d = (f.transformed(&t).matrix() - g.transformed(&t).matrix()).amax();
            assert!(d < 1e-15, "case {k}: {d:e}");
        }
    }

    /// Zero mass: `h = 0` keeps a form (a pure rotational inertia), `h ≠ 0` has none; a diagonal
    /// inertia keeps the frame axes exactly.
    #[test]
    fn massless_bodies_and_exact_diagonals() {
        let g = SpatialInertia::from_parts(
            0.0,
            Vec3::zeros(),
            RotationalInertia::diagonal(1.0, 2.0, 3.0),
        );
        let t = Transform::new(rotation(0.1, 0.2, 0.3), Vec3::new(1.0, 2.0, 3.0));
        let f = PrincipalForm::new(&g).expect("a form");
        assert!((f.transformed(&t).matrix() - g.transformed(&t).matrix()).amax() < 1e-14);
        let bad =
            SpatialInertia::from_parts(0.0, Vec3::x(), RotationalInertia::diagonal(1.0, 2.0, 3.0));
        assert!(PrincipalForm::new(&bad).is_none());
        let diag = SpatialInertia::from_com(
            2.0,
            Vec3::zeros(),
            RotationalInertia::diagonal(1.0, 2.0, 3.0),
        );
        let f = PrincipalForm::new(&diag).expect("a form");
        assert!((f.transformed(&Transform::identity()).matrix() - diag.matrix()).amax() < 1e-15);
    }
}
