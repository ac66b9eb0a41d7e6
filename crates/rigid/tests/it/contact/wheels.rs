//! Wheels that roll: the differential drive of `examples/diff_drive.urdf` (two cylinder wheels,
//! a swivel caster) on the ground under constant wheel torques moves as its kinematic model says,
//! `v = r (ω_R + ω_L)/2`, `ω = r (ω_R − ω_L)/track` (Lynch & Park §13.3), within 2 % at every
//! step after the first 0.1 s (relative to the motion's speed: `|v|`, or the rim speed when it
//! turns in place), without sideways motion of the axle (`A(q) q̇ = 0`, 1 %). Measured: straight
//! 4e-8, a curve 0.8 % (the 4 mm tread's scrub), in place 1.1 %.

use rigid::io::collision::{urdf_world, WorldOptions};
use rigid::io::urdf::{load_urdf_str, parse_urdf_str};
use rigid::mobile::Base;
use rigid::simulation::{Integrator, Scenario};

fn diff_drive() -> (
    rigid::multibody::Model,
    Option<rigid::collision::CollisionModel>,
) {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/diff_drive.urdf");
    let text = std::fs::read_to_string(path).unwrap();
    let model = load_urdf_str(&text, true).unwrap();
    let robot = parse_urdf_str(&text).unwrap();
    let options = WorldOptions {
        ground: Some(0.0),
        friction: Some(1.0),
        ..WorldOptions::default()
    };
    let (cm, _) = urdf_world(&robot, &model, &options).unwrap();
    (model, cm)
}

#[test]
fn a_differential_drive_rolls_without_slipping() {
    let (model, cm) = diff_drive();
    let base = Base::diff_drive(0.08, 0.36).unwrap();
    let v_of = |name: &str| model.joints()[model.joint_id(name).unwrap().0].idx_v;
    let (left, right) = (v_of("left_wheel_joint"), v_of("right_wheel_joint"));
    for (tl, tr) in [(0.3, 0.3), (0.2, 0.4), (-0.2, 0.2)] {
        let mut s = Scenario::new(model.clone());
        s.collision = cm.clone();
        s.options.integrator = Integrator::SemiImplicitEuler;
        s.options.dt = 1e-3;
        let mut sim = s
            .build_with(move |_t: f64, _q: &[f64], _v: &[f64], tau: &mut [f64]| {
                tau.fill(0.0);
                tau[left] = tl;
                tau[right] = tr;
            })
            .unwrap();
        let (mut worst_v, mut worst_w, mut worst_side, mut worst_z) =
            (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for k in 0..1000 {
            sim.step().unwrap();
            let v = sim.v();
            let [w_model, v_model, _] = base.body_twist(&[v[left], v[right]]).unwrap();
            // the chassis's body twist: (ω_b, v_b), angular first
            let (w_sim, v_sim) = (v[2], v[3]);
            if k >= 100 {
                let rim = 0.08 * (v[left].abs() + v[right].abs()) / 2.0;
                let scale_v = v_model.abs().max(rim);
                let scale_w = w_model.abs().max(rim / 0.18);
                worst_v = worst_v.max((v_sim - v_model).abs() / scale_v);
                worst_w = worst_w.max((w_sim - w_model).abs() / scale_w);
                // A(q) q̇ = 0: the axle does not move sideways
                worst_side = worst_side.max(v[4].abs() / scale_v);
                worst_z = worst_z.max((sim.q()[2] - 0.08).abs());
            }
        }
        eprintln!(
            "τ = ({tl}, {tr}) N·m, 1 s: worst relative error of v {worst_v:.2e}, of ω {worst_w:.2e}, \
             sideways {worst_side:.2e}, height {worst_z:.1e} m; v = {:.3} m/s, ω = {:.3} rad/s at the end",
            sim.v()[3],
            sim.v()[2]
        );
        assert!(
            worst_v < 0.02 && worst_w < 0.02,
            "τ = ({tl}, {tr}): the wheels slip"
        );
        assert!(
            worst_side < 0.01 && worst_z < 1e-6,
            "τ = ({tl}, {tr}): sideways {worst_side:e}, height {worst_z:e}"
        );
    }
}

/// TIAGo (example-robot-data) drives a circle under a wheel-velocity controller
/// (`rigid::mobile::wheel_simulator`: `WheelDrive`, `τ_wheel = K (u_d - u)`) with the wheel speeds `u_d = H(0) (ω, v, 0)` of the circle, the rest of
/// the body held by the stance controller. Its URDF fixes its four swivel casters (fixed joints,
/// sphere collisions): they are made frictionless (the ground's friction 0, the wheels' 1: a
/// geometry's friction with the ground is the larger of the two), as a free swivel caster drags
/// nothing to first order.
#[test]
fn tiago_drives_a_circle() {
    use rigid::io::collision::{ground_model, urdf_geometries};
    use rigid::io::urdf::{load_urdf, parse_urdf_file};
    use rigid::mobile::{chassis_motion, wheel_simulator, DriveOptions};
    let path = crate::common::example_robot_data().join("tiago_description/robots/tiago.urdf");
    let model = load_urdf(&path, true).unwrap();
    let robot = parse_urdf_file(&path).unwrap();
    let (geometries, _) = urdf_geometries(&robot, &model);
    let cm = ground_model(Some(0.0), Some(0.0), None, geometries).unwrap();
    let (r, track) = (0.0985, 2.0 * 0.2022);
    let base = Base::diff_drive(r, track).unwrap();
    let (radius, speed) = (1.0, 0.3);
    let ud = base.H(0.0) * nalgebra::Vector3::new(speed / radius, speed, 0.0);
    let options = DriveOptions {
        wheels: vec!["wheel_left_joint".into(), "wheel_right_joint".into()],
        speeds: vec![ud[0], ud[1]],
        gain: 20.0,
        wheel_friction: Some(1.0),
        hold: true,
        dt: 1e-3,
    };
    let mut sim = wheel_simulator(&model, cm, &options).unwrap();
    let [left, right] = [sim.control().wheels()[0], sim.control().wheels()[1]];
    // 6 s at 1 ms: a third of the circle of radius 1 m centred at (0, 1)
    let (mut worst_radius, mut worst_speed, mut worst_wheel) = (0.0f64, 0.0f64, 0.0f64);
    for k in 0..6000 {
        sim.step().unwrap();
        let (q, v) = (sim.q(), sim.v());
        let [x, y, _, forward, _] = chassis_motion(q, v).unwrap();
        if k >= 500 {
            worst_radius = worst_radius.max((x.hypot(y - radius) - radius).abs() / radius);
            worst_speed = worst_speed.max((forward - speed).abs() / speed);
            for (k, u) in [(left, ud[0]), (right, ud[1])] {
                worst_wheel = worst_wheel.max((v[k] - u).abs() / u);
            }
        }
    }
    let turned = sim.q()[0].atan2(radius - sim.q()[1]);
    eprintln!(
        "TIAGo on a 1 m circle at 0.3 m/s: radius off by {:.2} %, speed by {:.2} %, wheels by {:.2} %; \
         {:.0}° of the circle in 6 s",
        100.0 * worst_radius,
        100.0 * worst_speed,
        100.0 * worst_wheel,
        turned.to_degrees()
    );
    assert!(worst_radius < 0.03 && worst_speed < 0.03 && worst_wheel < 0.01);
    assert!((turned - speed / radius * 6.0).abs() < 0.1, "{turned}");
}
