//! Lagrange's equations by automatic differentiation, checked on the rod on a spherical pivot of
//! the notes 002: against the closed form, against Euler's equations about the pivot, and
//! against the pivot simulator along a whole trajectory.

use nalgebra::Vector2;
use proptest::prelude::*;
use rigid::body::lagrange::{self, equations_of_motion, Lagrangian, RodOnPivot, Scalar};
use rigid::body::{euler_moment, Integrator, Simulator};
use rigid::mass::RotationalInertia;
use rigid::spatial::Vec3;

const ROD: RodOnPivot = RodOnPivot {
    mass: 1.5,
    length: 0.8,
    gravity: 9.81,
};

/// The closed form of 002: `(⅓mL² s²θ φ̈ + ⅔mL² sθ cθ θ̇ φ̇, ⅓mL² θ̈ - ⅓mL² sθ cθ φ̇² + mg(L/2) sθ)`.
fn closed_form(
    r: &RodOnPivot,
    q: &Vector2<f64>,
    qd: &Vector2<f64>,
    qdd: &Vector2<f64>,
) -> Vector2<f64> {
    let (m, l, g) = (r.mass, r.length, r.gravity);
    let (s, c) = q[1].sin_cos();
    let i = m * l * l / 3.0;
    Vector2::new(
        i * s * s * qdd[0] + 2.0 * i * s * c * qd[1] * qd[0],
        i * qdd[1] - i * s * c * qd[0] * qd[0] + m * g * 0.5 * l * s,
    )
}

fn state() -> impl Strategy<Value = (Vector2<f64>, Vector2<f64>, Vector2<f64>)> {
    let v2 = |r: f64| (-r..r, -r..r).prop_map(|(a, b)| Vector2::new(a, b));
    (v2(7.0), v2(5.0), v2(20.0))
}

proptest! {
    #[test]
    fn rod_lagrange_equations_equal_the_closed_form_of_the_notes((q, qd, qdd) in state()) {
        let eom = equations_of_motion(&ROD, &q, &qd);
        let lhs = eom.force(&qdd);
        let rhs = closed_form(&ROD, &q, &qd, &qdd);
        prop_assert!((lhs - rhs).norm() < 1e-12 * (1.0 + rhs.norm()), "{lhs} vs {rhs}");
        prop_assert!((eom.mass_matrix - eom.mass_matrix.transpose()).norm() == 0.0);
    }

    /// The notes' second derivation: Euler's equations about the pivot, `I_B ω̇ + ω × I_B ω`, equal
    /// the moment of gravity about the pivot when `q̈` comes from Lagrange's equations.
    #[test]
    fn rod_lagrange_acceleration_satisfies_euler_about_the_pivot((q, qd, _) in state()) {
        prop_assume!(q[1].sin().abs() > 0.1);
        let qdd = lagrange::acceleration(&ROD, &q, &qd, &Vector2::zeros()).unwrap();
        let (s, c) = q[1].sin_cos();
        let w = Vec3::new(qd[1], qd[0] * s, qd[0] * c);
        let wdot = Vec3::new(qdd[1], qdd[0] * s + qd[0] * qd[1] * c, qdd[0] * c - qd[0] * qd[1] * s);
        let i = ROD.mass * ROD.length * ROD.length / 3.0;
        let lhs = euler_moment(&RotationalInertia::diagonal(i, i, 0.0), &w, &wdot);
        let r = RodOnPivot::rotation(&q);
        let weight = r.transpose() * Vec3::new(0.0, 0.0, -ROD.mass * ROD.gravity);
        let rhs = Vec3::new(0.0, 0.0, -0.5 * ROD.length).cross(&weight);
        prop_assert!((lhs - rhs).norm() < 1e-10 * (1.0 + rhs.norm()), "{lhs} vs {rhs}");
    }
}

/// A system written once over the scalar type: a 2-D particle in a central spring, in polar
/// coordinates, whose equations are textbook: `m r̈ - m r θ̇² + k r = 0`, `m r² θ̈ + 2 m r ṙ θ̇ = 0`.
struct Polar {
    m: f64,
    k: f64,
}

impl Lagrangian<2> for Polar {
    fn kinetic_energy<D: Scalar>(&self, q: &[D; 2], qd: &[D; 2]) -> D {
        (qd[0] * qd[0] + q[0] * q[0] * qd[1] * qd[1]) * (0.5 * self.m)
    }
    fn potential_energy<D: Scalar>(&self, q: &[D; 2]) -> D {
        q[0] * q[0] * (0.5 * self.k)
    }
}

#[test]
fn autodiff_mass_matrix_coriolis_and_gravity_match_polar_coordinates() {
    let p = Polar { m: 2.0, k: 3.0 };
    let (q, qd) = (Vector2::new(1.5, 0.4), Vector2::new(-0.7, 2.0));
    let eom = equations_of_motion(&p, &q, &qd);
    let r = q[0];
    assert!((eom.mass_matrix - nalgebra::Matrix2::new(2.0, 0.0, 0.0, 2.0 * r * r)).norm() < 1e-14);
    let c = Vector2::new(-p.m * r * qd[1] * qd[1], 2.0 * p.m * r * qd[0] * qd[1]);
    assert!((eom.coriolis - c).norm() < 1e-14, "{}", eom.coriolis);
    assert!((eom.gravity - Vector2::new(p.k * r, 0.0)).norm() < 1e-14);
}

/// Integrate the rod in `(φ, θ)` by Lagrange + RK4, and the same rod as a rigid body on a pivot
/// by the SE(3) simulator (Euler's equations about the pivot); the tips follow the same path.
#[test]
fn rod_lagrangian_and_pivot_simulator_trajectories_agree() {
    let (mut q, mut qd) = (Vector2::new(0.2, 1.0), Vector2::new(2.0, 0.3));
    let h = 1e-3;
    let n = 3000;
    let body = ROD.pivot_body(1e-4).unwrap();
    let e0 = lagrange::energy(&ROD, &q, &qd);
    assert!((body.energy(&RodOnPivot::state(&q, &qd)) - e0).abs() < 1e-12);
    let mut sims = [Integrator::Rk4, Integrator::Lgvi]
        .map(|i| Simulator::new(body.clone(), RodOnPivot::state(&q, &qd), i, h).unwrap());
    let mut worst = [0.0f64; 2];
    for k in 1..=n {
        (q, qd) =
            lagrange::rk4_step(&ROD, (k - 1) as f64 * h, &q, &qd, h, lagrange::no_force).unwrap();
        let tip = ROD.tip(&q);
        for (s, w) in sims.iter_mut().zip(worst.iter_mut()) {
            let x = s.step().unwrap();
            let tip_sim = x.pose.rotation * Vec3::new(0.0, 0.0, -ROD.length);
            *w = w.max((tip_sim - tip).norm());
        }
    }
    let drift = (lagrange::energy(&ROD, &q, &qd) - e0).abs() / e0.abs();
    println!("tip distance over 3 s: RK4 {:.2e} m, variational {:.2e} m; Lagrange energy drift {drift:.2e}", worst[0], worst[1]);
    assert!(worst[0] < 1e-9, "{}", worst[0]);
    assert!(worst[1] < 1e-4, "{}", worst[1]);
    assert!(drift < 1e-8);
}

#[test]
fn rod_mass_matrix_is_singular_at_the_pole() {
    let e = lagrange::acceleration(
        &ROD,
        &Vector2::new(0.3, 0.0),
        &Vector2::new(1.0, 1.0),
        &Vector2::zeros(),
    );
    assert!(e.is_err());
}
