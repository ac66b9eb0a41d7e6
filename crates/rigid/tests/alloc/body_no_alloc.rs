//! The simulator's step allocates nothing: the counting global allocator of this test binary
//! sees no allocation on the simulating thread across thousands of steps of either integrator.

use crate::allocations;
use rigid::body::{Integrator, RigidBody, Simulator, State};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::spatial::{Transform, Twist, Vec3};

#[test]
fn simulator_steps_do_not_allocate() {
    // The counter works: a Vec allocates once.
    let before = allocations();
    let v: Vec<u8> = Vec::with_capacity(16);
    assert_eq!(allocations(), before + 1);
    drop(v);
    let g = SpatialInertia::from_com(
        1.0,
        Vec3::new(0.0, 0.0, 0.2),
        RotationalInertia::diagonal(1.0, 2.0, 2.5),
    );
    let gravity = Vec3::new(0.0, 0.0, -9.81);
    let x0 = State::new(
        Transform::identity(),
        Twist::new(Vec3::new(0.3, 1.0, -2.0), Vec3::zeros()),
    );
    for body in [RigidBody::free(g).unwrap(), RigidBody::pivot(g).unwrap()] {
        let body = body.with_gravity(gravity).unwrap();
        for integrator in [Integrator::Rk4, Integrator::Lgvi] {
            let mut sim = Simulator::new(body.clone(), x0, integrator, 1e-3).unwrap();
            let before = allocations();
            for _ in 0..5000 {
                sim.step().unwrap();
            }
            let after = allocations();
            assert_eq!(
                after,
                before,
                "{integrator}: {} allocations",
                after - before
            );
        }
    }
}
