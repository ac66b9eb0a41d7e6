//! Identities of the spatial algebra over random inputs.

use proptest::prelude::*;
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::spatial::{skew, so3, Mat3, Mat6, Transform, Twist, Vec3, Wrench};

fn vec3(r: f64) -> impl Strategy<Value = Vec3> {
    (-r..r, -r..r, -r..r).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}
fn twist() -> impl Strategy<Value = Twist> {
    (vec3(3.0), vec3(3.0)).prop_map(|(w, v)| Twist::new(w, v))
}
fn wrench() -> impl Strategy<Value = Wrench> {
    (vec3(3.0), vec3(3.0)).prop_map(|(m, f)| Wrench::new(m, f))
}
/// Rotations with angle up to π, including angles within 1e-9 of 0 and π.
fn rotation() -> impl Strategy<Value = Mat3> {
    let angle = prop_oneof![
        0.0..std::f64::consts::PI,
        (0.0..1e-6f64),
        (0.0..1e-6f64).prop_map(|e| std::f64::consts::PI - e),
    ];
    (vec3(1.0), angle).prop_filter_map("axis", |(a, t)| {
        (a.norm() > 1e-3).then(|| so3::from_axis_angle(&a, t).unwrap())
    })
}
fn transform() -> impl Strategy<Value = Transform> {
    (rotation(), vec3(2.0)).prop_map(|(r, p)| Transform::new(r, p))
}
/// A physical spatial inertia: random mass, CoM and principal moments `(B+C, A+C, A+B)` from
/// second moments `A = ∫x² dm` etc., so the triangle inequality holds, in rotated axes.
fn spatial_inertia() -> impl Strategy<Value = SpatialInertia> {
    (
        0.1..10.0f64,
        vec3(1.0),
        rotation(),
        0.01..2.0f64,
        0.01..2.0f64,
        0.01..2.0f64,
    )
        .prop_map(|(m, c, r, a, b, cc)| {
            let i = RotationalInertia::diagonal(b + cc, a + cc, a + b).rotated_by(&r);
            SpatialInertia::from_com(m, c, i)
        })
}

