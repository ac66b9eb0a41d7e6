//! The simulator on SE(3): orders of accuracy, conservation, the intermediate-axis theorem, the
//! heavy top, and clean errors on bad input.

use rigid::body::{BodyError, Integrator, RigidBody, Simulator, State};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::spatial::{so3, Mat3, Transform, Twist, Vec3, Wrench};

const G: Vec3 = Vec3::new(0.0, 0.0, -9.81);

/// An asymmetric body (principal moments 1, 2, 3 in slightly rotated axes), its frame {b} away
/// from the CoM, so the simulator runs the full twist-wrench form.
fn asymmetric() -> SpatialInertia {
    let i = RotationalInertia::diagonal(1.0, 2.0, 3.0)
        .rotated_by(&so3::exp(&Vec3::new(0.1, -0.2, 0.05)));
    SpatialInertia::from_com(2.0, Vec3::new(0.2, -0.1, 0.3), i)
}

fn start() -> State {
    State::new(
        Transform::from_xyz_rpy([0.1, 0.2, 0.3], [0.3, -0.2, 0.5]),
        Twist::new(Vec3::new(1.0, 0.5, -0.7), Vec3::new(0.3, 0.0, -0.1)),
    )
}

fn run(body: &RigidBody, integrator: Integrator, x0: State, t_end: f64, n: u64) -> State {
    let mut sim = Simulator::new(body.clone(), x0, integrator, t_end / n as f64).unwrap();
    sim.run(n, |_, _| {}).unwrap();
    *sim.state()
}

/// Distance on SE(3) × twists: `|log(T_ref⁻¹ T)| + |V - V_ref|`.
fn distance(a: &State, b: &State) -> f64 {
    (b.pose.inverse() * a.pose).log().norm() + (a.twist - b.twist).norm()
}

fn convergence_ratios(integrator: Integrator) -> (f64, f64) {
    let body = RigidBody::free(asymmetric())
        .unwrap()
        .with_gravity(G)
        .unwrap();
    let reference = run(&body, Integrator::Rk4, start(), 2.0, 40 * 64);
    let e: Vec<f64> = [40, 80, 160]
        .iter()
        .map(|&n| distance(&run(&body, integrator, start(), 2.0, n), &reference))
        .collect();
    (e[0] / e[1], e[1] / e[2])
}

#[test]
fn rk4_error_shrinks_sixteen_fold_when_dt_halves() {
    let (r1, r2) = convergence_ratios(Integrator::Rk4);
    println!("RKMK4 error ratios: {r1:.2}, {r2:.2}");
    assert!(
        (12.0..20.0).contains(&r1) && (12.0..20.0).contains(&r2),
        "{r1} {r2}"
    );
}

#[test]
fn variational_error_shrinks_four_fold_when_dt_halves() {
    let (r1, r2) = convergence_ratios(Integrator::Lgvi);
    println!("LGVI error ratios: {r1:.2}, {r2:.2}");
    assert!(
        (3.5..4.5).contains(&r1) && (3.5..4.5).contains(&r2),
        "{r1} {r2}"
    );
}

/// 10⁶ steps of a tumbling free body: world angular momentum to round-off, energy error bounded
/// (the same in the last tenth as in the first), rotation orthonormal with no re-normalisation.
#[test]
fn variational_keeps_momentum_and_energy_of_a_free_body_to_round_off_over_1e6_steps() {
    let body = RigidBody::free(asymmetric()).unwrap();
    let n = 1_000_000u64;
    let mut sim = Simulator::new(body, start(), Integrator::Lgvi, 1e-3).unwrap();
    let e0 = sim.body().energy(sim.state());
    let (mut first, mut last, mut worst_l) = (0.0f64, 0.0f64, 0.0f64);
    let l0 = sim.body().angular_momentum(sim.state());
    let p0 = sim.body().spatial_momentum(sim.state());
    let mut k = 0u64;
    let body = sim.body().clone();
    sim.run(n, |_, x| {
        k += 1;
        let de = ((body.energy(x) - e0) / e0).abs();
        if k <= n / 10 {
            first = first.max(de);
        } else if k > n - n / 10 {
            last = last.max(de);
        }
        if k.is_multiple_of(100) {
            worst_l = worst_l.max((body.angular_momentum(x) - l0).norm() / l0.norm());
        }
    })
    .unwrap();
    let x = sim.state();
    let dp = (body.spatial_momentum(x) - p0).norm() / p0.norm();
    let ortho = (x.pose.rotation.transpose() * x.pose.rotation - Mat3::identity()).amax();
    println!(
        "LGVI 1e6 steps: |ΔL|/|L| max {worst_l:.2e}, |ΔP_s|/|P_s| {dp:.2e}, |ΔE|/E first tenth {first:.2e}, last tenth {last:.2e}, |RᵀR-I| {ortho:.2e}"
    );
    assert!(worst_l < 1e-12, "{worst_l}");
    assert!(dp < 1e-10, "{dp}");
    // Torque-free, the discrete rigid body (Moser-Veselov) keeps the energy exactly too.
    assert!(first < 1e-13 && last < 1e-13, "{first} {last}");
    assert!(ortho < 1e-12, "{ortho}");
}

