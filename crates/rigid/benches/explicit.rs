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
//! says how). The UR5 comes from example-robot-data (`scripts/test.sh` installs it).

use criterion::{criterion_group, criterion_main, Criterion};
use rigid::multibody::*;
use std::hint::black_box;

#[path = "explicit/puma560.rs"]
mod puma560;
#[path = "../tests/explicit_support/mod.rs"]
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

fn bench_model<const N: usize>(c: &mut Criterion, name: &str, model: &Model, gen: &Generated<N>) {
    let mut rng = Rng::new(7);
    let states: Vec<([f64; N], [f64; N], [f64; N])> = (0..STATES)
        .map(|_| {
            let q = random_configuration(model, &mut rng);
            let v: [f64; N] = std::array::from_fn(|_| rng.uniform(-1.0, 1.0));
            let a: [f64; N] = std::array::from_fn(|_| rng.uniform(-1.0, 1.0));
            (q.try_into().expect("N joints"), v, a)
        })
        .collect();
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

criterion_group!(benches, bench);
criterion_main!(benches);
