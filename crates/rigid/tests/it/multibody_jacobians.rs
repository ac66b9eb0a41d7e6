//! Jacobians against finite differences of forward kinematics (perturbing `q` by `integrate`),
//! their time derivatives against finite differences of the Jacobians, and the external-wrench
//! RNEA against `τ - Σ J_iᵀ F_i`.
#![allow(non_snake_case)]

use crate::common;
use common::*;
use nalgebra::{DMatrix, DVector};
use rigid::multibody::*;
use rigid::spatial::{Transform, Twist, Vec3, Wrench};

/// The world pose of joint `i` (`frame: None`) or of a named frame.
fn pose(model: &Model, data: &mut Data, q: &[f64], target: Target) -> Transform {
    forward_kinematics_q(model, data, q).unwrap();
    update_frame_placements(model, data);
    match target {
        Target::Joint(i) => data.placements[i],
        Target::Frame(f) => data.frame_placements[f],
    }
}

#[derive(Clone, Copy, Debug)]
enum Target {
    Joint(usize),
    Frame(usize),
}

fn jac(model: &Model, data: &mut Data, q: &[f64], t: Target, rf: ReferenceFrame) -> DMatrix<f64> {
    match t {
        Target::Joint(i) => joint_jacobian(model, data, q, JointId(i), rf)
            .unwrap()
            .clone(),
        Target::Frame(f) => frame_jacobian(model, data, q, FrameId(f), rf)
            .unwrap()
            .clone(),
    }
}

fn targets(model: &Model) -> Vec<Target> {
    let mut t: Vec<Target> = (0..model.njoints()).map(Target::Joint).collect();
    t.extend((0..model.frames().len()).map(Target::Frame));
    t
}

#[test]
fn jacobians_equal_finite_differences_of_forward_kinematics() {
    let mut rng = Rng::new(20);
    let eps = 1e-6;
    for model in models() {
        let mut data = Data::new(&model);
        for _ in 0..3 {
            let (q, v, _) = state(&model, &mut rng);
            let vv = DVector::from_column_slice(&v);
            let (qp, qm) = (step(&model, &q, &v, eps), step(&model, &q, &v, -eps));
            for t in targets(&model) {
                let T0 = pose(&model, &mut data, &q, t);
                let Tp = pose(&model, &mut data, &qp, t);
                let Tm = pose(&model, &mut data, &qm, t);
                // body twist: log(T⁻¹ T(±ε)) / ε
                let Vb = ((T0.inverse() * Tp).log() - (T0.inverse() * Tm).log()) * (0.5 / eps);
                // spatial twist: log(T(±ε) T⁻¹) / ε
                let Vs = ((Tp * T0.inverse()).log() - (Tm * T0.inverse()).log()) * (0.5 / eps);
                let pdot = (Tp.translation - Tm.translation) / (2.0 * eps);
                let expect = [
                    (ReferenceFrame::Body, Vb),
                    (ReferenceFrame::Spatial, Vs),
                    (ReferenceFrame::WorldAligned, Twist::new(Vs.w, pdot)),
                ];
                for (rf, V) in expect {
                    let J = jac(&model, &mut data, &q, t, rf);
                    let Jv = &J * &vv;
                    let err = (Jv - V.to_vector()).amax() / V.norm().max(1.0);
                    assert!(err < 1e-6, "{} {t:?} {rf:?}: {err}", model.name());
                }
            }
        }
    }
}

