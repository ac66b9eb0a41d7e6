//! The helical and universal joints equal Pinocchio's `JointModelHelicalUnaligned` and
//! `JointModelUniversal` to 1e-12: RNEA, CRBA, ABA, the spatial Jacobian of every joint, a body
//! Jacobian, `integrate` and `difference`, on two trees built by the API (fixed base, and under a
//! free-flyer), read from `fixtures/joints_pinocchio.json` (generator beside it). Also: the
//! fast algorithms equal the reference ones on random trees that include both joints, and the
//! algorithms that assume a constant motion subspace refuse a universal joint by name.

#![allow(non_snake_case)]

use crate::common;

use common::{every_joint_tree, inertia, rel_err_m, rel_err_v, transform, unit};
use nalgebra::{DMatrix, DVector};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::multibody::*;
use rigid::spatial::{Mat3, Transform, Vec3};
use serde_json::Value;

fn vec_of(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn mat_of(v: &Value) -> DMatrix<f64> {
    let rows: Vec<Vec<f64>> = v.as_array().unwrap().iter().map(vec_of).collect();
    DMatrix::from_fn(rows.len(), rows[0].len(), |r, c| rows[r][c])
}

fn mat3(v: &Value) -> Mat3 {
    let m = mat_of(v);
    Mat3::from_fn(|r, c| m[(r, c)])
}

fn build(fx: &Value) -> Model {
    let mut b = ModelBuilder::new("pinocchio_joints");
    b.set_gravity(Vec3::from_column_slice(&vec_of(&fx["gravity"])));
    for j in fx["joints"].as_array().unwrap() {
        let axis = Vec3::from_column_slice(&vec_of(&j["axis"]));
        let kind = match j["type"].as_str().unwrap() {
            "free_flyer" => JointType::FreeFlyer,
            "helical" => JointType::Helical {
                axis,
                pitch: j["pitch"].as_f64().unwrap(),
            },
            "universal" => JointType::Universal {
                axis1: axis,
                axis2: Vec3::from_column_slice(&vec_of(&j["axis2"])),
            },
            "revolute" => JointType::Revolute { axis },
            "spherical" => JointType::Spherical,
            t => panic!("unknown joint type {t}"),
        };
        let parent = j["parent"].as_i64().unwrap();
        let parent = (parent >= 0).then_some(JointId(parent as usize));
        let placement = Transform::new(
            mat3(&j["rotation"]),
            Vec3::from_column_slice(&vec_of(&j["translation"])),
        );
        let G = SpatialInertia::from_com(
            j["mass"].as_f64().unwrap(),
            Vec3::from_column_slice(&vec_of(&j["com"])),
            RotationalInertia::from_matrix_unchecked(&mat3(&j["inertia_com"])),
        );
        b.add_joint(parent, j["name"].as_str().unwrap(), kind, placement, G)
            .unwrap();
    }
    let mut m = b.build().unwrap();
    m.set_armature(&vec_of(&fx["armature"])).unwrap();
    m
}

/// `|a - b|∞ / max(1, |b|∞)` with each quaternion compared up to its sign (both are the same
/// rotation; rigid returns `w ≥ 0`, Pinocchio keeps the hemisphere).
fn config_err(model: &Model, a: &[f64], b: &[f64]) -> f64 {
    let mut e = 0.0f64;
    let mut done = vec![false; a.len()];
    for j in model.joints() {
        if let Some(o) = j.kind.quaternion_offset() {
            let k = j.idx_q + o;
            let plus = (0..4)
                .map(|t| (a[k + t] - b[k + t]).abs())
                .fold(0.0, f64::max);
            let minus = (0..4)
                .map(|t| (a[k + t] + b[k + t]).abs())
                .fold(0.0, f64::max);
            e = e.max(plus.min(minus));
            done[k..k + 4].fill(true);
        }
    }
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        if !done[i] {
            e = e.max((x - y).abs() / y.abs().max(1.0));
        }
    }
    e
}

