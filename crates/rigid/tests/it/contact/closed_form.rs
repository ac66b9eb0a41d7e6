//! The closed forms of mechanics with contact and Coulomb friction.

use super::{com, q_of, scene, simulator, Free, G};
use rigid::collision::Ground;
use rigid::spatial::{Mat3, Vec3};

/// A box of any mass launched at `v₀` on the ground with friction `μ` stops after
/// `v₀² / (2 μ g)` (within 1 % at `dt = 1 ms`): Coulomb's law decelerates it at `μ g` whatever its
/// mass, the four corners' normal forces summing to `m g`.
#[test]
fn a_sliding_box_stops_after_v0_squared_over_2_mu_g() {
    for (mass, mu, v0) in [(3.7, 0.5, 2.0), (0.2, 0.3, 1.0), (250.0, 0.8, 3.0)] {
        let size = Vec3::new(0.3, 0.2, 0.1);
        let (model, cm) = scene(
            &[Free::cube(mass, size)],
            Vec3::new(0.0, 0.0, -G),
            Some(Ground::horizontal(0.0, mu)),
        );
        let q0 = q_of(Vec3::new(0.0, 0.0, 0.05), &Mat3::identity());
        let v0 = [0.0, 0.0, 0.0, v0, 0.0, 0.0];
        let dt = 1e-3;
        let mut sim = simulator(&model, cm, &q0, &v0, dt);
        let mut stopped = None;
        for _ in 0..5000 {
            sim.step().unwrap();
            let (p, v) = com(&sim, 0);
            if v.x.abs() < 1e-9 {
                stopped = Some(p);
                break;
            }
        }
        let p = stopped.expect("the box stops");
        let expected = v0[3] * v0[3] / (2.0 * mu * G);
        let err = (p.x - expected).abs() / expected;
        println!(
            "box m = {mass} kg, μ = {mu}, v₀ = {}: {:.5} m against {expected:.5} m, error {:.3} %",
            v0[3],
            p.x,
            100.0 * err
        );
        assert!(
            err < 0.01,
            "stopping distance {} vs {expected}: {err:e}",
            p.x
        );
        assert!(
            (p.z - 0.05).abs() < 1e-4 && p.y.abs() < 1e-9,
            "stays on the ground: {p}"
        );
    }
}

/// A solid ball on a slope of angle θ (level ground, gravity tilted by θ) rolls without
/// slipping at `a = 5/7 g sin θ` when `μ ≥ 2/7 tan θ`, and slips at `a = g (sin θ − μ cos θ)`
/// below it (to 0.5 % over one second at 1 ms).
#[test]
fn a_ball_rolls_at_five_sevenths_g_sin_theta_or_slips() {
    let theta = 20f64.to_radians();
    let gravity = Vec3::new(G * theta.sin(), 0.0, -G * theta.cos());
    let threshold = 2.0 / 7.0 * theta.tan();
    for (mu, rolls) in [
        (0.5, true),
        (1.2 * threshold, true),
        (0.8 * threshold, false),
        (0.05, false),
    ] {
        let r = 0.1;
        let (model, cm) = scene(
            &[Free::ball(2.0, r)],
            gravity,
            Some(Ground::horizontal(0.0, mu)),
        );
        let q0 = q_of(Vec3::new(0.0, 0.0, r), &Mat3::identity());
        let mut sim = simulator(&model, cm, &q0, &[0.0; 6], 1e-3);
        sim.run(1000, |_| {}).unwrap();
        let (p, v) = com(&sim, 0);
        let a = v.x / sim.time();
        let expected = if rolls {
            5.0 / 7.0 * G * theta.sin()
        } else {
            G * (theta.sin() - mu * theta.cos())
        };
        let err = (a - expected).abs() / expected;
        // rolling: the contact point is at rest, v = ω r
        let w = sim.v()[1];
        let slip = v.x - w * r;
        println!("μ = {mu:.4} ({}): a = {a:.5} against {expected:.5}, error {:.3} %, slip speed {slip:.2e}", if rolls { "rolls" } else { "slips" }, 100.0 * err);
        assert!(err < 5e-3, "μ = {mu}: a = {a} vs {expected}");
        assert!((p.z - r).abs() < 1e-6, "on the ground: {}", p.z);
        if rolls {
            assert!(slip.abs() < 1e-6, "rolling without slipping: {slip}");
        } else {
            assert!(slip > 0.1, "slipping: {slip}");
        }
    }
}

