//! The generated explicit model (`rigid explicit MODEL --lang rust`, exact) against rigid's
//! recursive algorithms, in one run, on the same 1000 pre-drawn random states:
//!
//! | key | explicit | recursive |
//! | --- | --- | --- |
//! | `mass_matrix` / `crba` | `mass_matrix(q)` | [`crba`] |
//! | `gravity` / `gravity_torques` | `gravity(q)` | [`gravity_torques`] |
//! | `nle` / `nonlinear_effects` | `coriolis_centrifugal(q, v) + gravity(q)` | [`nonlinear_effects`] |
//! | `inverse_dynamics` / `rnea` | `M(q) a + c(q, v) + g(q)` | [`rnea`] |
//!
//! `cargo bench -p rigid --bench explicit`. The generated files are committed in
//! `benches/explicit/` (the test `explicit_bench_files_are_up_to_date` regenerates them and
//! says how). The UR5 comes from example-robot-data (its copy under `tests/fixtures/robots/`).
//!
//! With `EXPLICIT_JSON=1` the bench skips criterion and times like `rigid bench` (the median of
//! 21 passes over the 1000 states, the algorithms taking turns pass by pass) and prints one JSON
//! line per model, `{"model", "nq", "nv", "ns_per_call": {...}}` with the keys `crba`, `gravity`,
//! `nonlinear_effects`, `rnea` (rigid's recursive algorithms) and `explicit_mass_matrix`,
//! `explicit_gravity`, `explicit_nle`, `explicit_inverse_dynamics`: `bench/compare.py --explicit`
//! runs it in each round beside Pinocchio's timing program.

use criterion::{criterion_group, Criterion};
use rigid::multibody::*;
use std::hint::black_box;

#[path = "explicit/puma560.rs"]
mod puma560;
#[path = "../tests/it/explicit_support/mod.rs"]
mod support;
#[path = "explicit/ur5.rs"]
mod ur5;

const STATES: usize = 1000;

/// The generated functions of one model, for arrays of size `N`.
struct Generated<const N: usize> {
    mass_matrix: fn(&[f64; N]) -> [[f64; N]; N],
    coriolis_centrifugal: fn(&[f64; N], &[f64; N]) -> [f64; N],
    gravity: fn(&[f64; N]) -> [f64; N],
}

/// `STATES` pre-drawn random states `(q, v, a)`: `q` within the joint limits, `v`, `a` uniform in
/// `[-1, 1]`.
fn states<const N: usize>(model: &Model) -> Vec<([f64; N], [f64; N], [f64; N])> {
    let mut rng = Rng::new(7);
    (0..STATES)
        .map(|_| {
            let q = random_configuration(model, &mut rng);
            let v: [f64; N] = std::array::from_fn(|_| rng.uniform(-1.0, 1.0));
            let a: [f64; N] = std::array::from_fn(|_| rng.uniform(-1.0, 1.0));
            (q.try_into().expect("N joints"), v, a)
        })
        .collect()
}

fn bench_model<const N: usize>(c: &mut Criterion, name: &str, model: &Model, gen: &Generated<N>) {
    let states = states::<N>(model);
    let mut data = Data::new(model);
    let mut g = c.benchmark_group(format!("explicit/{name}"));
    let mut i = 0usize;
    let mut next = || {
        i = (i + 1) % STATES;
        &states[i]
    };
    g.bench_function("crba", |b| {
        b.iter(|| black_box(crba(model, &mut data, &next().0).unwrap()[0]))
    });
    g.bench_function("mass_matrix", |b| {
        b.iter(|| black_box((gen.mass_matrix)(&next().0)))
    });
    g.bench_function("gravity_torques", |b| {
        b.iter(|| black_box(gravity_torques(model, &mut data, &next().0).unwrap()[0]))
    });
    g.bench_function("gravity", |b| {
        b.iter(|| black_box((gen.gravity)(&next().0)))
    });
    g.bench_function("nonlinear_effects", |b| {
        b.iter(|| {
            let (q, v, _) = next();
            black_box(nonlinear_effects(model, &mut data, q, v).unwrap()[0])
        })
    });
    g.bench_function("nle", |b| {
        b.iter(|| {
            let (q, v, _) = next();
            let (cc, gg) = ((gen.coriolis_centrifugal)(q, v), (gen.gravity)(q));
            black_box(std::array::from_fn::<f64, N, _>(|k| cc[k] + gg[k]))
        })
    });
    g.bench_function("rnea", |b| {
        b.iter(|| {
            let (q, v, a) = next();
            black_box(rnea(model, &mut data, q, v, a).unwrap()[0])
        })
    });
    g.bench_function("inverse_dynamics", |b| {
        b.iter(|| {
            let (q, v, a) = next();
            let (m, cc, gg) = (
                (gen.mass_matrix)(q),
                (gen.coriolis_centrifugal)(q, v),
                (gen.gravity)(q),
            );
            black_box(std::array::from_fn::<f64, N, _>(|k| {
                (0..N).map(|j| m[k][j] * a[j]).sum::<f64>() + cc[k] + gg[k]
            }))
        })
    });
    g.finish();
}

