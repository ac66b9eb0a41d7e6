//! A random tree (free-flyer root, revolute / prismatic with random axes, continuous, spherical,
//! planar joints, armature) against Pinocchio: fixture `fixtures/tree_pinocchio.json` generated
//! by `fixtures/gen_tree_pinocchio.py` (PyPI `pin`), converted to rigid's conventions there
//! (`M` and `M⁻¹` symmetrised from Pinocchio's upper triangles).
#![allow(non_snake_case)]

use nalgebra::DVector;
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::multibody::*;
use rigid::spatial::{Mat3, Transform, Vec3};
use serde_json::Value;

use crate::common;
use common::json::{mat_of, vec_of};

fn mat3(v: &Value) -> Mat3 {
    let m = mat_of(v);
    Mat3::from_fn(|i, j| m[(i, j)])
}

fn build(fx: &Value) -> Model {
    let mut b = ModelBuilder::new("pinocchio_tree");
    b.set_gravity(Vec3::from_column_slice(&vec_of(&fx["gravity"])));
    for j in fx["joints"].as_array().unwrap() {
        let axis = Vec3::from_column_slice(&vec_of(&j["axis"]));
        let kind = match j["type"].as_str().unwrap() {
            "free_flyer" => JointType::FreeFlyer,
            "revolute" | "continuous" => JointType::Revolute { axis },
            "prismatic" => JointType::Prismatic { axis },
            "spherical" => JointType::Spherical,
            "planar" => JointType::Planar,
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
        let id = b
            .add_joint(parent, j["name"].as_str().unwrap(), kind, placement, G)
            .unwrap();
        if j["type"] == "continuous" {
            b.set_continuous(id).unwrap();
        }
    }
    let mut m = b.build().unwrap();
    m.set_armature(&vec_of(&fx["armature"])).unwrap();
    m
}

fn rel(x: &DVector<f64>, y: &[f64]) -> f64 {
    let y = DVector::from_column_slice(y);
    (x - &y).amax() / y.amax().max(1.0)
}

#[test]
fn random_tree_agrees_with_pinocchio_to_1e9() {
    let fx: Value = serde_json::from_str(include_str!("../fixtures/tree_pinocchio.json")).unwrap();
    let model = build(&fx);
    let mut d = Data::new(&model);
    let mut worst_minv = 0.0f64;
    for c in fx["cases"].as_array().unwrap() {
        let (q, v, a, tau) = (
            vec_of(&c["q"]),
            vec_of(&c["v"]),
            vec_of(&c["a"]),
            vec_of(&c["tau"]),
        );
        let tol = 1e-9;
        let r = rnea(&model, &mut d, &q, &v, &a).unwrap().clone();
        assert!(
            rel(&r, &vec_of(&c["rnea"])) < tol,
            "rnea {}",
            rel(&r, &vec_of(&c["rnea"]))
        );
        let M = crba(&model, &mut d, &q).unwrap().clone();
        let Mp = mat_of(&c["mass_matrix"]);
        assert!(
            (&M - &Mp).amax() / Mp.amax() < tol,
            "crba {}",
            (&M - &Mp).amax()
        );
        let Minv = compute_minverse(&model, &mut d, &q).unwrap().clone();
        let Mp = mat_of(&c["minverse"]);
        let e = (&Minv - &Mp).amax() / Mp.amax();
        worst_minv = worst_minv.max(e);
        assert!(e < tol, "minverse {e}");
        let nle = nonlinear_effects(&model, &mut d, &q, &v).unwrap().clone();
        assert!(rel(&nle, &vec_of(&c["nonlinear_effects"])) < tol, "nle");
        let g = gravity_torques(&model, &mut d, &q).unwrap().clone();
        assert!(rel(&g, &vec_of(&c["gravity_torques"])) < tol, "g");
        let ddq = aba(&model, &mut d, &q, &v, &tau).unwrap().clone();
        assert!(
            rel(&ddq, &vec_of(&c["aba"])) < tol,
            "aba {}",
            rel(&ddq, &vec_of(&c["aba"]))
        );
        let ke = kinetic_energy(&model, &mut d, &q, &v).unwrap();
        let kp = c["kinetic_energy"].as_f64().unwrap();
        assert!((ke - kp).abs() < tol * kp.abs().max(1.0), "ke {ke} {kp}");
        let pe = potential_energy(&model, &mut d, &q).unwrap();
        let pp = c["potential_energy"].as_f64().unwrap();
        assert!((pe - pp).abs() < tol * pp.abs().max(1.0), "pe {pe} {pp}");
        let com = center_of_mass(&model, &mut d, &q).unwrap();
        assert!(
            (com - Vec3::from_column_slice(&vec_of(&c["com"]))).amax() < tol,
            "com"
        );
        forward_kinematics_qv(&model, &mut d, &q, &v).unwrap();
        for (i, p) in c["placements"].as_array().unwrap().iter().enumerate() {
            let T = Transform::new(
                mat3(&p["rotation"]),
                Vec3::from_column_slice(&vec_of(&p["translation"])),
            );
            assert!(
                (d.placements[i].inverse() * T).is_identity(tol),
                "placement {i}"
            );
            let V = DVector::from_column_slice(d.velocities[i].to_vector().as_slice());
            assert!(rel(&V, &vec_of(&c["velocities"][i])) < tol, "velocity {i}");
        }
        let last = JointId(model.njoints() - 1);
        let J = joint_jacobian(&model, &mut d, &q, last, ReferenceFrame::Body)
            .unwrap()
            .clone();
        assert!(
            (&J - mat_of(&c["jacobian_last_body"])).amax() < tol,
            "jacobian"
        );
        let C = coriolis_matrix(&model, &mut d, &q, &v).unwrap().clone();
        let Cp = mat_of(&c["coriolis"]);
        assert!(
            (&C - &Cp).amax() < tol * Cp.amax().max(1.0),
            "coriolis matrix"
        );
        let cv = C * DVector::from_column_slice(&v);
        assert!(rel(&cv, &vec_of(&c["coriolis_times_v"])) < tol, "coriolis");
    }
    eprintln!("minverse: max relative error {worst_minv:.1e}");
}