/// A heavy asymmetric body swinging and tumbling on a pivot under gravity, 10⁵ steps: the
/// variational integrator's energy error oscillates at `O(h²)` and does not grow; RK4's drifts.
#[test]
fn variational_energy_error_stays_bounded_on_a_pivot_under_gravity() {
    let g = SpatialInertia::from_com(
        1.0,
        Vec3::new(0.1, 0.0, -0.5),
        RotationalInertia::diagonal(0.02, 0.05, 0.06),
    );
    let body = RigidBody::pivot(g).unwrap().with_gravity(G).unwrap();
    let x0 = State::new(
        Transform::from_rotation(so3::exp(&Vec3::new(1.2, 0.3, 0.0))),
        Twist::new(Vec3::new(0.5, -2.0, 3.0), Vec3::zeros()),
    );
    let n = 100_000u64;
    let mut out = Vec::new();
    for integrator in [Integrator::Lgvi, Integrator::Rk4] {
        let mut sim = Simulator::new(body.clone(), x0, integrator, 5e-3).unwrap();
        let e0 = body.energy(&x0);
        let scale = body.kinetic_energy(&x0);
        let (mut first, mut last, mut k) = (0.0f64, 0.0f64, 0u64);
        sim.run(n, |_, x| {
            k += 1;
            let de = (body.energy(x) - e0).abs() / scale;
            if k <= n / 10 {
                first = first.max(de);
            } else if k > n - n / 10 {
                last = last.max(de);
            }
        })
        .unwrap();
        let dl = sim.summary().relative_momentum_error();
        println!("{integrator}: |ΔE|/K₀ first tenth {first:.2e}, last tenth {last:.2e}; vertical |ΔL|/|L| {dl:.2e}");
        out.push((first, last, dl));
    }
    let (first, last, dl) = out[0];
    assert!(first < 1e-3 && last < 3.0 * first, "{first} {last}");
    assert!(out[1].1 > 3.0 * out[1].0, "RK4 drift {:?}", out[1]);
    assert!(dl < 1e-12, "{dl}");
}

#[test]
fn rk4_keeps_rotation_orthonormal() {
    let body = RigidBody::free(asymmetric()).unwrap();
    let x = run(&body, Integrator::Rk4, start(), 20.0, 20_000);
    let ortho = (x.pose.rotation.transpose() * x.pose.rotation - Mat3::identity()).amax();
    assert!(ortho < 1e-13, "{ortho}");
}

/// Torque-free body with principal moments 1 < 2 < 3 (in its CoM frame, principal axes), spun
/// about one axis with a 1e-3 rad/s perturbation on the others.
fn spin_about(axis: usize, integrator: Integrator) -> (f64, f64) {
    let g = SpatialInertia::from_com(
        1.0,
        Vec3::zeros(),
        RotationalInertia::diagonal(1.0, 2.0, 3.0),
    );
    let body = RigidBody::free(g).unwrap();
    let mut w = Vec3::repeat(1e-3);
    w[axis] = 1.0;
    let x0 = State::new(Transform::identity(), Twist::new(w, Vec3::zeros()));
    let mut sim = Simulator::new(body, x0, integrator, 1e-2).unwrap();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    sim.run(6000, |_, x| {
        lo = lo.min(x.twist.w[axis]);
        hi = hi.max(x.twist.w[axis]);
    })
    .unwrap();
    (lo, hi)
}

#[test]
fn torque_free_body_flips_about_its_intermediate_axis() {
    for integrator in [Integrator::Rk4, Integrator::Lgvi] {
        let (lo, hi) = spin_about(1, integrator);
        assert!(lo < -0.9 && hi > 0.9, "{integrator}: ω_y in [{lo}, {hi}]");
    }
}

