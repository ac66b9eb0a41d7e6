//! Robots standing on the ground under the stance controller (`ControlLaw::standing`): PD to
//! the stance, gains on the inertia each joint moves while the feet hold, and the feedforward
//! that carries the weight on the feet, its PD part implicit in the time stepper. Solo-12 fell
//! after ~1.4 s under gains on the legs' own inertia (a yaw twist of the base growing ×2 every
//! 0.09 s); TALOS fell at 6.1 s at 2 Hz (a forward lean), and became NaN at 12 ms with these
//! gains explicit.

use super::options;
use crate::common::example_robot_data;
use rigid::collision::place_on_ground;
use rigid::io::collision::{ground_model, urdf_geometries};
use rigid::io::urdf::{load_urdf, parse_urdf_file};
use rigid::simulation::{ControlLaw, Controller, Simulator};

/// Simulates `urdf` (floating) standing at `stance` (rigid's layout) for 10 s at 1 ms and checks
/// the bars: after the first 0.5 s (settling) the base height stays within 1 cm of its
/// start, no penetration reaches 2 mm, no state is NaN, at least `contacts` are active at the
/// end, and the mean normal force over the last second is the weight within 1 %. Returns the
/// base height's largest departure (m).
fn stands(urdf: &str, stance: &[f64], contacts: usize) -> f64 {
    let path = example_robot_data().join(urdf);
    let model = load_urdf(&path, true).unwrap();
    let robot = parse_urdf_file(&path).unwrap();
    let (geometries, _) = urdf_geometries(&robot, &model);
    let cm = ground_model(Some(0.0), None, None, geometries).unwrap();
    let mut q0 = stance.to_vec();
    place_on_ground(&model, &cm, &mut q0).unwrap();
    let law = ControlLaw::standing(&model, &q0, &cm).unwrap();
    let control = Controller::new(&model, law).unwrap();
    let v0 = vec![0.0; model.nv()];
    let mut sim = Simulator::new(&model, &q0, &v0, options(1e-3), control)
        .unwrap()
        .with_collision(cm)
        .unwrap();
    let (mut drift, mut penetration, mut impulse): (f64, f64, f64) = (0.0, 0.0, 0.0);
    let steps = 10_000;
    for k in 0..steps {
        sim.step().unwrap();
        assert!(sim.q().iter().chain(sim.v()).all(|x| x.is_finite()));
        penetration = penetration.max(sim.contact_stats().penetration);
        if k >= 500 {
            drift = drift.max((sim.q()[2] - q0[2]).abs());
        }
        if k + 1000 >= steps {
            impulse += sim.contact_stats().normal_impulse;
        }
    }
    // the impulses of the last 1000 steps of 1 ms: the mean force over that second
    let (normal, weight) = (impulse / 1.0, model.total_mass() * 9.81);
    let active = sim.contact_stats().active;
    // the points that push, per body
    // the candidate points and those that push, per body
    let mut per_body = std::collections::BTreeMap::new();
    for (c, p) in sim.contacts().iter().zip(sim.contact_impulses()) {
        let e = per_body
            .entry(c.body1.map(|j| j.0))
            .or_insert((0usize, 0usize));
        e.0 += 1;
        e.1 += usize::from(p.dot(&c.normal) > 0.0);
    }
    println!("{urdf}: {active} active contacts; per body (candidates, pushing) {per_body:?}");
    assert!(drift < 1e-2, "{urdf}: the base height moved {drift} m");
    assert!(penetration < 2e-3, "{urdf}: penetration {penetration} m");
    assert!(active >= contacts, "{urdf}: {active} active contacts");
    assert!(
        (normal - weight).abs() < 0.01 * weight,
        "{urdf}: normal force {normal} N, weight {weight} N"
    );
    drift
}

#[test]
fn solo12_stands_ten_seconds_under_the_stance_controller() {
    let stance = [
        0.0, 0.0, 0.3, 0.0, 0.0, 0.0, 1.0, 0.1, 0.8, -1.6, -0.1, 0.8, -1.6, 0.1, -0.8, 1.6, -0.1,
        -0.8, 1.6,
    ];
    // measured: drift 1.0e-4 m, penetration 1e-8 m after the first step's 0.5 mm
    stands("solo_description/robots/solo12.urdf", &stance, 4);
}

#[test]
fn anymal_stands_ten_seconds_under_the_stance_controller() {
    // example-robot-data's SRDF "standing", in rigid's joint order (the file's)
    let stance = [
        0.0, 0.0, 0.4792, 0.0, 0.0, 0.0, 1.0, -0.1, 0.7, -1.0, 0.1, 0.7, -1.0, -0.1, -0.7, 1.0,
        0.1, -0.7, 1.0,
    ];
    // measured: drift 1e-13 m
    stands("anymal_b_simple_description/robots/anymal.urdf", &stance, 4);
}

#[test]
fn talos_stands_ten_seconds_under_the_stance_controller() {
    // example-robot-data's SRDF "half_sitting", in rigid's joint order (the file's): torso,
    // head, arms and grippers, then the legs
    let mut stance = vec![0.0, 0.0, 1.01927, 0.0, 0.0, 0.0, 1.0];
    stance.extend([0.0, 0.006761, 0.0, 0.0]);
    stance.extend([0.25847, 0.173046, -0.0002, -0.525366, 0.0, 0.0, 0.1, 0.0]);
    stance.extend([-0.25847, -0.173046, 0.0002, -0.525366, 0.0, 0.0, 0.1, 0.0]);
    for _ in 0..2 {
        stance.extend([0.0, 0.0, -0.411354, 0.859395, -0.448041, -0.001708]);
    }
    // measured: drift 3.0e-4 m, the mean normal force 885.587 N for a weight of 885.570 N; the
    // uneven mesh soles (±0.7 mm) rest on one point each, whose force at one step strays by 3 %
    stands("talos_data/robots/talos_reduced.urdf", &stance, 2);
}
