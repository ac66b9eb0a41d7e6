//! Robots standing on the ground under the stance controller (`ControlLaw::standing`): PD to
//! the stance, gains on the inertia each joint moves while the feet hold, and the feedforward
//! that carries the weight on the feet. Solo-12 fell after ~1.4 s under gains on the legs' own
//! inertia (a yaw twist of the base growing ×2 every 0.09 s).

use super::options;
use crate::common::example_robot_data;
use rigid::collision::place_on_ground;
use rigid::io::collision::{ground_model, urdf_geometries};
use rigid::io::urdf::{load_urdf, parse_urdf_file};
use rigid::multibody::simulation::{ControlLaw, Controller, Simulator};

/// Simulates `urdf` (floating) standing at `stance` (rigid's layout) for `seconds` at 1 ms and
/// returns the largest departure of the base height from its start after the first 0.5 s
/// (settling), the deepest penetration, the active contacts and normal force at the end.
fn stand(urdf: &str, stance: &[f64], seconds: f64) -> (f64, f64, usize, f64, f64) {
    let path = example_robot_data().join(urdf);
    let model = load_urdf(&path, true).unwrap();
    let robot = parse_urdf_file(&path).unwrap();
    let (geometries, _) = urdf_geometries(&robot, &model);
    let cm = ground_model(0.0, None, None, geometries).unwrap();
    let mut q0 = stance.to_vec();
    place_on_ground(&model, &cm, &mut q0).unwrap();
    let law = ControlLaw::standing(&model, &q0, &cm).unwrap();
    let control = Controller::new(&model, law).unwrap();
    let v0 = vec![0.0; model.nv()];
    let mut sim = Simulator::new(&model, &q0, &v0, options(1e-3), control)
        .unwrap()
        .with_collision(cm)
        .unwrap();
    let (mut drift, mut penetration): (f64, f64) = (0.0, 0.0);
    let steps = (seconds / 1e-3).round() as u64;
    for k in 0..steps {
        sim.step().unwrap();
        assert!(sim.q().iter().chain(sim.v()).all(|x| x.is_finite()));
        penetration = penetration.max(sim.contact_stats().penetration);
        if k >= 500 {
            drift = drift.max((sim.q()[2] - q0[2]).abs());
        }
    }
    let s = sim.contact_stats();
    (
        drift,
        penetration,
        s.active,
        s.normal_impulse / 1e-3,
        model.total_mass(),
    )
}

#[test]
fn solo12_stands_ten_seconds_under_the_stance_controller() {
    let stance = [
        0.0, 0.0, 0.3, 0.0, 0.0, 0.0, 1.0, 0.1, 0.8, -1.6, -0.1, 0.8, -1.6, 0.1, -0.8, 1.6, -0.1,
        -0.8, 1.6,
    ];
    let (drift, penetration, active, normal, mass) =
        stand("solo_description/robots/solo12.urdf", &stance, 10.0);
    // measured: drift 1.0e-4 m, penetration 4e-9 m after the first step's 0.5 mm
    assert!(drift < 1e-2, "base height moved {drift} m");
    assert!(penetration < 2e-3, "penetration {penetration} m");
    assert!(active >= 4, "{active} contacts");
    assert!(
        (normal - mass * 9.81).abs() < 0.02 * mass * 9.81,
        "normal force {normal} N"
    );
}

#[test]
fn anymal_stands_ten_seconds_under_the_stance_controller() {
    // example-robot-data's SRDF "standing", in rigid's joint order (the file's)
    let stance = [
        0.0, 0.0, 0.4792, 0.0, 0.0, 0.0, 1.0, -0.1, 0.7, -1.0, 0.1, 0.7, -1.0, -0.1, -0.7, 1.0,
        0.1, -0.7, 1.0,
    ];
    let (drift, penetration, active, normal, mass) = stand(
        "anymal_b_simple_description/robots/anymal.urdf",
        &stance,
        10.0,
    );
    assert!(drift < 1e-2, "base height moved {drift} m");
    assert!(penetration < 2e-3, "penetration {penetration} m");
    assert!(active >= 4, "{active} contacts");
    assert!(
        (normal - mass * 9.81).abs() < 0.02 * mass * 9.81,
        "normal force {normal} N"
    );
}
