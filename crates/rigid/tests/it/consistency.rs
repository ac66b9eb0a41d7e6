//! Physical consistency (Wensing, Kim & Slotine 2017): the pseudo-inertia of a real mass
//! distribution is positive definite, it transforms by congruence with the homogeneous matrix,
//! consistency is the strict triangle inequality, and the repair is the nearest consistent body,
//! the same in every frame.

use proptest::prelude::*;
use rigid::mass::{
    nearest_consistent, Consistency, Mat4, RotationalInertia, SpatialInertia, Verdict,
};
use rigid::spatial::{so3, Transform, Vec3};

fn vec3(r: f64) -> impl Strategy<Value = Vec3> {
    (-r..r, -r..r, -r..r).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn transform() -> impl Strategy<Value = Transform> {
    (vec3(3.0), vec3(1.0)).prop_map(|(w, p)| Transform::new(so3::exp(&w), p))
}

/// A body made of 2 to 6 point masses: its parameters come from a mass distribution.
fn point_masses() -> impl Strategy<Value = Vec<(f64, Vec3)>> {
    prop::collection::vec((0.1..3.0f64, vec3(0.5)), 2..7)
}

/// The spatial inertia of point masses about the frame origin.
fn of_points(points: &[(f64, Vec3)]) -> SpatialInertia {
    points
        .iter()
        .map(|(m, p)| SpatialInertia::from_com(*m, *p, RotationalInertia::zero()))
        .fold(SpatialInertia::zero(), |a, b| a + b)
}

/// `J = Σ m [p; 1][p; 1]ᵀ`, computed directly from the points.
fn pseudo_of_points(points: &[(f64, Vec3)]) -> Mat4 {
    let mut j = Mat4::zeros();
    for (m, p) in points {
        let x = nalgebra::Vector4::new(p.x, p.y, p.z, 1.0);
        j += x * x.transpose() * *m;
    }
    j
}

proptest! {
    #[test]
    fn pseudo_inertia_is_the_second_moment_of_the_homogeneous_point(pts in point_masses()) {
        let g = of_points(&pts);
        let j = g.pseudo_inertia();
        prop_assert!((j - pseudo_of_points(&pts)).amax() < 1e-12);
        let back = SpatialInertia::from_pseudo_inertia(&j);
        prop_assert!((back.matrix() - g.matrix()).amax() < 1e-12);
    }

    #[test]
    fn pseudo_inertia_transforms_by_congruence(pts in point_masses(), t in transform()) {
        // G_a = [Ad_{T_ba}]ᵀ G_b [Ad_{T_ba}]  <=>  J_a = T_ab J_b T_abᵀ
        let g = of_points(&pts);
        let h = t.to_homogeneous();
        let lhs = g.transformed(&t).pseudo_inertia();
        let rhs = h * g.pseudo_inertia() * h.transpose();
        prop_assert!((lhs - rhs).amax() < 1e-10 * rhs.amax().max(1.0));
    }

    #[test]
    fn a_mass_distribution_is_consistent(pts in point_masses(), t in transform()) {
        // four or more points not in a plane: J positive definite in every frame
        prop_assume!(pts.len() >= 4);
        let g = of_points(&pts);
        let smallest = g.pseudo_inertia().symmetric_eigen().eigenvalues.min();
        prop_assume!(smallest > 1e-6);
        prop_assert_eq!(Consistency::of(&g).verdict(), Verdict::Consistent);
        prop_assert_eq!(Consistency::of(&g.transformed(&t)).verdict(), Verdict::Consistent);
    }

    #[test]
    fn consistency_is_the_strict_triangle_inequality(
        l in (0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64), w in vec3(3.0), c in vec3(0.3), m in 0.5..5.0f64,
    ) {
        let r = so3::exp(&w);
        let i = RotationalInertia::diagonal(l.0, l.1, l.2).rotated_by(&r);
        let g = SpatialInertia::from_com(m, c, i);
        let mut s = [l.0, l.1, l.2];
        s.sort_by(f64::total_cmp);
        let margin = s[0] + s[1] - s[2];
        prop_assume!(margin.abs() > 1e-6);
        let v = Consistency::of(&g).verdict();
        if margin > 0.0 {
            prop_assert_eq!(v, Verdict::Consistent);
            prop_assert!(g.pseudo_inertia().symmetric_eigen().eigenvalues.min() > 0.0);
        } else {
            prop_assert_eq!(v, Verdict::TriangleInequality);
            prop_assert!(g.pseudo_inertia().symmetric_eigen().eigenvalues.min() < 0.0);
        }
    }

    #[test]
    fn the_repair_is_consistent_nearest_and_frame_independent(
        l in (-0.5..1.0f64, 0.0..1.0f64, 0.0..1.0f64), w in vec3(3.0), c in vec3(0.3),
        m in 0.5..5.0f64, t in transform(),
    ) {
        let i = RotationalInertia::diagonal(l.0, l.1, l.2).rotated_by(&so3::exp(&w));
        let g = SpatialInertia::from_com(m, c, i);
        let fixed = nearest_consistent(&g, Some(1e-4)).unwrap();
        prop_assert_eq!(Consistency::of(&fixed).verdict(), Verdict::Consistent);
        prop_assert!((fixed.mass() - m).abs() < 1e-12);
        prop_assert!((fixed.com() - c).norm() < 1e-12);
        // the same repair computed in another frame
        let there = nearest_consistent(&g.transformed(&t), Some(1e-4)).unwrap();
        prop_assert!((there.matrix() - fixed.transformed(&t).matrix()).amax() < 1e-9);
        // nearest: no other second moment Σ ⪰ δ 1 is closer to the given one; try 50 of them,
        // some made by nudging the repair itself
        let s = g.second_moment_com();
        let d = (fixed.second_moment_com() - s).norm();
        for k in 0..50 {
            let kf = k as f64;
            let r = so3::exp(&(w * (0.1 * kf).cos() + Vec3::new(0.0, 0.0, 0.05 * kf)));
            let e = Vec3::new((1.3 * kf).sin().abs(), (0.7 * kf).cos().abs(), 0.3) * 0.02;
            let nudge = r * nalgebra::Matrix3::from_diagonal(&e) * r.transpose();
            let candidate = fixed.second_moment_com() + nudge * (0.1 * kf);
            let other = if k % 2 == 0 {
                candidate
            } else {
                r * nalgebra::Matrix3::from_diagonal(&(e * 10.0 + Vec3::repeat(1e-4))) * r.transpose()
            };
            prop_assert!((other - s).norm() >= d - 1e-12);
        }
        // a consistent body far from the boundary is left as it is
        let ok = SpatialInertia::from_com(m, c, RotationalInertia::diagonal(0.3, 0.4, 0.5));
        let same = nearest_consistent(&ok, Some(1e-4)).unwrap();
        prop_assert!((same.matrix() - ok.matrix()).amax() < 1e-12);
    }
}

#[test]
fn round_off_is_told_from_a_defect() {
    // iCub's head: a product of 2.4e-35 on a zero inertia, CoM 0.11 m from the origin
    let i = RotationalInertia::new(0.0, 0.0, 0.0, 0.0, 2.40741e-35, 0.0);
    let head = SpatialInertia::from_com(1.33687, Vec3::new(0.0185, -0.1108, 6.78454e-18), i);
    assert_eq!(Consistency::of(&head).verdict(), Verdict::RoundOff);
    // TIAGo's antenna: a real defect
    let i = RotationalInertia::new(2.371e-8, 2.833e-8, 3.849e-8, 6.119e-8, 1.179e-8, 7.74e-9);
    let antenna = SpatialInertia::from_com(1e-6, Vec3::zeros(), i);
    assert_eq!(
        Consistency::of(&antenna).verdict(),
        Verdict::NotPositiveSemiDefinite
    );
    // a point mass is degenerate, a massless frame is fine, a negative mass is not
    let point = SpatialInertia::from_com(1.0, Vec3::x(), RotationalInertia::zero());
    assert_eq!(Consistency::of(&point).verdict(), Verdict::Degenerate);
    assert_eq!(
        Consistency::of(&SpatialInertia::zero()).verdict(),
        Verdict::Massless
    );
    let negative = SpatialInertia::from_com(-1.0, Vec3::zeros(), RotationalInertia::zero());
    assert_eq!(Consistency::of(&negative).verdict(), Verdict::BadMass);
}
