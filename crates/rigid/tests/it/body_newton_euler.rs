//! Newton-Euler equations of one body: both directions, frame independence, power, Euler's
//! equations about the CoM and about a pivot, and the errors for non-physical bodies.

use proptest::prelude::*;
use rigid::body::{
    euler_moment, forward_dynamics, gravity_wrench, inverse_dynamics, world_force_at_point,
    BodyError, InverseInertia, RigidBody, State,
};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::spatial::{so3, Mat3, Transform, Twist, Vec3, Wrench};

fn vec3(r: f64) -> impl Strategy<Value = Vec3> {
    (-r..r, -r..r, -r..r).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}
fn twist() -> impl Strategy<Value = Twist> {
    (vec3(3.0), vec3(3.0)).prop_map(|(w, v)| Twist::new(w, v))
}
fn wrench() -> impl Strategy<Value = Wrench> {
    (vec3(3.0), vec3(3.0)).prop_map(|(m, f)| Wrench::new(m, f))
}
fn rotation() -> impl Strategy<Value = Mat3> {
    (vec3(1.0), 0.0..std::f64::consts::PI).prop_filter_map("axis", |(a, t)| {
        (a.norm() > 1e-3).then(|| so3::from_axis_angle(&a, t).unwrap())
    })
}
fn transform() -> impl Strategy<Value = Transform> {
    (rotation(), vec3(2.0)).prop_map(|(r, p)| Transform::new(r, p))
}
/// A physical CoM inertia: principal moments `(B+C, A+C, A+B)` from second moments, rotated.
fn inertia_com() -> impl Strategy<Value = RotationalInertia> {
    (rotation(), 0.05..2.0f64, 0.05..2.0f64, 0.05..2.0f64)
        .prop_map(|(r, a, b, c)| RotationalInertia::diagonal(b + c, a + c, a + b).rotated_by(&r))
}
/// A body in a random frame: mass, CoM anywhere, inertia in rotated axes.
fn spatial_inertia() -> impl Strategy<Value = SpatialInertia> {
    (0.1..10.0f64, vec3(1.0), inertia_com()).prop_map(|(m, c, i)| SpatialInertia::from_com(m, c, i))
}

fn close(a: &Wrench, b: &Wrench, tol: f64) -> bool {
    (*a - *b).norm() <= tol * (1.0 + a.norm().max(b.norm()))
}

proptest! {
    #[test]
    fn forward_dynamics_inverts_inverse_dynamics(g in spatial_inertia(), v in twist(), a in twist()) {
        let f = inverse_dynamics(&g, &v, &a);
        let back = forward_dynamics(&g, &v, &f).unwrap();
        prop_assert!((back - a).norm() < 1e-9 * (1.0 + a.norm()), "{a:?} -> {back:?}");
    }

    #[test]
    fn inverse_dynamics_inverts_forward_dynamics(g in spatial_inertia(), v in twist(), f in wrench()) {
        let a = forward_dynamics(&g, &v, &f).unwrap();
        prop_assert!(close(&inverse_dynamics(&g, &v, &a), &f, 1e-9));
    }

    #[test]
    fn inverse_inertia_solves_the_6x6_system(g in spatial_inertia(), f in wrench()) {
        let x = InverseInertia::new(&g).unwrap().solve(&f);
        let lhs = g.matrix() * x.to_vector();
        prop_assert!((lhs - f.to_vector()).norm() < 1e-9 * (1.0 + f.norm()));
    }

    /// The notes' "the form of the dynamics is independent of the frame": in {a}, with
    /// `G_a = Ad_{T_ca}ᵀ G_c Ad_{T_ca}`, `V_a = Ad_{T_ac} V_c`, the wrench is the CoM one moved by
    /// `F_a = Ad_{T_ca}ᵀ F_c`.
    #[test]
    fn twist_wrench_form_in_any_frame_equals_com_form_moved_by_ad(
        m in 0.1..10.0f64, i in inertia_com(), t_ac in transform(), v_c in twist(), a_c in twist()
    ) {
        let g_c = SpatialInertia::from_com(m, Vec3::zeros(), i);
        // The CoM form: m = I ω̇ + ω × I ω, f = m (v̇ + ω × v).
        let f_c = Wrench::new(
            i.mul_vec(&a_c.w) + v_c.w.cross(&i.mul_vec(&v_c.w)),
            (a_c.v + v_c.w.cross(&v_c.v)) * m,
        );
        prop_assert!(close(&inverse_dynamics(&g_c, &v_c, &a_c), &f_c, 1e-12));
        let g_a = g_c.transformed(&t_ac);
        let (v_a, a_a) = (t_ac.act_twist(&v_c), t_ac.act_twist(&a_c));
        let f_a = inverse_dynamics(&g_a, &v_a, &a_a);
        prop_assert!(close(&f_a, &t_ac.act_wrench(&f_c), 1e-10));
    }

    /// `dK/dt = Vᵀ G V̇ = Fᵀ V` because `Vᵀ [ad_V]ᵀ G V = (ad_V V)ᵀ G V = 0`.
    #[test]
    fn power_of_the_wrench_is_the_rate_of_kinetic_energy(g in spatial_inertia(), v in twist(), f in wrench()) {
        let a = forward_dynamics(&g, &v, &f).unwrap();
        let dk = v.dot(&g.momentum(&a)); // d/dt ½VᵀGV with G constant in the body frame
        prop_assert!((dk - v.dot(&f)).abs() < 1e-9 * (1.0 + v.norm() * f.norm()));
        // and by a central difference of K along the motion V(t) = V + t V̇
        let h = 1e-6;
        let fd = (g.kinetic_energy(&(v + a * h)) - g.kinetic_energy(&(v - a * h))) / (2.0 * h);
        prop_assert!((fd - v.dot(&f)).abs() < 1e-5 * (1.0 + v.norm() * f.norm() + a.norm().powi(2)));
    }

    /// On a pivot (`v = 0`, `v̇ = 0` at the origin of {b}), the moment part of the twist-wrench form
    /// is Euler's equation about the fixed point, `I_O ω̇ + ω × I_O ω`.
    #[test]
    fn euler_about_a_fixed_point_is_the_twist_wrench_form_without_translation(
        g in spatial_inertia(), w in vec3(3.0), wdot in vec3(3.0)
    ) {
        let f = inverse_dynamics(&g, &Twist::new(w, Vec3::zeros()), &Twist::new(wdot, Vec3::zeros()));
        let e = euler_moment(&g.inertia_origin(), &w, &wdot);
        prop_assert!((f.m - e).norm() < 1e-10 * (1.0 + e.norm()));
    }

    /// The gravity wrench is the force `m g` at the CoM, in body axes.
    #[test]
    fn gravity_wrench_is_the_weight_at_the_com(g in spatial_inertia(), t in transform()) {
        let gs = Vec3::new(0.0, 0.0, -9.81);
        let fg = gravity_wrench(&g, &t, &gs);
        let at_com = world_force_at_point(&t, &(gs * g.mass()), &t.act_point(&g.com()));
        prop_assert!(close(&fg, &at_com, 1e-12));
        prop_assert!((t.rotation * fg.f - gs * g.mass()).norm() < 1e-12);
    }
}

