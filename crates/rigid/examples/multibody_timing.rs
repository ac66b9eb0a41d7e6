//! Rough per-call timings of the multibody algorithms (fastest of 21 batches over 1000 pre-drawn
//! random states) on the PUMA 560, a UR5 built from its DH table, and a 30-dof random tree.
//! Run with `cargo run --release -p rigid --example multibody_timing [MODEL [ALGORITHM]]`;
//! `bench/pinocchio/ur5_dh.cpp` times Pinocchio on the same "ur5" model.
//!
//! A quick local check, not the measurement of record: the timings against Pinocchio, their
//! machine and commit, and how to re-run them are in BENCHMARKS.md.
#![allow(non_snake_case)]

use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::multibody::*;
use rigid::spatial::{Transform, Vec3};
use std::f64::consts::FRAC_PI_2;
use std::hint::black_box;
use std::time::Instant;

fn ur5() -> Model {
    // Universal Robots' published DH table and link masses; CoMs and inertias approximate.
    let d = [0.089159, 0.0, 0.0, 0.10915, 0.09465, 0.0823];
    let a = [0.0, -0.425, -0.39225, 0.0, 0.0, 0.0];
    let alpha = [FRAC_PI_2, 0.0, 0.0, FRAC_PI_2, -FRAC_PI_2, 0.0];
    let m = [3.7, 8.393, 2.275, 1.219, 1.219, 0.1879];
    let links: Vec<DhLink> = (0..6)
        .map(|i| DhLink {
            a: a[i],
            alpha: alpha[i],
            d: d[i],
            theta_offset: 0.0,
            joint: DhJoint::Revolute,
            mass: m[i],
            com: Vec3::new(-a[i] / 2.0, 0.0, 0.01),
            inertia: RotationalInertia::diagonal(0.01 * m[i], 0.012 * m[i], 0.008 * m[i]),
        })
        .collect();
    from_dh(
        "ur5",
        DhConvention::Standard,
        &links,
        Vec3::new(0.0, 0.0, -9.81),
    )
    .unwrap()
}

fn tree(n: usize) -> Model {
    let mut rng = Rng::new(1);
    let mut b = ModelBuilder::new("tree");
    let g = SpatialInertia::from_com(
        1.0,
        Vec3::new(0.1, 0.0, 0.0),
        RotationalInertia::diagonal(0.01, 0.02, 0.025),
    );
    let root = b
        .add_joint(None, "root", JointType::FreeFlyer, Transform::identity(), g)
        .unwrap();
    // four limbs
    let per = n / 4;
    for l in 0..4 {
        let mut p = root;
        for k in 0..per {
            let axis = Vec3::new(rng.normal(), rng.normal(), rng.normal());
            p = b
                .add_joint(
                    Some(p),
                    &format!("l{l}j{k}"),
                    JointType::Revolute { axis },
                    Transform::from_translation(Vec3::new(0.0, 0.1, 0.2)),
                    g,
                )
                .unwrap();
        }
    }
    b.build().unwrap()
}

fn time(name: &str, n: usize, mut f: impl FnMut(usize)) {
    let only = std::env::args().nth(2);
    if only.as_deref().is_some_and(|o| o != name) {
        return;
    }
    let reps = if only.is_some() { 1 } else { 21 };
    let mut samples = Vec::new();
    for _ in 0..reps {
        let t = Instant::now();
        for i in 0..n {
            f(i);
        }
        samples.push(t.elapsed().as_nanos() as f64 / n as f64);
    }
    samples.sort_by(f64::total_cmp);
    print!(" {name} {:.0}", samples[0]);
    let _ = reps;
}

fn main() {
    let only = std::env::args().nth(1);
    for model in [puma560(Puma560Options::default()), ur5(), tree(28)] {
        if only.as_deref().is_some_and(|o| o != model.name()) {
            continue;
        }
        let mut rng = Rng::new(7);
        let n = 1000;
        let states: Vec<_> = (0..n)
            .map(|_| {
                let q = random_configuration(&model, &mut rng);
                let v: Vec<f64> = (0..model.nv()).map(|_| rng.uniform(-1.0, 1.0)).collect();
                let a: Vec<f64> = (0..model.nv()).map(|_| rng.uniform(-1.0, 1.0)).collect();
                (q, v, a)
            })
            .collect();
        let mut d = Data::new(&model);
        print!("{} (nv {}), ns/call:", model.name(), model.nv());
        time("fk", n, |i| {
            forward_kinematics(&model, &mut d, &states[i].0, &states[i].1, &states[i].2).unwrap();
            black_box(&d.placements);
        });
        time("jac", n, |i| {
            black_box(compute_joint_jacobians(&model, &mut d, &states[i].0).unwrap());
        });
        time("rnea", n, |i| {
            black_box(rnea(&model, &mut d, &states[i].0, &states[i].1, &states[i].2).unwrap());
        });
        time("crba", n, |i| {
            black_box(crba(&model, &mut d, &states[i].0).unwrap());
        });
        time("aba", n, |i| {
            black_box(aba(&model, &mut d, &states[i].0, &states[i].1, &states[i].2).unwrap());
        });
        time("coriolis", n, |i| {
            black_box(coriolis_matrix(&model, &mut d, &states[i].0, &states[i].1).unwrap());
        });
        println!();
    }
}
