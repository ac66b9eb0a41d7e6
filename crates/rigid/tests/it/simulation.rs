//! The claims of the multibody simulator (`rigid::simulation`):
//!
//! - energy and momentum: UR5 and Talos on a free-flyer, no gravity, no damping, from a random
//!   state, 10 s at 1 ms: the variational integrator keeps the energy to 1e-6 (relative, at
//!   every 0.1 s) and the world spatial momentum to 1e-10;
//! - RK4 converges at 4th order on the manifold (error ratio ≈ 16 when dt halves), semi-implicit
//!   Euler at 1st order, the variational integrator at 4th;
//! - the double pendulum under gravity matches SciPy's `solve_ivp` (DOP853 at 1e-12) on the
//!   closed-form equations (`tests/simulation/double_pendulum.py`) to 1e-8 over 5 s: its
//!   checked-in trajectory (`tests/simulation/double_pendulum.json`, written by
//!   `gen_double_pendulum.py` beside it), and with `RIGID_CROSSCHECK=1` the script run live too;
//! - gravity compensation holds the Panda still (drift < 1e-9 rad over 10 s); computed torque
//!   tracks a quintic trajectory with an error below 1e-6 rad;
//! - a batch of simulations gives the single runs bit for bit on 1 and 2 threads.
//!
//! The robots are example-robot-data's, from the copies under `tests/fixtures/robots/`.

use rigid::io::urdf::load_urdf;
use rigid::multibody::{builtin, difference, random_configuration, Model, Rng};
use rigid::simulation::{
    simulate_batch, ControlLaw, Controller, Integrator, JointTrajectory, SimulationOptions,
    Simulator, TimeScaling,
};

fn robot(rel: &str, floating: bool) -> Model {
    load_urdf(common::example_robot_data().join(rel), floating).unwrap()
}

/// A random state: `q` within the limits, `v` uniform in [-1, 1] per dof.
fn random_state(model: &Model, seed: u64) -> (Vec<f64>, Vec<f64>) {
    let mut rng = Rng::new(seed);
    let q = random_configuration(model, &mut rng);
    let v = (0..model.nv()).map(|_| rng.uniform(-1.0, 1.0)).collect();
    (q, v)
}

/// Max relative energy error and momentum error over 10 s at 1 ms, sampled every 0.1 s.
fn conservation(model: &Model, integrator: Integrator) -> (f64, f64) {
    let model = model.clone().with_gravity(Default::default());
    let (q0, v0) = random_state(&model, 4);
    let opts = SimulationOptions::conservative(1e-3, integrator);
    let mut sim = Simulator::new(&model, &q0, &v0, opts, Controller::none(&model)).unwrap();
    let e0 = sim.energy().unwrap();
    let h0 = sim.momentum().unwrap().to_vector();
    let (mut de, mut dh) = (0.0f64, 0.0f64);
    for _ in 0..100 {
        sim.run(100, |_| {}).unwrap();
        de = de.max((sim.energy().unwrap() - e0).abs() / e0.abs());
        dh = dh.max((sim.momentum().unwrap().to_vector() - h0).norm() / h0.norm());
    }
    (de, dh)
}

#[test]
fn variational_keeps_energy_and_momentum_of_free_floating_ur5_and_talos() {
    for (name, rel) in [
        ("ur5", "ur_description/urdf/ur5_robot.urdf"),
        ("talos", "talos_data/robots/talos_reduced.urdf"),
    ] {
        let model = robot(rel, true);
        let (de, dh) = conservation(&model, Integrator::Variational);
        eprintln!(
            "{name} (nv = {}): variational energy {de:.2e}, momentum {dh:.2e}",
            model.nv()
        );
        assert!(de <= 1e-6, "{name}: relative energy drift {de:e}");
        assert!(dh <= 1e-10, "{name}: relative momentum error {dh:e}");
    }
}