#[test]
fn torque_free_body_does_not_flip_about_its_largest_or_smallest_axis() {
    for integrator in [Integrator::Rk4, Integrator::Lgvi] {
        for axis in [0, 2] {
            let (lo, _) = spin_about(axis, integrator);
            assert!(lo > 0.99, "{integrator}, axis {axis}: min ω = {lo}");
        }
    }
}

/// A fast symmetric top on a pivot (CoM at `l` on its axis, spin inertia `I₃`, spin `ω₃`)
/// precesses about the vertical at `Ω ≈ m g l / (I₃ ω₃)`.
#[test]
fn fast_top_precesses_at_the_gyroscopic_rate() {
    let (m, l, i3, spin) = (1.0, 0.1, 0.01, 150.0);
    let g = SpatialInertia::from_com(
        m,
        Vec3::new(0.0, 0.0, l),
        RotationalInertia::diagonal(0.005, 0.005, i3),
    );
    let body = RigidBody::pivot(g).unwrap().with_gravity(G).unwrap();
    let omega = m * 9.81 * l / (i3 * spin);
    let r0 = so3::exp(&Vec3::new(0.5, 0.0, 0.0));
    let w0 = Vec3::new(0.0, 0.0, spin) + r0.transpose() * Vec3::new(0.0, 0.0, omega);
    let x0 = State::new(Transform::from_rotation(r0), Twist::new(w0, Vec3::zeros()));
    for integrator in [Integrator::Rk4, Integrator::Lgvi] {
        let (t_end, n) = (3.0, 6000u64);
        let mut sim = Simulator::new(body.clone(), x0, integrator, t_end / n as f64).unwrap();
        let azimuth = |x: &State| {
            let a = x.pose.rotation * Vec3::z();
            a.y.atan2(a.x)
        };
        let (mut total, mut prev) = (0.0, azimuth(&x0));
        sim.run(n, |_, x| {
            let a = azimuth(x);
            let mut d = a - prev;
            d -= (d / std::f64::consts::TAU).round() * std::f64::consts::TAU;
            total += d;
            prev = a;
        })
        .unwrap();
        let rate = total / t_end;
        println!("{integrator}: precession {rate:.4} rad/s, m g l / (I₃ ω₃) = {omega:.4}");
        assert!(
            (rate / omega - 1.0).abs() < 0.03,
            "{integrator}: {rate} vs {omega}"
        );
        // The pivot stays at the origin exactly.
        assert_eq!(sim.state().pose.translation, Vec3::zeros());
    }
}

#[test]
fn bad_inputs_are_clean_errors() {
    let body = RigidBody::free(asymmetric()).unwrap();
    for dt in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let e = Simulator::new(body.clone(), start(), Integrator::Rk4, dt).unwrap_err();
        assert!(matches!(e, BodyError::TimeStep { .. }), "{e}");
    }
    let mut bad = start();
    bad.twist.w.x = f64::NAN;
    assert!(matches!(
        Simulator::new(body.clone(), bad, Integrator::Rk4, 1e-3),
        Err(BodyError::NonFinite { .. })
    ));
    assert!(body
        .clone()
        .with_gravity(Vec3::new(0.0, f64::NAN, 0.0))
        .is_err());
    let g = SpatialInertia::from_com(
        1.0,
        Vec3::new(0.0, 0.0, 1.0),
        RotationalInertia::diagonal(1.0, 1.0, 1.0),
    );
    let pivot = RigidBody::pivot(g).unwrap();
    let moving = State::new(Transform::identity(), Twist::new(Vec3::zeros(), Vec3::x()));
    assert!(matches!(
        Simulator::new(pivot, moving, Integrator::Rk4, 1e-3),
        Err(BodyError::PivotMoves { .. })
    ));
    // A wrench that blows up stops the run with an error and leaves the last finite state.
    for integrator in [Integrator::Rk4, Integrator::Lgvi] {
        let wild = body.clone().with_wrench(|t: f64, _: &State| {
            Wrench::new(
                Vec3::new(if t > 0.05 { f64::INFINITY } else { 0.0 }, 0.0, 0.0),
                Vec3::zeros(),
            )
        });
        let mut sim = Simulator::new(wild, start(), integrator, 1e-2).unwrap();
        let err = sim.run(100, |_, x| assert!(x.is_finite())).unwrap_err();
        assert!(
            matches!(
                err,
                BodyError::NonFinite { .. } | BodyError::NoConvergence { .. }
            ),
            "{err}"
        );
        assert!(sim.state().is_finite());
    }
}