#[test]
fn helical_and_universal_joints_equal_pinocchio_to_1e12() {
    let fx: Value =
        serde_json::from_str(include_str!("../fixtures/joints_pinocchio.json")).unwrap();
    for tree in ["fixed", "floating"] {
        let fx = &fx[tree];
        let model = build(fx);
        let mut d = Data::new(&model);
        let last = JointId(model.njoints() - 1);
        let tol = 1e-12;
        for c in fx["cases"].as_array().unwrap() {
            let (q, v, a, tau) = (
                vec_of(&c["q"]),
                vec_of(&c["v"]),
                vec_of(&c["a"]),
                vec_of(&c["tau"]),
            );
            let dv = |k: &str| DVector::from_vec(vec_of(&c[k]));
            let e = rel_err_v(rnea(&model, &mut d, &q, &v, &a).unwrap(), &dv("rnea"));
            assert!(e < tol, "{tree}: rnea {e:e}");
            let e = rel_err_m(
                crba(&model, &mut d, &q).unwrap(),
                &mat_of(&c["mass_matrix"]),
            );
            assert!(e < tol, "{tree}: crba {e:e}");
            let e = rel_err_v(aba(&model, &mut d, &q, &v, &tau).unwrap(), &dv("aba"));
            assert!(e < tol, "{tree}: aba {e:e}");
            let J = compute_joint_jacobians(&model, &mut d, &q).unwrap();
            let e = rel_err_m(J, &mat_of(&c["jacobian_world"]));
            assert!(e < tol, "{tree}: spatial Jacobian {e:e}");
            let J = joint_jacobian(&model, &mut d, &q, last, ReferenceFrame::Body).unwrap();
            let e = rel_err_m(J, &mat_of(&c["jacobian_last_body"]));
            assert!(e < tol, "{tree}: body Jacobian {e:e}");
            let mut qn = vec![0.0; model.nq()];
            integrate(&model, &q, &v, 1.0, &mut qn).unwrap();
            let e = config_err(&model, &qn, &vec_of(&c["integrate"]));
            assert!(e < tol, "{tree}: integrate {e:e}");
            let mut dq = vec![0.0; model.nv()];
            difference(&model, &q, &vec_of(&c["q1"]), &mut dq).unwrap();
            let e = rel_err_v(&DVector::from_vec(dq), &dv("difference"));
            assert!(e < tol, "{tree}: difference {e:e}");
        }
    }
}

#[test]
fn fast_algorithms_equal_the_reference_on_trees_with_every_joint_type() {
    for seed in 0..6 {
        let model = every_joint_tree(seed, 14);
        let mut rng = Rng::new(seed + 40);
        let mut d = Data::new(&model);
        for _ in 0..5 {
            let (q, v, a) = common::state(&model, &mut rng);
            let tau = reference::rnea(&model, &q, &v, &a).unwrap();
            let e = rel_err_v(rnea(&model, &mut d, &q, &v, &a).unwrap(), &tau);
            assert!(e < 1e-12, "{}: rnea {e:e}", model.name());
            let M = reference::crba(&model, &q).unwrap();
            let e = rel_err_m(crba(&model, &mut d, &q).unwrap(), &M);
            assert!(e < 1e-12, "{}: crba {e:e}", model.name());
            let ddq = reference::aba(&model, &q, &v, tau.as_slice()).unwrap();
            let e = rel_err_v(aba(&model, &mut d, &q, &v, tau.as_slice()).unwrap(), &ddq);
            assert!(e < 1e-12, "{}: aba {e:e}", model.name());
            // and both invert each other: M q̈ + nle = τ
            let e = rel_err_v(&ddq, &DVector::from_vec(a.clone()));
            assert!(e < 1e-9, "{}: aba(rnea(a)) = a {e:e}", model.name());
            let Minv = compute_minverse(&model, &mut d, &q).unwrap().clone();
            let e = rel_err_m(&(Minv * &M), &DMatrix::identity(model.nv(), model.nv()));
            assert!(e < 1e-9, "{}: M⁻¹ M = 1 {e:e}", model.name());
        }
    }
}

#[test]
fn a_universal_joint_is_two_revolute_joints_with_a_massless_link_between() {
    // the closed form of the joint: X_J = exp([a₁] q₁) exp([a₂] q₂) is a revolute about a₁
    // followed by a revolute about a₂ with nothing between them
    let mut rng = Rng::new(3);
    let (a1, a2) = (unit(&mut rng), unit(&mut rng));
    let (xt, g) = (transform(&mut rng), inertia(&mut rng));
    let mut b = ModelBuilder::new("universal");
    b.add_joint(
        None,
        "u",
        JointType::Universal {
            axis1: a1,
            axis2: a2,
        },
        xt,
        g,
    )
    .unwrap();
    let universal = b.build().unwrap();
    let mut b = ModelBuilder::new("two_revolute");
    let r1 = b
        .add_joint(
            None,
            "r1",
            JointType::Revolute { axis: a1 },
            xt,
            SpatialInertia::zero(),
        )
        .unwrap();
    b.add_joint(
        Some(r1),
        "r2",
        JointType::Revolute { axis: a2 },
        Transform::identity(),
        g,
    )
    .unwrap();
    let chain = b.build().unwrap();
    let (mut du, mut dc) = (Data::new(&universal), Data::new(&chain));
    for _ in 0..10 {
        let q: Vec<f64> = (0..2).map(|_| rng.uniform(-3.0, 3.0)).collect();
        let v: Vec<f64> = (0..2).map(|_| rng.uniform(-2.0, 2.0)).collect();
        let a: Vec<f64> = (0..2).map(|_| rng.uniform(-2.0, 2.0)).collect();
        let e = rel_err_v(
            rnea(&universal, &mut du, &q, &v, &a).unwrap(),
            rnea(&chain, &mut dc, &q, &v, &a).unwrap(),
        );
        assert!(e < 1e-12, "rnea {e:e}");
        let e = rel_err_m(
            crba(&universal, &mut du, &q).unwrap(),
            crba(&chain, &mut dc, &q).unwrap(),
        );
        assert!(e < 1e-12, "crba {e:e}");
        forward_kinematics(&universal, &mut du, &q, &v, &a).unwrap();
        forward_kinematics(&chain, &mut dc, &q, &v, &a).unwrap();
        let (Au, Ac) = (
            du.accelerations[0].to_vector(),
            dc.accelerations[1].to_vector(),
        );
        assert!((Au - Ac).amax() < 1e-12, "accelerations (c_J)");
    }
}

