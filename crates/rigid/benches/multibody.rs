//! Multibody algorithms, ns per call: forward kinematics, joint Jacobians, RNEA, gravity,
//! nonlinear effects, CRBA, `M⁻¹`, ABA and Cholesky forward dynamics, each cycling through 1000
//! pre-drawn random states (so that branch prediction is not flattered).
//!
//! `cargo bench -p rigid --bench multibody [-- FILTER]`. Models: the built-in `puma560` and the
//! robots of `example-robot-data` (UR5, Panda; Solo-12, ANYmal and Talos with a free-flyer
//! root), found by [`rigid::io::robots::example_robot_data`]; a robot whose URDF is not found
//! is skipped with a note on stderr.

use criterion::{criterion_group, criterion_main, Criterion};
use rigid::multibody::*;
use std::hint::black_box;

const STATES: usize = 1000;

/// Pre-drawn random states `(q, v, a)`.
fn states(model: &Model) -> Vec<(Vec<f64>, Vec<f64>, Vec<f64>)> {
    let mut rng = Rng::new(7);
    (0..STATES)
        .map(|_| {
            let q = random_configuration(model, &mut rng);
            let v = (0..model.nv()).map(|_| rng.uniform(-1.0, 1.0)).collect();
            let a = (0..model.nv()).map(|_| rng.uniform(-1.0, 1.0)).collect();
            (q, v, a)
        })
        .collect()
}

/// The benchmark models, by name.
fn models() -> Vec<(String, Model)> {
    let mut out = vec![("puma560".to_string(), puma560(Puma560Options::default()))];
    out.extend(robots::load_all());
    out
}

mod robots {
    //! The example-robot-data URDFs ([`rigid::io::robots`]).
    use rigid::io::robots::{example_robot_data, robot};
    use rigid::io::urdf::load_urdf;
    use rigid::multibody::Model;

    /// The robots timed (Solo-12, ANYmal and Talos with a free-flyer root).
    const ROBOTS: [&str; 5] = ["ur5", "panda", "solo12", "anymal", "talos"];

    /// `(name, model)` of every robot found; notes on stderr for the others.
    pub fn load_all() -> Vec<(String, Model)> {
        let Some(dir) = example_robot_data() else {
            eprintln!(
                "note: example-robot-data not found (set EXAMPLE_ROBOT_DATA): robots skipped"
            );
            return Vec::new();
        };
        ROBOTS
            .iter()
            .filter_map(|&name| robot(name))
            .filter_map(|r| match load_urdf(dir.join(r.file), r.floating) {
                Ok(m) => Some((r.name.to_string(), m)),
                Err(e) => {
                    eprintln!("note: {} skipped: {e}", r.name);
                    None
                }
            })
            .collect()
    }
}

fn bench(c: &mut Criterion) {
    for (name, model) in models() {
        let s = states(&model);
        let mut data = Data::new(&model);
        let mut g = c.benchmark_group(name.as_str());
        let mut i = 0usize;
        let mut next = || {
            i = (i + 1) % STATES;
            &s[i]
        };
        g.bench_function("forward_kinematics", |b| {
            b.iter(|| {
                let (q, _, _) = next();
                forward_kinematics_q(&model, &mut data, q).unwrap();
                black_box(&data.placements);
            })
        });
        g.bench_function("jacobians", |b| {
            b.iter(|| black_box(compute_joint_jacobians(&model, &mut data, &next().0).unwrap()[0]))
        });
        g.bench_function("rnea", |b| {
            b.iter(|| {
                let (q, v, a) = next();
                black_box(rnea(&model, &mut data, q, v, a).unwrap()[0])
            })
        });
        g.bench_function("gravity", |b| {
            b.iter(|| black_box(gravity_torques(&model, &mut data, &next().0).unwrap()[0]))
        });
        g.bench_function("nonlinear_effects", |b| {
            b.iter(|| {
                let (q, v, _) = next();
                black_box(nonlinear_effects(&model, &mut data, q, v).unwrap()[0])
            })
        });
        g.bench_function("crba", |b| {
            b.iter(|| black_box(crba(&model, &mut data, &next().0).unwrap()[0]))
        });
        g.bench_function("minverse", |b| {
            b.iter(|| black_box(compute_minverse(&model, &mut data, &next().0).unwrap()[0]))
        });
        g.bench_function("aba", |b| {
            b.iter(|| {
                let (q, v, a) = next();
                black_box(aba(&model, &mut data, q, v, a).unwrap()[0])
            })
        });
        g.bench_function("cholesky_fd", |b| {
            b.iter(|| {
                let (q, v, a) = next();
                black_box(forward_dynamics_cholesky(&model, &mut data, q, v, a).unwrap()[0])
            })
        });
        g.bench_function("rnea_derivatives", |b| {
            b.iter(|| {
                let (q, v, a) = next();
                black_box(
                    rnea_derivatives(&model, &mut data, q, v, a)
                        .unwrap()
                        .dtau_dq[0],
                )
            })
        });
        g.bench_function("aba_derivatives", |b| {
            b.iter(|| {
                let (q, v, a) = next();
                black_box(aba_derivatives(&model, &mut data, q, v, a).unwrap().dqdd_dq[0])
            })
        });
        g.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