#[test]
fn jacobian_time_derivatives_equal_finite_differences_along_v() {
    let mut rng = Rng::new(21);
    let eps = 1e-6;
    for model in models() {
        let mut data = Data::new(&model);
        for _ in 0..3 {
            let (q, v, _) = state(&model, &mut rng);
            let (qp, qm) = (step(&model, &q, &v, eps), step(&model, &q, &v, -eps));
            for t in targets(&model) {
                for rf in [
                    ReferenceFrame::Body,
                    ReferenceFrame::Spatial,
                    ReferenceFrame::WorldAligned,
                ] {
                    let dJ = match t {
                        Target::Joint(i) => {
                            joint_jacobian_time_variation(&model, &mut data, &q, &v, JointId(i), rf)
                        }
                        Target::Frame(f) => {
                            frame_jacobian_time_variation(&model, &mut data, &q, &v, FrameId(f), rf)
                        }
                    }
                    .unwrap()
                    .clone();
                    let J = data.frame_jacobian.clone();
                    assert!(rel_err_m(&J, &jac(&model, &mut data, &q, t, rf)) < 1e-14);
                    let fd = (jac(&model, &mut data, &qp, t, rf)
                        - jac(&model, &mut data, &qm, t, rf))
                        / (2.0 * eps);
                    let err = rel_err_m(&dJ, &fd);
                    assert!(err < 1e-6, "{} {t:?} {rf:?}: {err}", model.name());
                }
            }
        }
    }
}

#[test]
fn frame_acceleration_is_j_a_plus_jdot_v() {
    // body-frame classical check: A_i (from forward kinematics) = J_b a + J̇_b v for joint frames
    let mut rng = Rng::new(22);
    for model in models() {
        let mut data = Data::new(&model);
        let (q, v, a) = state(&model, &mut rng);
        for i in 0..model.njoints() {
            let dJ = joint_jacobian_time_variation(
                &model,
                &mut data,
                &q,
                &v,
                JointId(i),
                ReferenceFrame::Body,
            )
            .unwrap()
            .clone();
            let J = data.frame_jacobian.clone();
            let A = J * DVector::from_column_slice(&a) + dJ * DVector::from_column_slice(&v);
            forward_kinematics(&model, &mut data, &q, &v, &a).unwrap();
            let err = (A - data.accelerations[i].to_vector()).amax();
            assert!(
                err < 1e-9 * A_scale(&data),
                "{} joint {i}: {err}",
                model.name()
            );
        }
    }
}

fn A_scale(data: &Data) -> f64 {
    data.accelerations
        .iter()
        .map(|a| a.norm())
        .fold(1.0, f64::max)
}

#[test]
fn rnea_with_external_wrenches_subtracts_body_jacobian_transpose_times_wrench() {
    let mut rng = Rng::new(23);
    for model in models() {
        let mut data = Data::new(&model);
        let (q, v, a) = state(&model, &mut rng);
        let fext: Vec<Wrench> = (0..model.njoints())
            .map(|_| {
                Wrench::new(
                    Vec3::new(rng.normal(), rng.normal(), rng.normal()),
                    Vec3::new(rng.normal(), rng.normal(), rng.normal()),
                )
            })
            .collect();
        let tau0 = rnea(&model, &mut data, &q, &v, &a).unwrap().clone();
        let tau = rnea_with_external(&model, &mut data, &q, &v, &a, &fext)
            .unwrap()
            .clone();
        let mut expect = tau0;
        for (i, f) in fext.iter().enumerate() {
            let J =
                joint_jacobian(&model, &mut data, &q, JointId(i), ReferenceFrame::Body).unwrap();
            expect -= J.transpose() * f.to_vector();
        }
        assert!(rel_err_v(&tau, &expect) < 1e-10, "{}", model.name());
        // and ABA with the same wrenches inverts it
        let ddq = aba_with_external(&model, &mut data, &q, &v, tau.as_slice(), &fext).unwrap();
        let a = DVector::from_column_slice(&a);
        assert!(
            rel_err_v(ddq, &a) < 1e-8,
            "{}: {}",
            model.name(),
            rel_err_v(ddq, &a)
        );
    }
}

