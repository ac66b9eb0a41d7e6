//! After `Data::new` and `ConstraintData::new`, the constrained algorithms allocate nothing:
//! `constraint_dynamics` (exact and proximal), `impulse_dynamics`, `contact_inverse_dynamics`,
//! their derivatives (after their workspaces are made), and a step of the simulator with a closed loop, smooth or with a ground contact (counted by
//! this binary's allocator, per thread).

use super::allocations_in as allocations;
use rigid::io::urdf::{load_urdf_with, SiblingOrder, UrdfOptions};
use rigid::multibody::constraints::{
    constraint_dynamics, constraint_dynamics_derivatives, contact_inverse_dynamics,
    impulse_dynamics, impulse_dynamics_derivatives, ConstraintData, ConstraintDynamicsDerivatives,
    ConstraintKind, ConstraintModel, ImpulseDynamicsDerivatives, ProximalSettings,
};
use rigid::multibody::{neutral, Data};
use rigid::simulation::{
    ConstraintOptions, Controller, Integrator, JointLimits, SimulationOptions, Simulator,
};
use rigid::spatial::{Transform, Vec3};

fn load(rel: &str, floating: bool) -> rigid::multibody::Model {
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures");
    let opts = UrdfOptions {
        floating,
        sibling_order: SiblingOrder::Name,
        ..UrdfOptions::default()
    };
    load_urdf_with(dir.join(rel), &opts).unwrap().0
}

#[test]
fn constrained_algorithms_allocate_nothing() {
    let talos = load(
        "robots/example-robot-data/robots/talos_data/robots/talos_reduced.urdf",
        true,
    );
    let feet: Vec<ConstraintModel> = ["left_sole_link", "right_sole_link"]
        .iter()
        .map(|f| {
            ConstraintModel::on_frames(&talos, ConstraintKind::Frame, f, "universe")
                .unwrap()
                .with_baumgarte(10.0, 2.0)
        })
        .collect();
    let mut data = Data::new(&talos);
    let mut cd = ConstraintData::new(&talos, &feet).unwrap();
    let q = neutral(&talos);
    let nv = talos.nv();
    let v: Vec<f64> = (0..nv).map(|k| 0.1 * (k as f64).sin()).collect();
    let tau = vec![0.5; nv];
    let exact = ProximalSettings::default();
    let prox = ProximalSettings::new(1e-12, 1e-4, 20);
    let n = allocations(|| {
        constraint_dynamics(&talos, &mut data, &mut cd, &q, &v, &tau, &exact).unwrap();
        constraint_dynamics(&talos, &mut data, &mut cd, &q, &v, &tau, &prox).unwrap();
    });
    assert_eq!(n, 0);
    let a = cd.ddq.clone_owned();
    let n = allocations(|| {
        contact_inverse_dynamics(&talos, &mut data, &mut cd, &q, &v, a.as_slice()).unwrap();
        impulse_dynamics(&talos, &mut data, &mut cd, &q, &v, 0.5, &exact).unwrap();
    });
    assert_eq!(n, 0);
    let mut dd = ConstraintDynamicsDerivatives::new(&talos, &cd);
    let mut di = ImpulseDynamicsDerivatives::new(&talos, &cd);
    let n = allocations(|| {
        for s in [&exact, &prox] {
            constraint_dynamics_derivatives(&talos, &mut data, &mut cd, &q, &v, &tau, s, &mut dd)
                .unwrap();
            impulse_dynamics_derivatives(&talos, &mut data, &mut cd, &q, &v, 0.5, s, &mut di)
                .unwrap();
        }
    });
    assert_eq!(n, 0);

    let fourbar = load("constraints/fourbar.urdf", false);
    let tip = |x: f64| Transform::from_translation(Vec3::new(x, 0.0, 0.0));
    let closure = ConstraintModel::point(
        fourbar.joint_id("coupler_joint"),
        tip(0.8),
        fourbar.joint_id("rocker_joint"),
        tip(0.6),
    );
    let opts = ConstraintOptions {
        settings: ProximalSettings::new(1e-12, 1e-6, 100),
        ..ConstraintOptions::default()
    };
    // smooth (rk4 on the constrained dynamics), then the time-stepping scheme (the loop's rows
    // in the contact problem, with the unilateral joint limits)
    for (integrator, limits) in [
        (Integrator::Rk4, JointLimits::Ignored),
        (Integrator::SemiImplicitEuler, JointLimits::Unilateral),
    ] {
        let so = SimulationOptions {
            limits,
            ..SimulationOptions::conservative(1e-3, integrator)
        };
        let none = Controller::none(&fourbar);
        // assembled at crank angle 0.5 rad (fixtures/constraints/fourbar.xml)
        let q0 = [0.5, 0.02116623166979137, 1.1280269456729848];
        let mut sim = Simulator::new(&fourbar, &q0, &[1.0, 0.0, 0.0], so, none)
            .unwrap()
            .with_constraints(std::slice::from_ref(&closure), opts)
            .unwrap();
        sim.run(3, |_| {}).unwrap(); // the contact solver's pool grows on its first steps
        let n = allocations(|| {
            for _ in 0..10 {
                sim.step().unwrap();
            }
        });
        assert_eq!(n, 0, "{integrator}");
    }
}
