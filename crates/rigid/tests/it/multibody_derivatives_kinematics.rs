//! The derivatives of frame placements, twists and accelerations, and the Jacobians of
//! `integrate` and `difference`, against central finite differences on the manifold (h = 1e-6),
//! on every built-in model and random trees with every joint type.
#![allow(non_snake_case)]

use crate::common;
use common::*;
use nalgebra::{DMatrix, DVector};
use rigid::multibody::*;
use rigid::spatial::{so3, Transform, Twist, Vec3};

const H: f64 = 1e-6;
const FD_TOLERANCE: f64 = 1e-6;

/// `‖x - y‖max / max(‖y‖max, 1e-3)`.
fn rel(x: &DMatrix<f64>, y: &DMatrix<f64>) -> f64 {
    (x - y).amax() / y.amax().max(1e-3)
}

/// Central differences of `f` along `x ± h e_k`, where `plus(x, k, h)` perturbs.
fn fd(n: usize, mut perturbed: impl FnMut(usize, f64) -> DVector<f64>) -> DMatrix<f64> {
    let cols: Vec<DVector<f64>> = (0..n)
        .map(|k| (perturbed(k, H) - perturbed(k, -H)) / (2.0 * H))
        .collect();
    DMatrix::from_columns(&cols)
}

fn unit(n: usize, k: usize) -> Vec<f64> {
    let mut e = vec![0.0; n];
    e[k] = 1.0;
    e
}

fn twist_vec(t: &Twist) -> DVector<f64> {
    DVector::from_column_slice(t.to_vector().as_slice())
}

/// The frame's twist `J v` and acceleration `J a + J̇ v` in `rf`.
fn motion(
    model: &Model,
    data: &mut Data,
    x: &(Vec<f64>, Vec<f64>, Vec<f64>),
    target: Target,
    rf: ReferenceFrame,
) -> (DVector<f64>, DVector<f64>) {
    let (q, v, a) = x;
    let dJ = match target {
        Target::Frame(f) => frame_jacobian_time_variation(model, data, q, v, f, rf),
        Target::Joint(j) => joint_jacobian_time_variation(model, data, q, v, j, rf),
    }
    .unwrap()
    .clone();
    let J = &data.frame_jacobian;
    let (v, a) = (DVector::from_column_slice(v), DVector::from_column_slice(a));
    (J * &v, J * &a + dJ * &v)
}

/// The frame's world pose.
fn pose(model: &Model, data: &mut Data, q: &[f64], target: Target) -> Transform {
    forward_kinematics_q(model, data, q).unwrap();
    match target {
        Target::Joint(j) => data.placements[j.0],
        Target::Frame(f) => {
            update_frame_placements(model, data);
            data.frame_placements[f.0]
        }
    }
}

#[derive(Clone, Copy, Debug)]
enum Target {
    Frame(FrameId),
    Joint(JointId),
}

