//! Closed-form Lagrange equations: the rod on a spherical pivot (notes 002) as two revolute
//! joints, the built-in pendulum and double pendulum.
#![allow(non_snake_case)]

use rigid::mass::RotationalInertia;
use rigid::mass::SpatialInertia;
use rigid::multibody::*;
use rigid::spatial::{Transform, Vec3};

fn close(a: f64, b: f64, what: &str) {
    assert!(
        (a - b).abs() < 1e-12 * b.abs().max(1.0),
        "{what}: {a} vs {b}"
    );
}

/// The rod of notes 002: mass m, length L, hinged at one end. Joint `phi` turns about the world
/// vertical `z`; joint `theta` turns about the x axis of the frame rotated by φ (the axis
/// `ê_B` of the notes), both at the pivot; at θ = 0 the rod hangs along `-z`. Body frame B:
/// `ω_B = (θ̇, φ̇ sθ, φ̇ cθ)` as in the notes; inertia about the pivot `diag(⅓mL², ⅓mL², 0)` (thin
/// rod), CoM `(0, 0, -L/2)` in B.
fn rod(m: f64, L: f64, g: f64) -> Model {
    let mut b = ModelBuilder::new("rod_on_pivot");
    b.set_gravity(Vec3::new(0.0, 0.0, -g));
    let phi = b
        .add_joint(
            None,
            "phi",
            JointType::Revolute { axis: Vec3::z() },
            Transform::identity(),
            SpatialInertia::zero(),
        )
        .unwrap();
    let i = m * L * L / 3.0;
    let G = SpatialInertia::from_parts(
        m,
        Vec3::new(0.0, 0.0, -m * L / 2.0),
        RotationalInertia::diagonal(i, i, 0.0),
    );
    b.add_joint(
        Some(phi),
        "theta",
        JointType::Revolute { axis: Vec3::x() },
        Transform::identity(),
        G,
    )
    .unwrap();
    b.build().unwrap()
}

#[test]
fn rod_on_spherical_pivot_matches_the_lagrange_equations_of_notes_002() {
    let (m, L, g) = (2.0, 1.5, 9.81);
    let model = rod(m, L, g);
    let mut data = Data::new(&model);
    let mut rng = Rng::new(2);
    let k = m * L * L / 3.0;
    for _ in 0..20 {
        let (phi, th) = (rng.uniform(-3.0, 3.0), rng.uniform(0.2, 2.9));
        let (dphi, dth) = (rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0));
        let (s, c) = th.sin_cos();
        let q = [phi, th];
        let v = [dphi, dth];
        let M = crba(&model, &mut data, &q).unwrap().clone();
        close(M[(0, 0)], k * s * s, "M_φφ = ⅓mL² sθ²");
        close(M[(1, 1)], k, "M_θθ = ⅓mL²");
        close(M[(0, 1)], 0.0, "M_φθ = 0");
        let grav = gravity_torques(&model, &mut data, &q).unwrap().clone();
        close(grav[0], 0.0, "g_φ = 0");
        close(grav[1], m * g * L / 2.0 * s, "g_θ = mg(L/2) sθ");
        let nle = nonlinear_effects(&model, &mut data, &q, &v)
            .unwrap()
            .clone();
        let cvec = nle - grav;
        close(
            cvec[0],
            2.0 * k * s * c * dth * dphi,
            "c_φ = ⅔mL² sθ cθ θ̇ φ̇",
        );
        close(cvec[1], -k * s * c * dphi * dphi, "c_θ = -⅓mL² sθ cθ φ̇²");
        // the free motion (τ = 0) obeys both equations
        let a = aba(&model, &mut data, &q, &v, &[0.0, 0.0]).unwrap().clone();
        let e1 = k * a[1] - k * s * c * dphi * dphi + m * g * L / 2.0 * s;
        let e2 = k * s * s * a[0] + 2.0 * k * s * c * dth * dphi;
        assert!(e1.abs() < 1e-10 && e2.abs() < 1e-10, "{e1} {e2}");
    }
}