/// The error at `T` of a run with step `h` against a run with step `h/32`, on the manifold
/// (`q ⊖ q_ref` and `v - v_ref`, max norm).
fn error_at(
    model: &Model,
    integrator: Integrator,
    q0: &[f64],
    v0: &[f64],
    h: f64,
    t_end: f64,
) -> f64 {
    let run = |h: f64| {
        let opts = SimulationOptions::conservative(h, integrator);
        let mut sim = Simulator::new(model, q0, v0, opts, Controller::none(model)).unwrap();
        sim.run((t_end / h).round() as u64, |_| {}).unwrap();
        (sim.q().to_vec(), sim.v().to_vec())
    };
    let (q, v) = run(h);
    let (qr, vr) = run(h / 32.0);
    let mut dq = vec![0.0; model.nv()];
    difference(model, &qr, &q, &mut dq).unwrap();
    dq.iter()
        .chain(
            v.iter()
                .zip(&vr)
                .map(|(a, b)| a - b)
                .collect::<Vec<_>>()
                .iter(),
        )
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

#[test]
fn rk4_and_variational_converge_at_fourth_order_and_euler_at_first() {
    // a free-floating random tree (free-flyer, spherical, planar, revolute, prismatic joints)
    // under gravity: the stages live on SE(3), SO(3) and SE(2)
    let model = common_tree();
    let (q0, v0) = random_state(&model, 9);
    for (integrator, order, hs) in [
        (Integrator::Rk4, 4.0, [0.02, 0.01]),
        (Integrator::Variational, 4.0, [0.02, 0.01]),
        (Integrator::SemiImplicitEuler, 1.0, [0.002, 0.001]),
    ] {
        let e1 = error_at(&model, integrator, &q0, &v0, hs[0], 0.4);
        let e2 = error_at(&model, integrator, &q0, &v0, hs[1], 0.4);
        let ratio = e1 / e2;
        let expected = 2f64.powf(order);
        eprintln!(
            "{integrator}: error {e1:.3e} -> {e2:.3e}, ratio {ratio:.2} (expected {expected})"
        );
        assert!(
            (ratio / expected - 1.0).abs() < 0.25,
            "{integrator}: ratio {ratio} not ≈ {expected}"
        );
    }
}

use crate::common;

fn common_tree() -> Model {
    common::random_tree(21, 6, true)
}

/// SciPy's trajectories of the double pendulum: the checked-in one and, with
/// `RIGID_CROSSCHECK=1`, the script's output now; each with where it comes from.
fn double_pendulum_references() -> Vec<(&'static str, serde_json::Value)> {
    let fixture = common::reference::fixture("simulation/double_pendulum.json");
    let args = ["0.5", "-0.3", "0.2", "0", "5", "50"];
    assert_eq!(
        fixture["args"],
        serde_json::json!(args),
        "tests/simulation/double_pendulum.json is of another run: regenerate it"
    );
    let mut out = vec![("fixture", fixture)];
    if common::reference::live("the double pendulum against SciPy live") {
        let live = common::reference::run_script("simulation/double_pendulum.py", &args);
        out.push(("live", serde_json::from_slice(&live).unwrap()));
    }
    out
}

#[test]
fn double_pendulum_matches_scipy_to_1e_8_over_5_s() {
    let (q0, v0) = ([0.5, -0.3], [0.2, 0.0]);
    for (source, reference) in double_pendulum_references() {
        let rows = |k: &str| -> Vec<Vec<f64>> {
            reference[k]
                .as_array()
                .unwrap()
                .iter()
                .map(|r| {
                    r.as_array()
                        .unwrap()
                        .iter()
                        .map(|x| x.as_f64().unwrap())
                        .collect()
                })
                .collect()
        };
        let (qs, vs) = (rows("q"), rows("v"));
        assert_eq!(qs.len(), 51, "{source}: 0.1 s samples over 5 s");
        let model = builtin("double_pendulum").unwrap();
        let dt = 1e-3;
        let opts = SimulationOptions::conservative(dt, Integrator::Rk4);
        let mut sim = Simulator::new(&model, &q0, &v0, opts, Controller::none(&model)).unwrap();
        let mut worst = 0.0f64;
        for (k, (q, v)) in qs.iter().zip(&vs).enumerate() {
            if k > 0 {
                sim.run(100, |_| {}).unwrap(); // 0.1 s
            }
            for i in 0..2 {
                worst = worst
                    .max((sim.q()[i] - q[i]).abs())
                    .max((sim.v()[i] - v[i]).abs());
            }
        }
        eprintln!(
            "double pendulum, RK4 at 1 ms vs SciPy ({source}) over 5 s: max error {worst:.2e}"
        );
        assert!(worst < 1e-8, "{source}: {worst:e}");
    }
}

#[test]
fn gravity_compensation_holds_the_panda_and_computed_torque_tracks_a_quintic() {
    let model = robot("panda_description/urdf/panda.urdf", false);
    let mut rng = Rng::new(12);
    let q0 = random_configuration(&model, &mut rng);
    let zeros = vec![0.0; model.nv()];
    let opts = SimulationOptions::default(); // RK4, 1 ms, damping, friction and limits on
    let ctrl = Controller::new(&model, ControlLaw::GravityCompensation).unwrap();
    let mut sim = Simulator::new(&model, &q0, &zeros, opts, ctrl).unwrap();
    let mut drift = 0.0f64;
    sim.run(10_000, |s| {
        drift = s
            .q()
            .iter()
            .zip(&q0)
            .fold(drift, |m, (a, b)| m.max((a - b).abs()));
    })
    .unwrap();
    eprintln!("panda, gravity compensation, 10 s: max drift {drift:.2e} rad");
    assert!(drift < 1e-9, "{drift:e}");

    let q1 = random_configuration(&model, &mut rng);
    let trajectory = JointTrajectory::new(&model, &q0, &q1, 2.0, TimeScaling::Quintic).unwrap();
    let law = ControlLaw::ComputedTorque {
        trajectory: trajectory.clone(),
        kp: 100.0,
        kd: 20.0,
    };
    // the controller's model is the rigid-body model: no joint damping or friction in the plant
    let plant = SimulationOptions {
        joint_dynamics: false,
        ..opts
    };
    let mut sim = Simulator::new(
        &model,
        &q0,
        &zeros,
        plant,
        Controller::new(&model, law).unwrap(),
    )
    .unwrap();
    let (mut qd, mut vd, mut ad) = (vec![0.0; model.nq()], zeros.clone(), zeros.clone());
    let mut e = zeros.clone();
    let mut worst = 0.0f64;
    sim.run(3000, |s| {
        trajectory.sample(&model, s.time(), &mut qd, &mut vd, &mut ad);
        difference(&model, s.q(), &qd, &mut e).unwrap();
        worst = e.iter().fold(worst, |m, x| m.max(x.abs()));
    })
    .unwrap();
    let travel = q0
        .iter()
        .zip(&q1)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    eprintln!(
        "panda, computed torque on a 2 s quintic ({travel:.2} rad): max error {worst:.2e} rad"
    );
    assert!(worst < 1e-6, "{worst:e}");
    assert!(travel > 0.5);
}

#[test]
fn batch_gives_the_single_runs_bit_for_bit() {
    let model = common_tree();
    let (nq, nv, n) = (model.nq(), model.nv(), 5);
    let (mut q0s, mut v0s) = (Vec::new(), Vec::new());
    for k in 0..n {
        let (q, v) = random_state(&model, 100 + k as u64);
        q0s.extend(q);
        v0s.extend(v);
    }
    let opts = SimulationOptions::default();
    let single: Vec<(Vec<f64>, Vec<f64>)> = (0..n)
        .map(|k| {
            let mut s = Simulator::new(
                &model,
                &q0s[k * nq..(k + 1) * nq],
                &v0s[k * nv..(k + 1) * nv],
                opts,
                Controller::none(&model),
            )
            .unwrap();
            s.run(50, |_| {}).unwrap();
            (s.q().to_vec(), s.v().to_vec())
        })
        .collect();
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let (mut qs, mut vs) = (vec![0.0; n * nq], vec![0.0; n * nv]);
        pool.install(|| {
            simulate_batch(
                &model,
                &q0s,
                &v0s,
                opts,
                50,
                |_| Controller::none(&model),
                &mut qs,
                &mut vs,
            )
        })
        .unwrap();
        for (k, (q, v)) in single.iter().enumerate() {
            assert_eq!(&qs[k * nq..(k + 1) * nq], q.as_slice());
            assert_eq!(&vs[k * nv..(k + 1) * nv], v.as_slice());
        }
    }
}