fn bench(c: &mut Criterion) {
    let puma = Generated::<6> {
        mass_matrix: puma560::mass_matrix,
        coriolis_centrifugal: puma560::coriolis_centrifugal,
        gravity: puma560::gravity,
    };
    bench_model(c, "puma560", &puma560(Puma560Options::default()), &puma);
    let ur = Generated::<6> {
        mass_matrix: ur5::mass_matrix,
        coriolis_centrifugal: ur5::coriolis_centrifugal,
        gravity: ur5::gravity,
    };
    bench_model(c, "ur5", &support::ur5(), &ur);
}

/// `rigid bench`'s method: per algorithm the median over `REPS` passes of (pass time / states),
/// the algorithms taking turns pass by pass, after one warm-up pass each.
fn json_timing<const N: usize>(name: &str, model: &Model, gen: &Generated<N>) {
    const REPS: usize = 21;
    let states = states::<N>(model);
    let mut data = Data::new(model);
    type Pass<'a, const N: usize> = Box<dyn FnMut(&([f64; N], [f64; N], [f64; N]), &mut Data) + 'a>;
    let mut algos: Vec<(&str, Pass<N>)> = vec![
        (
            "crba",
            Box::new(|s, d| {
                black_box(crba(model, d, &s.0).unwrap()[0]);
            }),
        ),
        (
            "gravity",
            Box::new(|s, d| {
                black_box(gravity_torques(model, d, &s.0).unwrap()[0]);
            }),
        ),
        (
            "nonlinear_effects",
            Box::new(|s, d| {
                black_box(nonlinear_effects(model, d, &s.0, &s.1).unwrap()[0]);
            }),
        ),
        (
            "rnea",
            Box::new(|s, d| {
                black_box(rnea(model, d, &s.0, &s.1, &s.2).unwrap()[0]);
            }),
        ),
        (
            "explicit_mass_matrix",
            Box::new(|s, _| {
                black_box((gen.mass_matrix)(&s.0));
            }),
        ),
        (
            "explicit_gravity",
            Box::new(|s, _| {
                black_box((gen.gravity)(&s.0));
            }),
        ),
        (
            "explicit_nle",
            Box::new(|s, _| {
                let (cc, gg) = ((gen.coriolis_centrifugal)(&s.0, &s.1), (gen.gravity)(&s.0));
                black_box(std::array::from_fn::<f64, N, _>(|k| cc[k] + gg[k]));
            }),
        ),
        (
            "explicit_inverse_dynamics",
            Box::new(|s, _| {
                let (m, cc, gg) = (
                    (gen.mass_matrix)(&s.0),
                    (gen.coriolis_centrifugal)(&s.0, &s.1),
                    (gen.gravity)(&s.0),
                );
                black_box(std::array::from_fn::<f64, N, _>(|k| {
                    (0..N).map(|j| m[k][j] * s.2[j]).sum::<f64>() + cc[k] + gg[k]
                }));
            }),
        ),
    ];
    let mut samples = vec![Vec::with_capacity(REPS); algos.len()];
    for rep in 0..=REPS {
        for (k, (_, f)) in algos.iter_mut().enumerate() {
            let t = std::time::Instant::now();
            for s in &states {
                f(s, &mut data);
            }
            if rep > 0 {
                samples[k].push(t.elapsed().as_secs_f64() * 1e9 / STATES as f64);
            }
        }
    }
    let fields: Vec<String> = algos
        .iter()
        .zip(&mut samples)
        .map(|((key, _), s)| {
            s.sort_by(f64::total_cmp);
            format!("\"{key}\": {:.2}", s[REPS / 2])
        })
        .collect();
    println!(
        "{{\"model\": \"{name}\", \"nq\": {N}, \"nv\": {N}, \"ns_per_call\": {{{}}}}}",
        fields.join(", ")
    );
}

criterion_group!(benches, bench);

fn main() {
    if std::env::var("EXPLICIT_JSON").is_ok_and(|v| v == "1") {
        json_timing(
            "puma560",
            &puma560(Puma560Options::default()),
            &Generated::<6> {
                mass_matrix: puma560::mass_matrix,
                coriolis_centrifugal: puma560::coriolis_centrifugal,
                gravity: puma560::gravity,
            },
        );
        json_timing(
            "ur5",
            &support::ur5(),
            &Generated::<6> {
                mass_matrix: ur5::mass_matrix,
                coriolis_centrifugal: ur5::coriolis_centrifugal,
                gravity: ur5::gravity,
            },
        );
        return;
    }
    benches();
    Criterion::default().configure_from_args().final_summary();
}
