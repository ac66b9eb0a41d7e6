//! After `Data::new`, forward kinematics, Jacobians, RNEA (and gravity, nle, external wrenches),
//! CRBA, `M⁻¹`, ABA, Cholesky forward dynamics, the Coriolis matrix, the energies and the analytical
//! derivatives (RNEA, ABA, gravity, frame kinematics, `integrate`/`difference` Jacobians) allocate
//! nothing, and so does a step of the simulator (every integrator, control law, an external wrench)
//! and the joint-torque regressor of identification (`Regressor::compute` and its stacked form):
//! a counting global allocator proves it.

use crate::allocations_in as allocations;
use crate::common;
use rigid::multibody::*;
use rigid::simulation;
use rigid::spatial::Wrench;

#[test]
fn algorithms_allocate_nothing_after_data_new() {
    // the counter sees allocations
    assert!(allocations(|| drop(std::hint::black_box(vec![1.0f64; 10]))) > 0);
    // the counter is per thread: the other tests of this binary run on other threads
    let mut models = vec![common::random_tree(7, 12, true)];
    models.push(puma560(Puma560Options { armature: true }));
    for model in &models {
        let mut rng = Rng::new(3);
        let (q, v, a) = common::state(model, &mut rng);
        let fext = vec![Wrench::zero(); model.njoints()];
        let mut data = Data::new(model);
        let (mut j0, mut j1) = (data.minv.clone(), data.minv.clone());
        let n = allocations(|| {
            forward_kinematics_q(model, &mut data, &q).unwrap();
            forward_kinematics(model, &mut data, &q, &v, &a).unwrap();
            update_frame_placements(model, &mut data);
            compute_joint_jacobians(model, &mut data, &q).unwrap();
            compute_joint_jacobians_time_variation(model, &mut data, &q, &v).unwrap();
            joint_jacobian(
                model,
                &mut data,
                &q,
                JointId(model.njoints() - 1),
                ReferenceFrame::Body,
            )
            .unwrap();
            joint_jacobian_time_variation(
                model,
                &mut data,
                &q,
                &v,
                JointId(0),
                ReferenceFrame::WorldAligned,
            )
            .unwrap();
            if !model.frames().is_empty() {
                frame_jacobian(model, &mut data, &q, FrameId(0), ReferenceFrame::Spatial).unwrap();
            }
            rnea(model, &mut data, &q, &v, &a).unwrap();
            rnea_with_external(model, &mut data, &q, &v, &a, &fext).unwrap();
            gravity_torques(model, &mut data, &q).unwrap();
            nonlinear_effects(model, &mut data, &q, &v).unwrap();
            crba(model, &mut data, &q).unwrap();
            compute_minverse(model, &mut data, &q).unwrap();
            aba(model, &mut data, &q, &v, &a).unwrap();
            forward_dynamics_cholesky(model, &mut data, &q, &v, &a).unwrap();
            coriolis_matrix(model, &mut data, &q, &v).unwrap();
            kinetic_energy(model, &mut data, &q, &v).unwrap();
            potential_energy(model, &mut data, &q).unwrap();
            center_of_mass(model, &mut data, &q).unwrap();
            // analytical derivatives (their buffers are in `data.derivatives`)
            rnea_derivatives(model, &mut data, &q, &v, &a).unwrap();
            rnea_derivatives_with_external(model, &mut data, &q, &v, &a, &fext).unwrap();
            gravity_derivatives(model, &mut data, &q).unwrap();
            aba_derivatives(model, &mut data, &q, &v, &a).unwrap();
            aba_derivatives_with_external(model, &mut data, &q, &v, &a, &fext).unwrap();
            let last = JointId(model.njoints() - 1);
            joint_kinematics_derivatives(model, &mut data, &q, &v, &a, last, ReferenceFrame::Body)
                .unwrap();
            if !model.frames().is_empty() {
                let (f, rf) = (FrameId(0), ReferenceFrame::WorldAligned);
                frame_kinematics_derivatives(model, &mut data, &q, &v, &a, f, rf).unwrap();
            }
            integrate_jacobians(model, &q, &v, 0.1, &mut j0, &mut j1).unwrap();
            difference_jacobians(model, &q, &q, &mut j0, &mut j1).unwrap();
        });
        assert_eq!(n, 0, "{}: {n} allocations", model.name());
        // the joint-torque regressor, one sample and three stacked
        let mut reg = rigid::identification::Regressor::new(model);
        let (q3, v3, a3) = (q.repeat(3), v.repeat(3), a.repeat(3));
        let mut w = nalgebra::DMatrix::zeros(3 * model.nv(), 10 * model.njoints());
        let n = allocations(|| {
            reg.compute(model, &q, &v, &a).unwrap();
            reg.stack(model, &q3, &v3, &a3, &mut w).unwrap();
        });
        assert_eq!(n, 0, "{}: regressor: {n} allocations", model.name());
        // a simulation step, with every integrator, control law and an external wrench
        let target = q.clone();
        let q1 = random_configuration(model, &mut rng);
        let trajectory =
            simulation::JointTrajectory::new(model, &q, &q1, 1.0, simulation::TimeScaling::Quintic)
                .unwrap();
        let laws = [
            simulation::ControlLaw::GravityCompensation,
            simulation::ControlLaw::pd(model, &target, 10.0, 1.0).unwrap(),
            simulation::ControlLaw::ComputedTorque {
                trajectory,
                kp: 100.0,
                kd: 20.0,
            },
        ];
        for (integrator, law) in [
            simulation::Integrator::SemiImplicitEuler,
            simulation::Integrator::Rk4,
            simulation::Integrator::Variational,
        ]
        .into_iter()
        .zip(laws)
        {
            let opts = simulation::SimulationOptions {
                integrator,
                ..Default::default()
            };
            let ctrl = simulation::Controller::new(model, law).unwrap();
            let small: Vec<f64> = v.iter().map(|x| 0.1 * x).collect();
            let mut sim = simulation::Simulator::new(model, &q, &small, opts, ctrl).unwrap();
            sim.set_external_wrench(
                JointId(0),
                Wrench::from_slice(&[0.1, 0.0, 0.2, 1.0, 0.0, 0.0]),
            )
            .unwrap();
            sim.step().unwrap(); // warm-up
            let n = allocations(|| {
                for _ in 0..3 {
                    sim.step().unwrap();
                }
                sim.torques().unwrap();
                sim.energy().unwrap();
                sim.momentum().unwrap();
            });
            assert_eq!(n, 0, "{}: {integrator}: {n} allocations", model.name());
        }
    }
}