#[test]
fn frame_kinematics_derivatives_equal_finite_differences() {
    let mut rng = Rng::new(30);
    for model in models() {
        let mut data = Data::new(&model);
        let mut fd_data = Data::new(&model);
        let nv = model.nv();
        let mut targets: Vec<Target> = (0..model.frames().len())
            .map(|f| Target::Frame(FrameId(f)))
            .collect();
        targets.push(Target::Joint(JointId(model.njoints() - 1)));
        targets.push(Target::Joint(JointId(model.njoints() / 2)));
        for target in targets {
            let x = state(&model, &mut rng);
            for rf in [
                ReferenceFrame::Body,
                ReferenceFrame::Spatial,
                ReferenceFrame::WorldAligned,
            ] {
                let d = match target {
                    Target::Frame(f) => {
                        frame_kinematics_derivatives(&model, &mut data, &x.0, &x.1, &x.2, f, rf)
                    }
                    Target::Joint(j) => {
                        joint_kinematics_derivatives(&model, &mut data, &x.0, &x.1, &x.2, j, rf)
                    }
                }
                .unwrap();
                let (vq, vv, aq, av, aa) = (
                    d.velocity_dq.clone(),
                    d.velocity_dv.clone(),
                    d.acceleration_dq.clone(),
                    d.acceleration_dv.clone(),
                    d.acceleration_da.clone(),
                );
                let at_q = |k: usize, h: f64, data: &mut Data| {
                    let q = step(&model, &x.0, &unit(nv, k), h);
                    motion(&model, data, &(q, x.1.clone(), x.2.clone()), target, rf)
                };
                let fd_vq = fd(nv, |k, h| at_q(k, h, &mut fd_data).0);
                let fd_aq = fd(nv, |k, h| at_q(k, h, &mut fd_data).1);
                let fd_av = fd(nv, |k, h| {
                    let mut v = x.1.clone();
                    v[k] += h;
                    motion(
                        &model,
                        &mut fd_data,
                        &(x.0.clone(), v, x.2.clone()),
                        target,
                        rf,
                    )
                    .1
                });
                // the placement: T(q ⊕ h e_k) against T(q), as a twist in rf
                let T0 = pose(&model, &mut fd_data, &x.0, target);
                let fd_pose = fd(nv, |k, h| {
                    let T = pose(
                        &model,
                        &mut fd_data,
                        &step(&model, &x.0, &unit(nv, k), h),
                        target,
                    );
                    twist_vec(&match rf {
                        ReferenceFrame::Body => (T0.inverse() * T).log(),
                        ReferenceFrame::Spatial => (T * T0.inverse()).log(),
                        ReferenceFrame::WorldAligned => Twist::new(
                            so3::log(&(T.rotation * T0.rotation.transpose())),
                            T.translation - T0.translation,
                        ),
                    })
                });
                motion(&model, &mut fd_data, &x, target, rf);
                let J = fd_data.frame_jacobian.clone();
                let errors = [
                    ("∂V/∂q", rel(&vq, &fd_vq)),
                    ("∂A/∂q", rel(&aq, &fd_aq)),
                    ("∂A/∂v", rel(&av, &fd_av)),
                    ("placement", rel(&vv, &fd_pose)),
                    ("∂V/∂v = J", rel(&vv, &J)),
                    ("∂A/∂a = J", rel(&aa, &J)),
                ];
                for (what, e) in errors {
                    assert!(
                        e < FD_TOLERANCE,
                        "{} {target:?} {rf:?}: {what} {e:.2e}",
                        model.name()
                    );
                }
            }
        }
    }
}

#[test]
fn a_frame_fixed_in_the_world_has_zero_derivatives() {
    let model = {
        let mut b = ModelBuilder::new("world_frame");
        let j = b
            .add_joint(
                None,
                "j",
                JointType::Revolute { axis: Vec3::z() },
                Transform::identity(),
                inertia(&mut Rng::new(1)),
            )
            .unwrap();
        b.add_frame(None, "fixed", Transform::from_translation(Vec3::x()))
            .unwrap();
        b.add_frame(Some(j), "moving", Transform::from_translation(Vec3::x()))
            .unwrap();
        b.build().unwrap()
    };
    let mut data = Data::new(&model);
    let d = frame_kinematics_derivatives(
        &model,
        &mut data,
        &[0.3],
        &[1.0],
        &[2.0],
        FrameId(0),
        ReferenceFrame::Body,
    )
    .unwrap();
    assert_eq!(
        d.velocity_dq.amax() + d.acceleration_dq.amax() + d.acceleration_dv.amax(),
        0.0
    );
    let d = frame_kinematics_derivatives(
        &model,
        &mut data,
        &[0.3],
        &[1.0],
        &[2.0],
        FrameId(1),
        ReferenceFrame::WorldAligned,
    )
    .unwrap();
    // a point at radius 1 turning at 1 rad/s: ṗ = (-sin q, cos q, 0), ∂ṗ/∂q = (-cos q, -sin q, 0)
    assert!((d.velocity_dq[(3, 0)] + 0.3f64.cos()).abs() < 1e-12);
    assert!((d.velocity_dq[(4, 0)] + 0.3f64.sin()).abs() < 1e-12);
    let e = frame_kinematics_derivatives(
        &model,
        &mut data,
        &[0.3],
        &[1.0],
        &[2.0],
        FrameId(2),
        ReferenceFrame::Body,
    );
    assert!(matches!(
        e,
        Err(MultibodyError::OutOfRange {
            what: "frame",
            index: 2
        })
    ));
}

