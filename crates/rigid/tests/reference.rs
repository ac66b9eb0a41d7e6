//! The fast algorithms equal the textbook ones (`rigid::multibody::reference`, spatial_v2's
//! `ID.m`, `HandC.m`, `FDab.m`) to 1e-12 on random trees of every joint type, with armature,
//! and on the robots of example-robot-data (fixed and free-flyer base).

#![allow(non_snake_case)]

mod common;

use common::{models, rel_err_m, rel_err_v, state};
use rigid::multibody::{aba, crba, reference, rnea, Data, Model, Rng};

/// Largest relative difference of (RNEA, CRBA, ABA) between the fast and the reference
/// algorithms over `n` random states of `model`.
fn worst(model: &Model, n: usize, seed: u64) -> [f64; 3] {
    let mut rng = Rng::new(seed);
    let mut data = Data::new(model);
    let mut e = [0.0f64; 3];
    for _ in 0..n {
        let (q, v, a) = state(model, &mut rng);
        let tau = reference::rnea(model, &q, &v, &a).unwrap();
        e[0] = e[0].max(rel_err_v(rnea(model, &mut data, &q, &v, &a).unwrap(), &tau));
        let M = reference::crba(model, &q).unwrap();
        e[1] = e[1].max(rel_err_m(crba(model, &mut data, &q).unwrap(), &M));
        let ddq = reference::aba(model, &q, &v, tau.as_slice()).unwrap();
        e[2] = e[2].max(rel_err_v(
            aba(model, &mut data, &q, &v, tau.as_slice()).unwrap(),
            &ddq,
        ));
    }
    e
}

#[test]
fn fast_rnea_crba_aba_equal_the_reference_on_random_trees_of_every_joint_type() {
    for (k, model) in models().iter().enumerate() {
        let e = worst(model, 20, 100 + k as u64);
        assert!(e.iter().all(|x| *x < 1e-12), "{}: {e:?}", model.name());
    }
}

#[test]
fn the_reference_aba_inverts_the_reference_rnea_and_crba_is_symmetric() {
    for (k, model) in models().iter().enumerate() {
        let mut rng = Rng::new(7 + k as u64);
        let (q, v, a) = state(model, &mut rng);
        let tau = reference::rnea(model, &q, &v, &a).unwrap();
        let ddq = reference::aba(model, &q, &v, tau.as_slice()).unwrap();
        let a = nalgebra::DVector::from_vec(a);
        assert!(rel_err_v(&ddq, &a) < 1e-9, "{}", model.name());
        let M = reference::crba(model, &q).unwrap();
        assert!(rel_err_m(&M, &M.transpose()) < 1e-14, "{}", model.name());
        // M a + nle = τ, nle = rnea(q, v, 0)
        let nle = reference::rnea(model, &q, v.as_slice(), &vec![0.0; model.nv()]).unwrap();
        assert!(
            rel_err_v(&(&M * &a + nle), &tau) < 1e-10,
            "{}",
            model.name()
        );
    }
}

#[test]
fn the_reference_refuses_bad_input_like_the_fast_algorithms() {
    let model = rigid::multibody::builtin("puma560").unwrap();
    assert!(reference::rnea(&model, &[0.0; 5], &[0.0; 6], &[0.0; 6]).is_err());
    assert!(reference::crba(&model, &[f64::NAN; 6]).is_err());
    assert!(reference::aba(&model, &[0.0; 6], &[0.0; 6], &[0.0; 7]).is_err());
}

