//! The fast algorithms equal the textbook ones (`rigid::multibody::reference`, spatial_v2's
//! `ID.m`, `HandC.m`, `FDab.m`) to 1e-12 on random trees of every joint type, with armature,
//! and on the robots of example-robot-data (fixed and free-flyer base).

#![allow(non_snake_case)]

use crate::common;

use common::{models, rel_err_m, rel_err_v, state};
use rigid::multibody::{aba, crba, reference, rnea, Data, Model, Rng};

/// Over `n` random states of `model`, the largest relative differences between the fast and the
/// reference algorithms: `[RNEA, CRBA, ABA (forward error), ABA (backward error)]`, and the
/// largest condition number `κ(M)` met. The backward error of the fast ABA is
/// `‖M q̈ + nle - τ‖∞ / max(1, ‖τ‖∞)` with the reference's `M` and `nle`: a forward-dynamics
/// solver can do no better than a backward error at round-off, and then its forward error is up
/// to `ε κ(M)` (about 1e-9 on iCub, `κ(M) ≈ 2e8`, for the fast ABA, the reference ABA and the
/// Cholesky solve alike).
fn worst(model: &Model, n: usize, seed: u64) -> ([f64; 4], f64) {
    let mut rng = Rng::new(seed);
    let mut data = Data::new(model);
    let (mut e, mut kappa) = ([0.0f64; 4], 0.0f64);
    for _ in 0..n {
        let (q, v, a) = state(model, &mut rng);
        let tau = reference::rnea(model, &q, &v, &a).unwrap();
        e[0] = e[0].max(rel_err_v(rnea(model, &mut data, &q, &v, &a).unwrap(), &tau));
        let M = reference::crba(model, &q).unwrap();
        e[1] = e[1].max(rel_err_m(crba(model, &mut data, &q).unwrap(), &M));
        let ddq = reference::aba(model, &q, &v, tau.as_slice()).unwrap();
        let fast = aba(model, &mut data, &q, &v, tau.as_slice())
            .unwrap()
            .clone();
        e[2] = e[2].max(rel_err_v(&fast, &ddq));
        let nle = reference::rnea(model, &q, &v, &vec![0.0; model.nv()]).unwrap();
        e[3] = e[3].max(rel_err_v(&(&M * &fast + nle), &tau));
        let l = M.symmetric_eigenvalues();
        kappa = kappa.max(l.max() / l.min());
    }
    (e, kappa)
}

/// The fast algorithms equal the reference ones: RNEA and CRBA to 1e-12; ABA to a backward
/// error of 1e-12 and a forward error of 1e-12, or `1e-14 κ(M)` on an ill-conditioned model.
fn assert_equal(name: &str, (e, kappa): ([f64; 4], f64)) {
    let forward = 1e-12f64.max(1e-14 * kappa);
    assert!(
        e[0] < 1e-12 && e[1] < 1e-12 && e[3] < 1e-12 && e[2] < forward,
        "{name}: rnea, crba, aba forward, aba backward {e:?}, κ(M) {kappa:e}"
    );
}

#[test]
fn fast_rnea_crba_aba_equal_the_reference_on_random_trees_of_every_joint_type() {
    for (k, model) in models().iter().enumerate() {
        assert_equal(model.name(), worst(model, 20, 100 + k as u64));
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

/// Every URDF of example-robot-data that loads (with a free-flyer root, so that the base's six
/// columns are exercised too): the fast algorithms equal the reference ones. Every run walks the
/// files checked in under `tests/fixtures/robots/`; `RIGID_CROSSCHECK=1` adds every file of the
/// installed package (live: the package's folder comes from Python).
#[test]
fn fast_rnea_crba_aba_equal_the_reference_on_every_robot_of_example_robot_data() {
    check_robots("fixture", common::example_robot_data());
    if common::reference::live("every URDF of the installed example-robot-data") {
        let roots = common::reference::package_roots();
        check_robots("live", roots["example-robot-data"].clone());
    }
}

fn check_robots(source: &str, dir: std::path::PathBuf) {
    let mut files = Vec::new();
    let mut stack = vec![dir];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "urdf") {
                files.push(p);
            }
        }
    }
    files.sort();
    let mut checked = 0;
    for file in &files {
        let opts = rigid::io::urdf::UrdfOptions {
            floating: true,
            inertia: rigid::io::urdf::InertiaPolicy::Warn,
            ..Default::default()
        };
        let Ok((model, _)) = rigid::io::urdf::load_urdf_with(file, &opts) else {
            continue; // refused files are the URDF tests' business
        };
        if model.nv() == 6 || !model.inertia_issues().is_empty() {
            continue; // nothing but the base, or a non-physical body (ABA undefined)
        }
        let (e, kappa) = worst(&model, 3, 11);
        let name = file.to_string_lossy();
        assert_equal(&name, (e, kappa));
        if e[2] >= 1e-12 {
            eprintln!("{name}: ABA forward error {:.1e} at κ(M) {kappa:.1e}", e[2]);
        }
        checked += 1;
    }
    eprintln!(
        "{checked} of {} URDF files of example-robot-data ({source}) checked",
        files.len()
    );
    if source == "live" {
        assert!(checked >= 40, "only {checked} robots loaded");
    } else {
        // the checked-in copies: 10 of their 11 files load with physical bodies and more than
        // the base
        assert!(checked >= 10, "only {checked} robots loaded");
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
