//! The derivatives of one simulation step with contacts against central differences of the
//! step, in Rust alone: Solo-12 (example-robot-data's URDF, mesh feet) settled on its four feet
//! by the stance controller for 0.3 s, its torque then held open-loop. Central differences take
//! `2 · 3 · nv` steps (q, v and τ, each way); the time of one step is measured from the same
//! state (`set_state` then `step`). Fastest of 11 batches of 500 calls each.
//! Run with `cargo run --release -p rigid --example step_derivatives_timing`.

use rigid::collision::place_on_ground;
use rigid::io::collision::{ground_model, urdf_geometries};
use rigid::io::urdf::{load_urdf, parse_urdf_file};
use rigid::simulation::{
    ControlLaw, Controller, Integrator, OpenLoop, SimulationOptions, Simulator,
};
use std::hint::black_box;
use std::time::Instant;

/// The fastest per-call time (s) of 11 batches of `n` calls of `f`.
fn fastest(n: usize, mut f: impl FnMut()) -> f64 {
    (0..11)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..n {
                f();
            }
            t.elapsed().as_secs_f64() / n as f64
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/robots/example-robot-data/robots/solo_description/robots/solo12.urdf"
    );
    let model = load_urdf(path, true).unwrap();
    let robot = parse_urdf_file(path).unwrap();
    let (geometries, _) = urdf_geometries(&robot, &model);
    let cm = ground_model(Some(0.0), Some(0.9), None, geometries).unwrap();
    let mut q = vec![
        0.0, 0.0, 0.3, 0.0, 0.0, 0.0, 1.0, 0.1, 0.8, -1.6, -0.1, 0.8, -1.6, 0.1, -0.8, 1.6, -0.1,
        -0.8, 1.6,
    ];
    place_on_ground(&model, &cm, &mut q).unwrap();
    let opts = SimulationOptions {
        dt: 1e-3,
        integrator: Integrator::SemiImplicitEuler,
        ..Default::default()
    };
    let nv = model.nv();
    let law = Controller::new(&model, ControlLaw::standing(&model, &q, &cm).unwrap()).unwrap();
    let mut stand = Simulator::new(&model, &q, &vec![0.0; nv], opts, law)
        .unwrap()
        .with_collision(cm.clone())
        .unwrap();
    stand.run(300, |_| {}).unwrap();
    let tau = stand.torques().unwrap().0.to_vec();
    let (q0, v0) = (stand.q().to_vec(), stand.v().to_vec());
    let mut sim = Simulator::new(&model, &q0, &v0, opts, OpenLoop(tau))
        .unwrap()
        .with_collision(cm)
        .unwrap();
    let mut other = sim.clone();
    let td = fastest(500, || {
        black_box(sim.step_derivatives().unwrap());
    });
    let ts = fastest(500, || {
        other.set_state(&q0, &v0).unwrap();
        other.step().unwrap();
        black_box(other.q()[0]);
    });
    let steps = 6 * nv;
    println!(
        "Solo-12 standing: step_derivatives {:.1} µs; one step {:.1} µs, central differences \
         ({steps} steps) {:.1} µs; ratio {:.3}",
        td * 1e6,
        ts * 1e6,
        ts * steps as f64 * 1e6,
        td / (ts * steps as f64)
    );
}