proptest! {
    #[test]
    fn so3_exp_log_round_trip(r in rotation()) {
        let back = so3::exp(&so3::log(&r));
        prop_assert!((back - r).amax() < 1e-12, "{r} -> {back}");
    }

    #[test]
    fn se3_exp_of_log_is_identity(t in transform()) {
        let back = Transform::exp(&t.log());
        prop_assert!((back.rotation - t.rotation).amax() < 1e-12);
        prop_assert!((back.translation - t.translation).amax() < 1e-9);
    }

    #[test]
    fn se3_log_of_small_exp_is_identity(v in twist(), s in 1e-9..1.0f64) {
        let v = v * (s / v.norm().max(1e-300));
        prop_assert!((Transform::exp(&v).log() - v).norm() < 1e-12);
    }

    #[test]
    fn adjoint_of_product_is_product_of_adjoints(a in transform(), b in transform()) {
        prop_assert!(((a * b).adjoint() - a.adjoint() * b.adjoint()).amax() < 1e-12);
    }

    #[test]
    fn adjoint_conjugates_the_twist_bracket(t in transform(), v in twist()) {
        // [Ad_T V] = T [V] T⁻¹ as 4x4 matrices.
        let hat = |x: &Twist| {
            let mut m = nalgebra::Matrix4::zeros();
            m.fixed_view_mut::<3, 3>(0, 0).copy_from(&skew(&x.w));
            m.fixed_view_mut::<3, 1>(0, 3).copy_from(&x.v);
            m
        };
        let lhs = hat(&t.act_twist(&v));
        let rhs = t.to_homogeneous() * hat(&v) * t.inverse().to_homogeneous();
        prop_assert!((lhs - rhs).amax() < 1e-12);
        prop_assert!((t.adjoint() * v.to_vector() - t.act_twist(&v).to_vector()).amax() < 1e-12);
        prop_assert!((t.inverse().adjoint() - t.adjoint().try_inverse().unwrap()).amax() < 1e-9);
        prop_assert!((t.inv_act_twist(&t.act_twist(&v)) - v).norm() < 1e-12);
    }

    #[test]
    fn ad_is_antisymmetric_and_matches_its_matrix(a in twist(), b in twist(), f in wrench()) {
        prop_assert!((a.cross(&b) + b.cross(&a)).norm() < 1e-12);
        prop_assert!(a.cross(&a).norm() < 1e-12);
        prop_assert!((a.ad() * b.to_vector() - a.cross(&b).to_vector()).amax() < 1e-12);
        prop_assert!((a.ad().transpose() * f.to_vector() - a.ad_transpose(&f).to_vector()).amax() < 1e-12);
    }

    #[test]
    fn power_is_the_same_in_every_frame(t in transform(), v in twist(), f in wrench()) {
        // V_a = Ad_{T_ab} V_b and F_a = Ad_{T_ab}⁻ᵀ F_b.
        let (va, fa) = (t.act_twist(&v), t.act_wrench(&f));
        prop_assert!((va.dot(&fa) - v.dot(&f)).abs() < 1e-10);
        prop_assert!((t.adjoint().transpose() * fa.to_vector() - f.to_vector()).amax() < 1e-10);
        prop_assert!((t.inv_act_wrench(&fa) - f).norm() < 1e-10);
    }

    #[test]
    fn spatial_inertia_via_ad_equals_closed_form(g in spatial_inertia(), t_ba in transform()) {
        // G_a = Ad_{T_ba}ᵀ G_b Ad_{T_ba}; closed form about a point with CoM c_a.
        let g_a = g.transformed(&t_ba.inverse());
        let ad = t_ba.adjoint();
        let via_ad = ad.transpose() * g.matrix() * ad;
        prop_assert!((g_a.matrix() - via_ad).amax() < 1e-9);
        let c = g_a.com();
        let ic = g_a.inertia_com().matrix() * 1.0;
        let m = g_a.mass();
        let k = skew(&c);
        let mut closed = Mat6::zeros();
        closed.fixed_view_mut::<3, 3>(0, 0).copy_from(&(ic + k.transpose() * k * m));
        closed.fixed_view_mut::<3, 3>(0, 3).copy_from(&(k * m));
        closed.fixed_view_mut::<3, 3>(3, 0).copy_from(&(k.transpose() * m));
        closed.fixed_view_mut::<3, 3>(3, 3).copy_from(&(Mat3::identity() * m));
        prop_assert!((g_a.matrix() - closed).amax() < 1e-9);
        prop_assert!((g_a.inv_transformed(&t_ba.inverse()).matrix() - g.matrix()).amax() < 1e-9);
    }

    #[test]
    fn kinetic_energy_is_the_same_in_every_frame(g in spatial_inertia(), t_ab in transform(), v_b in twist()) {
        let g_a = g.transformed(&t_ab);
        let v_a = t_ab.act_twist(&v_b);
        let (ka, kb) = (g_a.kinetic_energy(&v_a), g.kinetic_energy(&v_b));
        prop_assert!((ka - kb).abs() < 1e-9 * kb.max(1.0));
        prop_assert!((g.momentum(&v_b).to_vector() - g.matrix() * v_b.to_vector()).amax() < 1e-9);
    }

    #[test]
    fn steiner_there_and_back_is_identity(g in spatial_inertia(), q in vec3(2.0)) {
        let i = g.inertia_com();
        let back = i.steiner_from_com(g.mass(), &q).steiner_to_com(g.mass(), &q);
        prop_assert!((back.matrix() - i.matrix()).amax() < 1e-12);
    }

    #[test]
    fn principal_axes_diagonalise_the_inertia(g in spatial_inertia()) {
        let i = g.inertia_com();
        let (l, r) = i.principal();
        prop_assert!(l[0] <= l[1] && l[1] <= l[2]);
        prop_assert!((r.transpose() * r - Mat3::identity()).amax() < 1e-12);
        prop_assert!((r.determinant() - 1.0).abs() < 1e-12);
        let d = r.transpose() * i.matrix() * r;
        prop_assert!((d - Mat3::from_diagonal(&l)).amax() < 1e-9 * l[2]);
        prop_assert!(i.validate(1e-9).is_ok());
    }

    #[test]
    fn rpy_and_quaternion_round_trip(r in rotation()) {
        let (a, b, c) = so3::to_rpy(&r);
        prop_assert!((so3::from_rpy(a, b, c) - r).amax() < 1e-9);
        let q = so3::to_quaternion(&r);
        prop_assert!((so3::from_quaternion(q[0], q[1], q[2], q[3], 1e-9).unwrap() - r).amax() < 1e-12);
    }
}

#[test]
fn so3_log_near_pi_keeps_the_axis() {
    let axis = Vec3::new(1.0, 2.0, -2.0) / 3.0;
    for eps in [0.0, 1e-12, 1e-8, 1e-5, 1e-3] {
        let w = axis * (std::f64::consts::PI - eps);
        let back = so3::log(&so3::exp(&w));
        // At exactly π, ±axis are both valid logarithms.
        let err = (back - w).norm().min(if eps == 0.0 {
            (back + w).norm()
        } else {
            f64::MAX
        });
        assert!(err < 1e-7, "eps {eps}: {back} vs {w}");
    }
}

#[test]
fn inertia_validation_names_the_failure() {
    use rigid::error::InertiaError;
    let not_psd = RotationalInertia::diagonal(1.0, 1.0, -0.5);
    assert!(matches!(
        not_psd.validate(1e-9),
        Err(InertiaError::NotPositiveSemiDefinite { .. })
    ));
    let triangle = RotationalInertia::diagonal(1.0, 1.0, 3.0);
    assert!(matches!(
        triangle.validate(1e-9),
        Err(InertiaError::TriangleInequality { .. })
    ));
    let rod = RotationalInertia::diagonal(0.0, 1.0, 1.0); // a thin rod is the limiting case
    assert!(rod.validate(1e-9).is_ok());
    let asym = Mat3::new(1.0, 0.1, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0);
    assert!(matches!(
        RotationalInertia::from_matrix(&asym),
        Err(InertiaError::NotSymmetric { .. })
    ));
    assert!(matches!(
        SpatialInertia::from_com(
            -1.0,
            Vec3::zeros(),
            RotationalInertia::diagonal(1.0, 1.0, 1.0)
        )
        .validate(1e-9),
        Err(InertiaError::BadMass { .. })
    ));
}