/// A ball dropped with restitution `e` rebounds to `e²` of its height, bounce after bounce
/// (each apex within 2 % of `e²` times the one before).
#[test]
fn a_ball_rebounds_to_e_squared_of_its_height() {
    for e in [0.5, 0.8, 0.9] {
        let r = 0.05;
        let ground = Ground {
            restitution: e,
            ..Ground::horizontal(0.0, 0.5)
        };
        let (model, cm) = scene(&[Free::ball(0.5, r)], Vec3::new(0.0, 0.0, -G), Some(ground));
        let h0 = 1.0;
        let q0 = q_of(Vec3::new(0.0, 0.0, r + h0), &Mat3::identity());
        let mut sim = simulator(&model, cm, &q0, &[0.0; 6], 1e-3);
        let (mut apexes, mut top, mut rising) = (vec![h0], 0.0f64, false);
        for _ in 0..6000 {
            sim.step().unwrap();
            let (p, v) = com(&sim, 0);
            if v.z > 0.0 {
                rising = true;
                top = top.max(p.z - r);
            } else if rising {
                rising = false;
                apexes.push(top.max(p.z - r));
                top = 0.0;
            }
            if apexes.len() == 5 {
                break;
            }
        }
        assert!(apexes.len() >= 4, "bounces: {apexes:?}");
        for w in apexes.windows(2) {
            let ratio = w[1] / w[0];
            let err = (ratio - e * e).abs() / (e * e);
            println!("e = {e}: apex {:.5} -> {:.5} m, ratio {ratio:.5} against e² = {:.4}, error {:.2} %", w[0], w[1], e * e, 100.0 * err);
            assert!(err < 0.02, "e = {e}: {apexes:?}");
        }
    }
}

/// A box resting on the ground stays within 0.1 mm of where it was put, and does not drift, over
/// 10 s.
#[test]
fn a_resting_box_stays_put_for_ten_seconds() {
    let size = Vec3::new(0.4, 0.3, 0.2);
    let (model, cm) = scene(
        &[Free::cube(5.0, size)],
        Vec3::new(0.0, 0.0, -G),
        Some(Ground::horizontal(0.0, 0.8)),
    );
    let p0 = Vec3::new(0.1, -0.2, 0.1);
    let q0 = q_of(p0, &Mat3::identity());
    let mut sim = simulator(&model, cm, &q0, &[0.0; 6], 1e-3);
    let mut worst: f64 = 0.0;
    for _ in 0..10_000 {
        sim.step().unwrap();
        worst = worst.max((com(&sim, 0).0 - p0).norm());
    }
    let s = sim.contact_stats();
    println!("resting box: largest displacement {worst:.2e} m over 10 s; {} contacts, normal force {:.4} N (mg = {:.4} N)", s.active, s.normal_impulse / 1e-3, 5.0 * G);
    assert!(worst < 1e-4, "moved {worst} m");
    assert!((s.normal_impulse / 1e-3 - 5.0 * G).abs() < 1e-6 * 5.0 * G);
}

/// Three boxes stacked on the ground stand: after 5 s each is within 1 mm of where it was put
/// and has not turned.
#[test]
fn a_tower_of_three_boxes_stands() {
    let size = Vec3::new(0.3, 0.3, 0.2);
    let boxes = [
        Free::cube(4.0, size),
        Free::cube(2.0, size),
        Free::cube(1.0, size),
    ];
    let (model, cm) = scene(
        &boxes,
        Vec3::new(0.0, 0.0, -G),
        Some(Ground::horizontal(0.0, 0.8)),
    );
    let mut q0 = Vec::new();
    let start: Vec<Vec3> = (0..3)
        .map(|i| Vec3::new(0.0, 0.0, 0.1 + 0.2 * i as f64))
        .collect();
    for p in &start {
        q0.extend(q_of(*p, &Mat3::identity()));
    }
    let mut sim = simulator(&model, cm, &q0, &[0.0; 18], 1e-3);
    let mut worst: f64 = 0.0;
    for _ in 0..5000 {
        sim.step().unwrap();
        for (i, p) in start.iter().enumerate() {
            worst = worst.max((com(&sim, i).0 - p).norm());
        }
    }
    let turn = (0..3)
        .map(|i| {
            sim.q()[7 * i + 3..7 * i + 6]
                .iter()
                .fold(0.0f64, |m, x| m.max(x.abs()))
        })
        .fold(0.0f64, f64::max);
    println!(
        "tower: largest displacement {worst:.2e} m, largest quaternion vector part {turn:.2e}"
    );
    assert!(
        worst < 1e-3 && turn < 1e-3,
        "the tower moved {worst} m, turned {turn}"
    );
}