#[test]
fn fast_rnea_crba_aba_equal_the_reference_on_example_robot_data() {
    let Some(dir) = common::example_robot_data() else {
        eprintln!("example-robot-data not found: robots skipped");
        return;
    };
    let robots = [
        ("ur_description/urdf/ur5_robot.urdf", false),
        ("panda_description/urdf/panda.urdf", false),
        ("solo_description/robots/solo12.urdf", true),
        ("anymal_b_simple_description/robots/anymal.urdf", true),
        ("talos_data/robots/talos_reduced.urdf", true),
        ("talos_data/robots/talos_full_v2.urdf", true),
        ("hyq_description/robots/hyq_no_sensors.urdf", true),
        ("tiago_description/robots/tiago.urdf", false),
    ];
    for (path, floating) in robots {
        let file = dir.join(path);
        if !file.exists() {
            continue;
        }
        let opts = rigid::io::urdf::UrdfOptions {
            floating,
            ..Default::default()
        };
        let model = rigid::io::urdf::load_urdf_with(&file, &opts).unwrap().0;
        let e = worst(&model, 5, 11);
        // Talos with its fingers has cond(M) ≈ 1.2e7: there the fast ABA is within 2.4e-12 of
        // the true q̈ (the reference, with 6x6 inverses, within 2e-13), both far inside the
        // conditioning bound ε κ(M) ≈ 3e-9; every other robot meets 1e-12
        let aba_tol = if path.contains("talos_full") {
            5e-12
        } else {
            1e-12
        };
        assert!(
            e[0] < 1e-12 && e[1] < 1e-12 && e[2] < aba_tol,
            "{path}: {e:?}"
        );
    }
}

/// The plan is never stale: inertias changed through the API (`Model::set_inertias`) change
/// CRBA, `M⁻¹` and ABA exactly as the reference algorithms (which read no cache) say.
#[test]
fn changing_inertias_through_the_api_rebuilds_the_plan() {
    let mut model = common::random_tree(9, 10, true);
    let mut rng = Rng::new(21);
    let heavier: Vec<_> = model
        .inertias()
        .iter()
        .map(|_| common::inertia(&mut rng))
        .collect();
    model.set_inertias(&heavier).unwrap();
    let mut data = Data::new(&model);
    let (q, v, _) = state(&model, &mut rng);
    let M = reference::crba(&model, &q).unwrap();
    assert!(rel_err_m(crba(&model, &mut data, &q).unwrap(), &M) < 1e-12);
    let Minv = rigid::multibody::compute_minverse(&model, &mut data, &q).unwrap();
    let eye = nalgebra::DMatrix::identity(model.nv(), model.nv());
    assert!(rel_err_m(&(Minv * &M), &eye) < 1e-9);
    let tau = vec![0.3; model.nv()];
    let ddq = reference::aba(&model, &q, &v, &tau).unwrap();
    assert!(rel_err_v(aba(&model, &mut data, &q, &v, &tau).unwrap(), &ddq) < 1e-12);
    // a wrong count or a negative mass is refused, and the model is left as it was
    assert!(model.set_inertias(&heavier[1..]).is_err());
    let mut bad = heavier.clone();
    bad[2] = rigid::mass::SpatialInertia::from_parts(
        -1.0,
        rigid::spatial::Vec3::zeros(),
        rigid::mass::RotationalInertia::diagonal(1.0, 1.0, 1.0),
    );
    assert!(model.set_inertias(&bad).is_err());
    assert_eq!(model.inertias(), &heavier[..]);
}

/// `Data::composite_inertias` means one thing: the composite inertias of CRBA, whichever
/// algorithm filled it last (the RNEA derivatives compute them too; `M⁻¹` and the ABA
/// derivatives keep their per-body inertias elsewhere).
#[test]
fn composite_inertias_are_the_composites_after_every_algorithm_that_writes_them() {
    let model = common::random_tree(4, 12, false);
    let mut rng = Rng::new(8);
    let (q, v, a) = state(&model, &mut rng);
    let mut data = Data::new(&model);
    crba(&model, &mut data, &q).unwrap();
    let after_crba = data.composite_inertias.clone();
    let mut other = Data::new(&model);
    rigid::multibody::rnea_derivatives(&model, &mut other, &q, &v, &a).unwrap();
    let mut other2 = Data::new(&model);
    crba(&model, &mut other2, &q).unwrap();
    rigid::multibody::aba_derivatives(&model, &mut other2, &q, &v, &a).unwrap();
    rigid::multibody::compute_minverse(&model, &mut other2, &q).unwrap();
    for ((x, y), z) in after_crba
        .iter()
        .zip(&other.composite_inertias)
        .zip(&other2.composite_inertias)
    {
        let (x, y, z) = (x.matrix(), y.matrix(), z.matrix());
        assert!((x - y).amax() < 1e-12 * x.amax().max(1.0));
        assert_eq!(x, z);
    }
}
