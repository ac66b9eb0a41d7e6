//! The product of exponentials for a chain given by screw axes alone (Lynch & Park ch. 4–5):
//! the form the textbook, its code library and its capstone use when there is no robot file,
//! only `M` and the body screw axes `B_i` (or the space screw axes `S_i`).
//!
//! | notes | code | source |
//! | --- | --- | --- |
//! | `T(θ) = M e^{[B_1]θ_1} ⋯ e^{[B_n]θ_n}` | [`fkin_body`] | Lynch & Park eq. 4.16, `FKinBody` |
//! | `T(θ) = e^{[S_1]θ_1} ⋯ e^{[S_n]θ_n} M` | [`fkin_space`] | eq. 4.14, `FKinSpace` |
//! | `J_bi = [Ad_{e^{-[B_n]θ_n} ⋯ e^{-[B_{i+1}]θ_{i+1}}}] B_i` | [`jacobian_body`] | eq. 5.18, `JacobianBody` |
//! | `J_si = [Ad_{e^{[S_1]θ_1} ⋯ e^{[S_{i-1}]θ_{i-1}}}] S_i` | [`jacobian_space`] | eq. 5.11, `JacobianSpace` |
//!
//! For a robot file, the same quantities come from [`crate::multibody`] (`forward_kinematics`,
//! `jacobian`).

use crate::error::DimensionError;
use crate::spatial::{Transform, Twist};
use nalgebra::DMatrix;

fn check(axes: &[Twist], theta: &[f64]) -> Result<(), DimensionError> {
    if axes.len() != theta.len() {
        return Err(DimensionError {
            what: "theta",
            expected: axes.len(),
            got: theta.len(),
        });
    }
    Ok(())
}

/// `T(θ) = M e^{[B_1]θ_1} ⋯ e^{[B_n]θ_n}` (Lynch & Park eq. 4.16): the end-effector pose for the
/// home pose `M` and the screw axes `B_i` in the end-effector frame.
///
/// ```
/// use rigid::kinematics::poe::fkin_body;
/// use rigid::spatial::{Transform, Twist, Vec3};
/// // one revolute joint about z, the end effector 1 m out along x: B = (0,0,1, 0,1,0)
/// let m = Transform::from_translation(Vec3::new(1.0, 0.0, 0.0));
/// let b = [Twist::new(Vec3::z(), Vec3::y())];
/// let t = fkin_body(&m, &b, &[std::f64::consts::FRAC_PI_2]).unwrap();
/// assert!((t.translation - Vec3::new(0.0, 1.0, 0.0)).norm() < 1e-15);
/// ```
///
/// # Errors
/// [`DimensionError`] when `theta` and `Blist` differ in length.
pub fn fkin_body(
    M: &Transform,
    Blist: &[Twist],
    theta: &[f64],
) -> Result<Transform, DimensionError> {
    check(Blist, theta)?;
    Ok(Blist
        .iter()
        .zip(theta)
        .fold(*M, |t, (b, &q)| t * Transform::exp(&(*b * q))))
}

/// `T(θ) = e^{[S_1]θ_1} ⋯ e^{[S_n]θ_n} M` (Lynch & Park eq. 4.14), the screw axes `S_i` in the
/// space frame.
///
/// # Errors
/// [`DimensionError`] when `theta` and `Slist` differ in length.
pub fn fkin_space(
    M: &Transform,
    Slist: &[Twist],
    theta: &[f64],
) -> Result<Transform, DimensionError> {
    check(Slist, theta)?;
    Ok(Slist
        .iter()
        .zip(theta)
        .rev()
        .fold(*M, |t, (s, &q)| Transform::exp(&(*s * q)) * t))
}

/// The body Jacobian `J_b(θ)` (6 × n, angular rows first; Lynch & Park eq. 5.18): column `i` is
/// `[Ad_{e^{-[B_n]θ_n} ⋯ e^{-[B_{i+1}]θ_{i+1}}}] B_i`, so that `V_b = J_b θ̇`.
///
/// # Errors
/// [`DimensionError`] when `theta` and `Blist` differ in length.
pub fn jacobian_body(Blist: &[Twist], theta: &[f64]) -> Result<DMatrix<f64>, DimensionError> {
    check(Blist, theta)?;
    let n = Blist.len();
    let mut j = DMatrix::zeros(6, n);
    let mut t = Transform::identity();
    for i in (0..n).rev() {
        j.column_mut(i)
            .copy_from(&t.act_twist(&Blist[i]).to_vector());
        t = t * Transform::exp(&(Blist[i] * -theta[i]));
    }
    Ok(j)
}

/// The space Jacobian `J_s(θ)` (6 × n; Lynch & Park eq. 5.11): column `i` is
/// `[Ad_{e^{[S_1]θ_1} ⋯ e^{[S_{i-1}]θ_{i-1}}}] S_i`, so that `V_s = J_s θ̇`.
///
/// # Errors
/// [`DimensionError`] when `theta` and `Slist` differ in length.
pub fn jacobian_space(Slist: &[Twist], theta: &[f64]) -> Result<DMatrix<f64>, DimensionError> {
    check(Slist, theta)?;
    let mut j = DMatrix::zeros(6, Slist.len());
    let mut t = Transform::identity();
    for (i, (s, &q)) in Slist.iter().zip(theta).enumerate() {
        j.column_mut(i).copy_from(&t.act_twist(s).to_vector());
        t = t * Transform::exp(&(*s * q));
    }
    Ok(j)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spatial::Vec3;

    /// A 3R arm in both forms: `M e^{[B]θ} = e^{[S]θ} M` with `S_i = [Ad_M] B_i`, and
    /// `J_s = [Ad_T] J_b`; each Jacobian column against a central difference of the pose.
    #[test]
    fn body_and_space_forms_agree_and_the_jacobian_is_the_derivative() {
        let m = Transform::new(
            crate::spatial::so3::from_rpy(0.3, -0.2, 0.7),
            Vec3::new(0.4, -0.1, 0.9),
        );
        let b = [
            Twist::new(Vec3::z(), Vec3::new(0.0, 0.3, 0.0)),
            Twist::new(-Vec3::y(), Vec3::new(-0.5, 0.0, 0.1)),
            Twist::new(Vec3::x(), Vec3::new(0.0, 0.2, -0.4)),
        ];
        let s: Vec<Twist> = b.iter().map(|bi| m.act_twist(bi)).collect();
        let theta = [0.4, -1.1, 2.3];
        let tb = fkin_body(&m, &b, &theta).unwrap();
        let ts = fkin_space(&m, &s, &theta).unwrap();
        assert!((tb.to_homogeneous() - ts.to_homogeneous()).norm() < 1e-14);
        let jb = jacobian_body(&b, &theta).unwrap();
        let js = jacobian_space(&s, &theta).unwrap();
        assert!((tb.adjoint() * &jb - &js).norm() < 1e-13);
        let h = 1e-6;
        for i in 0..3 {
            let (mut p, mut q) = (theta, theta);
            p[i] += h;
            q[i] -= h;
            let tp = fkin_body(&m, &b, &p).unwrap();
            let tq = fkin_body(&m, &b, &q).unwrap();
            // body twist of the motion: log(T⁻¹ T(θ + h e_i)) / h, centrally
            let d = ((tb.inverse() * tp).log() - (tb.inverse() * tq).log()) * (0.5 / h);
            let col: Vec<f64> = jb.column(i).iter().copied().collect();
            assert!((d.to_vector() - crate::spatial::Vec6::from_column_slice(&col)).norm() < 1e-8);
        }
        assert!(fkin_body(&m, &b, &[0.0]).is_err());
    }
}