/// A box on a slope (level ground, gravity tilted by θ) with μ = 0.5: it sticks at
/// tan θ = 0.45 (less than 1 mm in 2 s) and slides at tan θ = 0.55 with
/// `a = g (sin θ − μ cos θ)` (within 1 %), resting on its four corners (issue 48).
#[test]
fn a_box_on_a_slope_sticks_below_the_friction_angle_and_slides_above_it() {
    let mu = 0.5;
    for (slope, sticks) in [(0.45f64, true), (0.55, false)] {
        let theta = slope.atan();
        let gravity = Vec3::new(G * theta.sin(), 0.0, -G * theta.cos());
        let (model, cm) = scene(
            &[Free::cube(2.0, Vec3::new(0.2, 0.16, 0.1))],
            gravity,
            Some(Ground::horizontal(0.0, mu)),
        );
        let q0 = q_of(Vec3::new(0.0, 0.0, 0.05), &Mat3::identity());
        let mut sim = simulator(&model, cm, &q0, &[0.0; 6], 1e-3);
        sim.run(2000, |_| {}).unwrap();
        let (p, v) = com(&sim, 0);
        let expected = G * (theta.sin() - mu * theta.cos());
        let a = v.x / sim.time();
        println!(
            "tan θ = {slope}: moved {:.2e} m in 2 s, a = {a:.5} m/s² (g (sin θ − μ cos θ) = {expected:.5}), {} contacts",
            p.x,
            sim.contact_stats().active
        );
        if sticks {
            assert!(p.x.abs() < 1e-3 && v.norm() < 1e-6, "{p} {v}");
        } else {
            assert!((a - expected).abs() < 0.01 * expected, "{a} vs {expected}");
        }
        assert_eq!(sim.contact_stats().active, 4);
        assert!((p.z - 0.05).abs() < 1e-5, "{p}");
    }
}

/// A 1 kg plate whose mesh bottom is uneven by 0.5 mm (a 5 x 5 grid of points at random
/// heights, as real sole meshes are), set down spinning at 2 rad/s about the vertical (issue
/// 48): from 0.5 s on the normal force is the weight within 2 % at every step, and from 1 s on
/// |ω| ≤ 1e-3 rad/s, |v| ≤ 1e-4 m/s on at least 3 points. The issue asks the rest from 0.5 s:
/// not met here, by physics: it stops spinning at 0.06 s balanced on the line through its two
/// lowest points, its CoM 1 mm off that line, and tips over it slowly (|ω| 3e-6 rad/s growing
/// to 2.1e-3 at 0.96 s) onto a third point, where it rests (|ω| ≤ 2.0e-11 rad/s after 1 s). Before,
/// it rocked for good (|ω| 0.11 rad/s, the force off by 33 %): the four widest points of its
/// resting face missed the lower interior vertex it
/// settles on, which penetrated each step and was pushed back by the position correction; the
/// reduction now keeps the face's points under the envelope of the four and those touching
/// outside them (`collision::detect`, at most 8).
#[test]
fn a_plate_with_an_uneven_mesh_bottom_set_down_spinning_comes_to_rest() {
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let (a, b, t) = (0.1, 0.08, 0.01);
    let mut points = Vec::new();
    for i in 0..5 {
        for j in 0..5 {
            let (x, y) = (-a + 0.5 * a * i as f64, -b + 0.5 * b * j as f64);
            points.push(Vec3::new(x, y, -0.5 * t + 5e-4 * next()));
        }
    }
    for (x, y) in [(-a, -b), (a, -b), (a, b), (-a, b)] {
        points.push(Vec3::new(x, y, 0.5 * t));
    }
    let mut plate = Free::cube(1.0, Vec3::new(2.0 * a, 2.0 * b, t));
    plate.shape = rigid::collision::Shape::ConvexHull { points };
    let (model, cm) = scene(
        &[plate],
        Vec3::new(0.0, 0.0, -G),
        Some(Ground::horizontal(0.0, 0.5)),
    );
    let q0 = q_of(Vec3::new(0.0, 0.0, 0.5 * t), &Mat3::identity());
    let mut sim = simulator(&model, cm, &q0, &[0.0, 0.0, 2.0, 0.0, 0.0, 0.0], 1e-3);
    let (mut worst_force, mut steps): (f64, usize) = (0.0, 0);
    let mut pushing = usize::MAX;
    // the largest |ω| and |v| from 0.5 s and from 1 s on
    let (mut tipping, mut w, mut lin): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for k in 0..1500 {
        sim.step().unwrap();
        let v = sim.v();
        let (wk, vk) = (
            Vec3::new(v[0], v[1], v[2]).norm(),
            Vec3::new(v[3], v[4], v[5]).norm(),
        );
        if k >= 500 {
            let force = sim.contact_stats().normal_impulse / 1e-3;
            worst_force = worst_force.max((force - G).abs() / G);
            tipping = tipping.max(wk);
        }
        if k >= 1000 {
            pushing = pushing.min(sim.contact_stats().active);
            steps += 1;
            w = w.max(wk);
            lin = lin.max(vk);
        }
    }
    println!(
        "plate: |ω| ≤ {tipping:.1e} rad/s from 0.5 s; over the last {steps} steps |ω| ≤ {w:.1e} rad/s, |v| ≤ {lin:.1e} m/s, at least {pushing} points pushing; from 0.5 s the normal force within {:.2} % of the weight",
        100.0 * worst_force
    );
    assert!(w <= 1e-3 && lin <= 1e-4, "{w} {lin}");
    assert!(pushing >= 3, "{pushing} points push");
    assert!(worst_force <= 0.02, "{worst_force}");
}