#[test]
fn forward_dynamics_rejects_non_physical_bodies() {
    let i = RotationalInertia::diagonal(1.0, 1.0, 3.0); // 1 + 1 < 3
    let bad = SpatialInertia::from_com(1.0, Vec3::zeros(), i);
    let e = forward_dynamics(&bad, &Twist::zero(), &Wrench::zero()).unwrap_err();
    assert!(matches!(e, BodyError::Inertia(_)), "{e}");
    let massless = SpatialInertia::from_com(
        0.0,
        Vec3::zeros(),
        RotationalInertia::diagonal(1.0, 1.0, 1.0),
    );
    assert!(matches!(
        InverseInertia::new(&massless),
        Err(BodyError::Inertia(_))
    ));
    let rod = SpatialInertia::from_com(
        1.0,
        Vec3::zeros(),
        RotationalInertia::diagonal(1.0, 1.0, 0.0),
    );
    assert!(matches!(
        InverseInertia::new(&rod),
        Err(BodyError::SingularInertia { .. })
    ));
    let nan = SpatialInertia::from_com(
        f64::NAN,
        Vec3::zeros(),
        RotationalInertia::diagonal(1.0, 1.0, 1.0),
    );
    assert!(InverseInertia::new(&nan).is_err());
}

#[test]
fn pivot_needs_mass_and_accepts_a_thin_rod() {
    let massless = SpatialInertia::from_com(
        0.0,
        Vec3::new(0.0, 0.0, -1.0),
        RotationalInertia::diagonal(1.0, 1.0, 1.0),
    );
    assert!(matches!(
        RigidBody::pivot(massless),
        Err(BodyError::MasslessPivot { .. })
    ));
    // A thin rod: singular about its CoM axis... but also about the pivot along the rod axis.
    let rod = SpatialInertia::from_com(
        1.0,
        Vec3::new(0.0, 0.0, -0.5),
        RotationalInertia::diagonal(1.0 / 12.0, 1.0 / 12.0, 0.0),
    );
    assert!(matches!(
        RigidBody::pivot(rod),
        Err(BodyError::SingularInertia { .. })
    ));
    let rod = SpatialInertia::from_com(
        1.0,
        Vec3::new(0.0, 0.0, -0.5),
        RotationalInertia::diagonal(1.0 / 12.0, 1.0 / 12.0, 1e-6),
    );
    let body = RigidBody::pivot(rod).unwrap();
    // Hanging still: no acceleration; tilted: gravity swings it back.
    let hanging = State::default();
    let body = body.with_gravity(Vec3::new(0.0, 0.0, -9.81)).unwrap();
    assert!(body.acceleration(0.0, &hanging).norm() < 1e-15);
    let tilted = State::new(
        Transform::from_rotation(so3::exp(&Vec3::new(0.3, 0.0, 0.0))),
        Twist::zero(),
    );
    assert!(body.acceleration(0.0, &tilted).w.x < 0.0);
}
