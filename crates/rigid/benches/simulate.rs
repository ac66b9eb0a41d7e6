//! Simulator steps per second for each integrator: a tumbling free body and a heavy top on a
//! pivot. `cargo bench -p rigid --bench simulate`; throughput is reported in steps/s
//! (criterion's "elem/s").

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use rigid::body::{Integrator, RigidBody, Simulator, State};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::spatial::{so3, Transform, Twist, Vec3};
use std::hint::black_box;

const STEPS: u64 = 1000;

fn bodies() -> [(&'static str, RigidBody, State); 2] {
    let free = SpatialInertia::from_com(
        2.0,
        Vec3::zeros(),
        RotationalInertia::diagonal(1.0, 2.0, 3.0),
    );
    let top = SpatialInertia::from_com(
        1.0,
        Vec3::new(0.0, 0.0, 0.1),
        RotationalInertia::diagonal(0.005, 0.005, 0.01),
    );
    [
        (
            "free",
            RigidBody::free(free).unwrap(),
            State::new(
                Transform::identity(),
                Twist::new(Vec3::new(0.1, 2.0, 0.1), Vec3::new(1.0, 0.0, 0.0)),
            ),
        ),
        (
            "top",
            RigidBody::pivot(top)
                .unwrap()
                .with_gravity(Vec3::new(0.0, 0.0, -9.81))
                .unwrap(),
            State::new(
                Transform::from_rotation(so3::exp(&Vec3::new(0.5, 0.0, 0.0))),
                Twist::new(Vec3::new(0.0, 0.0, 150.0), Vec3::zeros()),
            ),
        ),
    ]
}

fn steps_per_second(c: &mut Criterion) {
    let mut group = c.benchmark_group("simulate");
    group.throughput(Throughput::Elements(STEPS));
    for (name, body, x0) in bodies() {
        for integrator in [Integrator::Rk4, Integrator::Lgvi, Integrator::Variational] {
            group.bench_with_input(BenchmarkId::new(integrator.name(), name), &x0, |b, x0| {
                b.iter(|| {
                    let mut sim = Simulator::new(body.clone(), *x0, integrator, 1e-3).unwrap();
                    for _ in 0..STEPS {
                        sim.step().unwrap();
                    }
                    black_box(*sim.state())
                });
            });
        }
    }
    group.finish();
}

criterion_group!(benches, steps_per_second);
criterion_main!(benches);