/// `b ⊖ a` as a vector.
fn diff(model: &Model, a: &[f64], b: &[f64]) -> DVector<f64> {
    let mut out = vec![0.0; model.nv()];
    difference(model, a, b, &mut out).unwrap();
    DVector::from_vec(out)
}

/// `x` agrees with the finite differences `fd` to `FD_TOLERANCE`.
fn close(model: &Model, scale: f64, what: &str, x: &DMatrix<f64>, fd: &DMatrix<f64>) {
    let e = rel(x, fd);
    assert!(
        e < FD_TOLERANCE,
        "{} ×{scale}: {what} {e:.2e}",
        model.name()
    );
}

#[test]
fn integrate_and_difference_jacobians_equal_finite_differences() {
    let mut rng = Rng::new(31);
    for model in models() {
        let nv = model.nv();
        let (mut dq, mut dv) = (DMatrix::zeros(nv, nv), DMatrix::zeros(nv, nv));
        let (mut d0, mut d1) = (DMatrix::zeros(nv, nv), DMatrix::zeros(nv, nv));
        // velocities whose rotation angles fall in the Taylor branch, the closed form, near π
        for scale in [1e-3, 0.2, 1.0, 3.0] {
            let (q, v, _) = state(&model, &mut rng);
            let v: Vec<f64> = v.iter().map(|x| x * scale).collect();
            let dt = 0.7;
            integrate_jacobians(&model, &q, &v, dt, &mut dq, &mut dv).unwrap();
            let q1 = step(&model, &q, &v, dt);
            let fd_dq = fd(nv, |k, h| {
                diff(
                    &model,
                    &q1,
                    &step(&model, &step(&model, &q, &unit(nv, k), h), &v, dt),
                )
            });
            let fd_dv = fd(nv, |k, h| {
                let mut w = v.clone();
                w[k] += h;
                diff(&model, &q1, &step(&model, &q, &w, dt))
            });
            close(&model, scale, "∂/∂q", &dq, &fd_dq);
            close(&model, scale, "∂/∂v", &dv, &fd_dv);

            let (q0, _, _) = state(&model, &mut rng);
            let q1 = step(&model, &q0, &v, 1.0);
            difference_jacobians(&model, &q0, &q1, &mut d0, &mut d1).unwrap();
            let fd_d0 = fd(nv, |k, h| {
                diff(&model, &step(&model, &q0, &unit(nv, k), h), &q1)
            });
            let fd_d1 = fd(nv, |k, h| {
                diff(&model, &q0, &step(&model, &q1, &unit(nv, k), h))
            });
            close(&model, scale, "∂/∂q0", &d0, &fd_d0);
            close(&model, scale, "∂/∂q1", &d1, &fd_d1);
            // (q0 ⊕ v) ⊖ q0 = v (while no rotation exceeds π, where log wraps): by the chain rule
            // ∂/∂q1 of the difference inverts ∂/∂v of integrate
            if (diff(&model, &q0, &q1) - DVector::from_column_slice(&v)).amax() < 1e-9 {
                integrate_jacobians(&model, &q0, &v, 1.0, &mut dq, &mut dv).unwrap();
                let eye = DMatrix::<f64>::identity(nv, nv);
                assert!(
                    rel(&(&d1 * &dv), &eye) < 1e-12,
                    "{} ×{scale}: chain rule",
                    model.name()
                );
            }
        }
    }
}

#[test]
fn configuration_jacobians_reject_wrong_sizes() {
    let model = random_tree(2, 4, false);
    let nv = model.nv();
    let (q, v, _) = state(&model, &mut Rng::new(3));
    let (mut a, mut b) = (DMatrix::zeros(nv, nv), DMatrix::zeros(nv, nv - 1));
    let e = integrate_jacobians(&model, &q, &v, 1.0, &mut a, &mut b).unwrap_err();
    assert!(e.to_string().contains("d_dv"), "{e}");
    let e = integrate_jacobians(&model, &q, &v, f64::NAN, &mut a.clone(), &mut a).unwrap_err();
    assert!(e.to_string().contains("dt"), "{e}");
    let e = difference_jacobians(&model, &q, &q[1..], &mut a.clone(), &mut a).unwrap_err();
    assert!(e.to_string().contains('q'), "{e}");
}