/// A pendulum with a limit spring, damping and friction, and an external wrench: the limit
/// holds (penetration a few degrees at 5 rad/s), damping and friction only take energy out, and
/// a pure moment on the body acts as the same joint torque.
#[test]
fn limits_damping_friction_and_external_wrenches_act_as_documented() {
    use rigid::multibody::{JointId, JointType, ModelBuilder};
    use rigid::simulation::JointLimits;
    use rigid::spatial::{Transform, Vec3, Wrench};
    let build = |damping: f64, friction: f64| {
        let rod = *builtin("pendulum").unwrap().inertia(JointId(0));
        let mut b = ModelBuilder::new("p");
        let j = b
            .add_joint(
                None,
                "j",
                JointType::Revolute { axis: Vec3::y() },
                Transform::identity(),
                rod,
            )
            .unwrap();
        b.set_limits(j, &[-0.1], &[0.1], &[10.0], &[10.0]).unwrap();
        b.set_joint_dynamics(j, &[damping], &[friction]).unwrap();
        b.build().unwrap().with_gravity(Vec3::zeros())
    };
    let model = build(0.0, 0.0);
    // the limit
    for (limits, inside) in [
        (JointLimits::default(), true),
        (JointLimits::Ignored, false),
    ] {
        let opts = SimulationOptions {
            limits,
            ..Default::default()
        };
        let mut sim =
            Simulator::new(&model, &[0.0], &[5.0], opts, Controller::none(&model)).unwrap();
        let mut worst = 0.0f64;
        sim.run(1000, |s| worst = worst.max(s.q()[0].abs()))
            .unwrap();
        eprintln!("{limits:?}: max |q| = {worst:.4}");
        assert_eq!(worst < 0.1 + 0.1, inside, "{limits:?}: {worst}");
    }
    // damping and friction take energy out, monotonically
    let model = build(0.05, 0.02);
    let mut sim = Simulator::new(
        &model,
        &[0.0],
        &[1.0],
        SimulationOptions::conservative(1e-3, Integrator::Rk4),
        Controller::none(&model),
    )
    .unwrap();
    let opts = SimulationOptions {
        limits: JointLimits::Ignored,
        ..Default::default()
    };
    let mut damped =
        Simulator::new(&model, &[0.0], &[1.0], opts, Controller::none(&model)).unwrap();
    let (e0, mut last) = (sim.energy().unwrap(), f64::INFINITY);
    for _ in 0..20 {
        damped.run(50, |_| {}).unwrap();
        sim.run(50, |_| {}).unwrap();
        let e = damped.energy().unwrap();
        assert!(e < last);
        last = e;
    }
    assert!(
        (sim.energy().unwrap() - e0).abs() < 1e-12 * e0,
        "conservative without joint dynamics"
    );
    assert!(last < 0.8 * e0, "{last} vs {e0}");
    // a pure moment of 0.3 N·m about the joint axis = a joint torque of 0.3 N·m
    let model = build(0.0, 0.0);
    let opts = SimulationOptions::conservative(1e-3, Integrator::Rk4);
    let mut a = Simulator::new(&model, &[0.0], &[0.0], opts, Controller::none(&model)).unwrap();
    a.set_external_wrench(
        JointId(0),
        Wrench::new(Vec3::new(0.0, 0.3, 0.0), Vec3::zeros()),
    )
    .unwrap();
    let torque = |_t: f64, _q: &[f64], _v: &[f64], tau: &mut [f64]| tau[0] = 0.3;
    let mut b = Simulator::new(&model, &[0.0], &[0.0], opts, torque).unwrap();
    a.run(500, |_| {}).unwrap();
    b.run(500, |_| {}).unwrap();
    assert!((a.q()[0] - b.q()[0]).abs() < 1e-14 && a.q()[0] > 0.1);
}
