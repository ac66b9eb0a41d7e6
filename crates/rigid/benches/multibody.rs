//! Multibody algorithms, ns per call: forward kinematics, joint Jacobians, RNEA, gravity,
//! nonlinear effects, CRBA, `M⁻¹`, ABA and Cholesky forward dynamics, each cycling through 1000
//! pre-drawn random states (so that branch prediction is not flattered).
//!
//! `cargo bench -p rigid --bench multibody [-- FILTER]`. Models: the built-in `puma560` and the
//! robots of `example-robot-data` (UR5, Panda; Solo-12, ANYmal and Talos with a free-flyer
//! root), found under `$EXAMPLE_ROBOT_DATA` (the `robots/` folder) or through `python3`'s
//! `cmeel.prefix`; a robot whose URDF is not found is skipped with a note on stderr.

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
    //! The example-robot-data URDFs: `$EXAMPLE_ROBOT_DATA` (its `robots/` folder), or the
    //! `cmeel.prefix/share/example-robot-data/robots` folder of `python3`'s site-packages.
    use rigid::io::urdf::load_urdf;
    use rigid::multibody::Model;
    use std::path::PathBuf;

    /// `(name, file under robots/, free-flyer root)`.
    const ROBOTS: [(&str, &str, bool); 5] = [
        ("ur5", "ur_description/urdf/ur5_robot.urdf", false),
        ("panda", "panda_description/urdf/panda.urdf", false),
        ("solo12", "solo_description/robots/solo12.urdf", true),
        (
            "anymal",
            "anymal_b_simple_description/robots/anymal.urdf",
            true,
        ),
        ("talos", "talos_data/robots/talos_reduced.urdf", true),
    ];

    fn robots_dir() -> Option<PathBuf> {
        if let Some(d) = std::env::var_os("EXAMPLE_ROBOT_DATA") {
            return Some(d.into());
        }
        let out = std::process::Command::new("python3")
            .args([
                "-c",
                "import site, sysconfig; print('\\n'.join(site.getsitepackages() + [sysconfig.get_paths()['purelib']]))",
            ])
            .output()
            .ok()?;
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .map(|sp| PathBuf::from(sp).join("cmeel.prefix/share/example-robot-data/robots"))
            .find(|p| p.is_dir())
    }

    /// `(name, model)` of every robot found; notes on stderr for the others.
    pub fn load_all() -> Vec<(String, Model)> {
        let Some(dir) = robots_dir() else {
            eprintln!(
                "note: example-robot-data not found (set EXAMPLE_ROBOT_DATA): robots skipped"
            );
            return Vec::new();
        };
        ROBOTS
            .iter()
            .filter_map(
                |&(name, file, floating)| match load_urdf(dir.join(file), floating) {
                    Ok(m) => Some((name.to_string(), m)),
                    Err(e) => {
                        eprintln!("note: {name} skipped: {e}");
                        None
                    }
                },
            )
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