#[test]
fn free_flyer_velocity_is_the_body_twist_and_spherical_velocity_the_body_angular_velocity() {
    let mut b = ModelBuilder::new("ff");
    let g = common::inertia(&mut Rng::new(1));
    let root = b
        .add_joint(None, "base", JointType::FreeFlyer, Transform::identity(), g)
        .unwrap();
    b.add_joint(
        Some(root),
        "ball",
        JointType::Spherical,
        common::transform(&mut Rng::new(2)),
        g,
    )
    .unwrap();
    let model = b.build().unwrap();
    let mut data = Data::new(&model);
    let mut rng = Rng::new(3);
    let (q, v, _) = state(&model, &mut rng);
    // body Jacobian of the base = [1₆ | 0]; of the ball, its last three columns = [1₃; 0]
    let J0 = joint_jacobian(&model, &mut data, &q, JointId(0), ReferenceFrame::Body)
        .unwrap()
        .clone();
    assert!((J0.columns(0, 6) - DMatrix::<f64>::identity(6, 6)).amax() < 1e-14);
    let J1 = joint_jacobian(&model, &mut data, &q, JointId(1), ReferenceFrame::Body)
        .unwrap()
        .clone();
    let mut e = DMatrix::<f64>::zeros(6, 3);
    e.view_mut((0, 0), (3, 3)).fill_with_identity();
    assert!((J1.columns(6, 3) - e).amax() < 1e-14);
    // and the base twist from forward kinematics is v[0..6]
    forward_kinematics_qv(&model, &mut data, &q, &v).unwrap();
    let vb = data.velocities[0].to_vector();
    for k in 0..6 {
        assert!((vb[k] - v[k]).abs() < 1e-14);
    }
}

#[test]
fn joint_transform_fast_path_for_coordinate_axes_equals_rodrigues() {
    let mut rng = Rng::new(30);
    let placement = common::transform(&mut rng);
    for k in 0..3 {
        for sign in [1.0, -1.0] {
            let axis = Vec3::ith(k, sign);
            let q = [rng.uniform(-3.0, 3.0)];
            let fast = JointType::Revolute { axis }.placed_transform(&placement, &q);
            // the same axis, perturbed off the coordinate axis by nothing but its representation
            let r = rigid::spatial::so3::exp(&(axis * q[0]));
            let slow = placement * Transform::from_rotation(r);
            assert!((fast.inverse() * slow).is_identity(1e-14), "axis {axis:?}");
        }
    }
}

/// The frames by name, Pinocchio's and rigid's in any case, as the CLI, the constraint files
/// and Python read them; a constraint refuses the world's frame; the layouts by name.
#[test]
fn reference_frames_and_layouts_are_read_by_name() {
    use rigid::interop::Layout;
    use rigid::multibody::constraints::ConstraintModel;
    for frame in [
        ReferenceFrame::Body,
        ReferenceFrame::Spatial,
        ReferenceFrame::WorldAligned,
    ] {
        assert_eq!(frame.pinocchio_name().parse::<ReferenceFrame>(), Ok(frame));
        let lower = frame.pinocchio_name().to_ascii_lowercase();
        assert_eq!(lower.parse::<ReferenceFrame>(), Ok(frame));
    }
    assert_eq!("body".parse(), Ok(ReferenceFrame::Body));
    assert_eq!("Spatial".parse(), Ok(ReferenceFrame::Spatial));
    assert_eq!("world_aligned".parse(), Ok(ReferenceFrame::WorldAligned));
    let e = "mars".parse::<ReferenceFrame>().unwrap_err();
    assert!(
        e.contains("\"local\"") && e.ends_with("got \"mars\""),
        "{e}"
    );
    assert_eq!(
        ConstraintModel::reference_named("LOCAL_WORLD_ALIGNED"),
        Ok(ReferenceFrame::WorldAligned)
    );
    assert_eq!(
        ConstraintModel::reference_named("world").unwrap_err(),
        "\"reference_frame\" is \"world\" (expected \"local\" or \"local_world_aligned\")"
    );
    for layout in Layout::ALL {
        assert_eq!(layout.name().parse(), Ok(layout));
        assert_eq!(layout.to_string(), layout.name());
    }
    assert_eq!(
        "Pinocchio".parse::<Layout>().unwrap_err(),
        "layout must be \"rigid\", \"pinocchio\" or \"mujoco\", got \"Pinocchio\""
    );
}
