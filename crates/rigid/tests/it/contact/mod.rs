//! Contacts with friction (`simulation::contact`, `collision`): the closed forms of mechanics
//! (a box sliding to a stop, a ball rolling or slipping down a slope, bounces of restitution
//! `e`, a box and a tower of boxes at rest), kinetic energy never made by a contact, unilateral
//! joint limits, and robots standing on the ground (Solo-12, ANYmal, TALOS).

#![allow(non_snake_case)]

mod closed_form;
mod energy;
mod proximity;
mod robots;
mod solvers;
mod step_derivatives;
mod step_derivatives_pairs;
mod wheels;
mod world;

use rigid::collision::{CollisionModel, Geometry, Ground, Shape};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::multibody::{JointId, JointType, Model, ModelBuilder};
use rigid::simulation::{Controller, Integrator, SimulationOptions, Simulator};
use rigid::spatial::{so3, Mat3, Transform, Vec3};

/// Standard gravity in the tests (m/s²).
pub const G: f64 = 9.81;

/// A free body of the world: its mass, inertia about the CoM and collision shape.
#[derive(Clone)]
pub struct Free {
    pub mass: f64,
    pub inertia: RotationalInertia,
    pub shape: Shape,
}

impl Free {
    /// A solid box of edges `size`.
    pub fn cube(mass: f64, size: Vec3) -> Self {
        let (a, b, c) = (size.x * size.x, size.y * size.y, size.z * size.z);
        Self {
            mass,
            inertia: RotationalInertia::diagonal(
                mass * (b + c) / 12.0,
                mass * (a + c) / 12.0,
                mass * (a + b) / 12.0,
            ),
            shape: Shape::Box { size },
        }
    }

    /// A solid ball.
    pub fn ball(mass: f64, radius: f64) -> Self {
        let i = 0.4 * mass * radius * radius;
        Self {
            mass,
            inertia: RotationalInertia::diagonal(i, i, i),
            shape: Shape::Sphere { radius },
        }
    }
}

/// A model of free bodies (one free-flyer each, frames at the CoMs) under `gravity`, and their
/// collision model with `ground`.
pub fn scene(bodies: &[Free], gravity: Vec3, ground: Option<Ground>) -> (Model, CollisionModel) {
    let mut b = ModelBuilder::new("scene");
    let mut cm = CollisionModel::new(ground);
    for (i, f) in bodies.iter().enumerate() {
        let g = SpatialInertia::from_com(f.mass, Vec3::zeros(), f.inertia);
        let name = format!("body{i}");
        let j = b
            .add_joint(None, &name, JointType::FreeFlyer, Transform::identity(), g)
            .unwrap();
        assert_eq!(j, JointId(i));
        cm.geometries.push(Geometry::new(
            name,
            Some(j),
            Transform::identity(),
            f.shape.clone(),
        ));
    }
    (b.build().unwrap().with_gravity(gravity), cm)
}

/// The free-flyer configuration `(p, quaternion)` of a pose.
pub fn q_of(p: Vec3, r: &Mat3) -> Vec<f64> {
    let mut q = vec![p.x, p.y, p.z];
    q.extend_from_slice(&rigid::spatial::so3::to_quaternion(r));
    q
}

/// The time-stepping options at `dt`, without joint friction.
pub fn options(dt: f64) -> SimulationOptions {
    SimulationOptions {
        dt,
        integrator: Integrator::SemiImplicitEuler,
        joint_dynamics: false,
        ..SimulationOptions::default()
    }
}

/// A simulator of the scene from `q0`, `v0` (body twists), no control.
pub fn simulator(model: &Model, cm: CollisionModel, q0: &[f64], v0: &[f64], dt: f64) -> Simulator {
    Simulator::new(model, q0, v0, options(dt), Controller::none(model))
        .unwrap()
        .with_collision(cm)
        .unwrap()
}

/// Free-flyer `i`'s CoM position and world velocity.
pub fn com(sim: &Simulator, i: usize) -> (Vec3, Vec3) {
    let (q, v) = (&sim.q()[7 * i..7 * i + 7], &sim.v()[6 * i..6 * i + 6]);
    let r = so3::from_quaternion(q[3], q[4], q[5], q[6], 1e-6).unwrap();
    (Vec3::new(q[0], q[1], q[2]), r * Vec3::new(v[3], v[4], v[5]))
}