#[test]
fn a_helical_joint_with_zero_pitch_is_a_revolute_joint() {
    let mut rng = Rng::new(5);
    let axis = unit(&mut rng);
    let (xt, g) = (transform(&mut rng), inertia(&mut rng));
    let one = |kind| {
        let mut b = ModelBuilder::new("one");
        b.add_joint(None, "j", kind, xt, g).unwrap();
        b.build().unwrap()
    };
    let (h, r) = (
        one(JointType::Helical { axis, pitch: 0.0 }),
        one(JointType::Revolute { axis }),
    );
    let (mut dh, mut dr) = (Data::new(&h), Data::new(&r));
    let (q, v, a) = ([0.7], [1.3], [-0.4]);
    let th = rnea(&h, &mut dh, &q, &v, &a).unwrap()[0];
    assert!((th - rnea(&r, &mut dr, &q, &v, &a).unwrap()[0]).abs() < 1e-14);
    // and with a pitch, the displacement along the axis is pitch q
    let h = one(JointType::Helical { axis, pitch: 0.25 });
    let mut d = Data::new(&h);
    forward_kinematics_q(&h, &mut d, &[2.0]).unwrap();
    let p = xt.inverse() * d.placements[0];
    assert!((p.translation - axis * 0.5).amax() < 1e-15);
}

#[test]
fn derivatives_and_the_coriolis_matrix_refuse_a_universal_joint_by_name() {
    let model = every_joint_tree(1, 3);
    let mut d = Data::new(&model);
    let q = neutral(&model);
    let v = vec![0.1; model.nv()];
    let e = rnea_derivatives(&model, &mut d, &q, &v, &v).unwrap_err();
    assert!(matches!(e, MultibodyError::Unsupported { .. }), "{e}");
    assert!(e.to_string().contains("'j1' (universal)"), "{e}");
    assert!(coriolis_matrix(&model, &mut d, &q, &v).is_err());
    assert!(aba_derivatives(&model, &mut d, &q, &v, &v).is_err());
    // parallel axes are not a universal joint
    let mut b = ModelBuilder::new("bad");
    let e = b
        .add_joint(
            None,
            "u",
            JointType::Universal {
                axis1: Vec3::x(),
                axis2: -Vec3::x(),
            },
            Transform::identity(),
            SpatialInertia::zero(),
        )
        .unwrap_err();
    assert!(e.to_string().contains("parallel"), "{e}");
}

/// The simulator steps a tree with universal and helical joints (RK4 keeps its energy when
/// nothing but gravity acts), and the variational integrator, whose configuration gradient of
/// the kinetic energy assumes constant motion subspaces, refuses it by name.
#[test]
fn the_simulator_takes_every_joint_type_and_the_variational_integrator_says_what_it_cannot() {
    use rigid::simulation::{Controller, Integrator, SimulationOptions, Simulator};
    let model = every_joint_tree(2, 8);
    let mut rng = Rng::new(4);
    let q0 = random_configuration(&model, &mut rng);
    let v0: Vec<f64> = (0..model.nv()).map(|_| rng.uniform(-0.5, 0.5)).collect();
    let options = |integrator| SimulationOptions {
        integrator,
        dt: 1e-3,
        ..SimulationOptions::default()
    };
    let variational = Simulator::new(
        &model,
        &q0,
        &v0,
        options(Integrator::Variational),
        Controller::none(&model),
    );
    let Err(e) = variational else {
        panic!("the variational integrator took a universal joint");
    };
    assert!(e.to_string().contains("universal"), "{e}");
    let mut sim = Simulator::new(
        &model,
        &q0,
        &v0,
        options(Integrator::Rk4),
        Controller::none(&model),
    )
    .unwrap();
    let mut d = Data::new(&model);
    let energy = |d: &mut Data, q: &[f64], v: &[f64]| {
        kinetic_energy(&model, d, q, v).unwrap() + potential_energy(&model, d, q).unwrap()
    };
    let e0 = energy(&mut d, &q0, &v0);
    for _ in 0..500 {
        sim.step().unwrap();
    }
    let e1 = energy(&mut d, sim.q(), sim.v());
    assert!(
        (e1 - e0).abs() < 1e-6 * e0.abs().max(1.0),
        "energy {e0} → {e1}"
    );
}