#[test]
fn pendulum_has_m_one_third_and_gravity_4_905_sin_q() {
    let model = pendulum();
    let mut data = Data::new(&model);
    for q in [-2.0, -0.3, 0.0, 0.7, 2.5] {
        close(
            crba(&model, &mut data, &[q]).unwrap()[(0, 0)],
            1.0 / 3.0,
            "M",
        );
        close(
            gravity_torques(&model, &mut data, &[q]).unwrap()[0],
            4.905 * q.sin(),
            "g",
        );
    }
}

#[test]
fn double_pendulum_matches_its_closed_form_lagrangian() {
    // two uniform rods m = 1, l = 1, CoM at lc = 0.5, I = m l²/12 about the CoM
    let (m, l, lc, I, g) = (1.0, 1.0, 0.5, 1.0 / 12.0, 9.81);
    let model = double_pendulum();
    let mut data = Data::new(&model);
    let mut rng = Rng::new(4);
    for _ in 0..20 {
        let q = [rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0)];
        let v = [rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0)];
        let c2 = q[1].cos();
        let M = crba(&model, &mut data, &q).unwrap().clone();
        close(
            M[(0, 0)],
            2.0 * I + m * lc * lc + m * (l * l + lc * lc + 2.0 * l * lc * c2),
            "M11",
        );
        close(M[(0, 1)], I + m * lc * lc + m * l * lc * c2, "M12");
        close(M[(1, 1)], I + m * lc * lc, "M22");
        let gr = gravity_torques(&model, &mut data, &q).unwrap().clone();
        let s12 = (q[0] + q[1]).sin();
        close(
            gr[0],
            (m * lc + m * l) * g * q[0].sin() + m * lc * g * s12,
            "g1",
        );
        close(gr[1], m * lc * g * s12, "g2");
        let h = -m * l * lc * q[1].sin();
        let cv = nonlinear_effects(&model, &mut data, &q, &v)
            .unwrap()
            .clone()
            - gr;
        close(cv[0], h * (2.0 * v[0] * v[1] + v[1] * v[1]), "c1");
        close(cv[1], -h * v[0] * v[0], "c2");
    }
}

/// Issue 4: the rod as a chain of two revolute joints (CRBA / RNEA) gives the same `M`, `c`, `g`
/// as the single-body Lagrangian of [`rigid::body::lagrange::RodOnPivot`] (energies
/// differentiated by automatic differentiation): two independent derivations of one system.
#[test]
fn rod_as_two_revolute_joints_equals_the_autodiff_lagrangian() {
    use nalgebra::Vector2;
    use rigid::body::lagrange::{equations_of_motion, RodOnPivot};
    let (m, L, g) = (1.3, 0.8, 9.81);
    let model = rod(m, L, g);
    let lagrangian = RodOnPivot {
        mass: m,
        length: L,
        gravity: g,
    };
    let mut data = Data::new(&model);
    let mut rng = Rng::new(11);
    for _ in 0..25 {
        let q = [rng.uniform(-3.0, 3.0), rng.uniform(0.1, 3.0)];
        let v = [rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0)];
        let eom = equations_of_motion(
            &lagrangian,
            &Vector2::new(q[0], q[1]),
            &Vector2::new(v[0], v[1]),
        );
        let M = crba(&model, &mut data, &q).unwrap().clone();
        let grav = gravity_torques(&model, &mut data, &q).unwrap().clone();
        let nle = nonlinear_effects(&model, &mut data, &q, &v)
            .unwrap()
            .clone();
        for i in 0..2 {
            for j in 0..2 {
                close(M[(i, j)], eom.mass_matrix[(i, j)], "M");
            }
            close(grav[i], eom.gravity[i], "g");
            close(nle[i] - grav[i], eom.coriolis[i], "c");
        }
    }
}
