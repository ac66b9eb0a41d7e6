//! The analytical derivatives of RNEA, ABA and gravity against central finite differences on the
//! manifold (`q ⊕ ±h e_k`, h = 1e-6), on every built-in model, random trees with every joint
//! type (free-flyer root, spherical, planar, prismatic, revolute and continuous joints with random
//! axes) and the robots of example-robot-data; and their identities (`∂τ/∂a = M`,
//! `∂q̈/∂τ = M⁻¹`, `∂q̈/∂x = -M⁻¹ ∂τ/∂x`).
#![allow(non_snake_case)]

use crate::common;
use common::*;
use nalgebra::{DMatrix, DVector};
use rigid::io::urdf::load_urdf;
use rigid::multibody::*;
use rigid::spatial::{Vec3, Wrench};

/// Step of the central differences.
const H: f64 = 1e-6;
/// Largest relative error accepted against finite differences.
const FD_TOLERANCE: f64 = 1e-6;

/// `‖x - y‖max / max(‖y‖max, 1e-3)`: relative to the largest entry (absolute below 1e-3, for
/// matrices that are zero).
fn rel(x: &DMatrix<f64>, y: &DMatrix<f64>) -> f64 {
    (x - y).amax() / y.amax().max(1e-3)
}

/// `∂f/∂q` by central differences along `q ⊕ ±h e_k`.
fn fd_q(model: &Model, q: &[f64], mut f: impl FnMut(&[f64]) -> DVector<f64>) -> DMatrix<f64> {
    let nv = model.nv();
    let cols: Vec<DVector<f64>> = (0..nv)
        .map(|k| {
            let mut e = vec![0.0; nv];
            e[k] = 1.0;
            (f(&step(model, q, &e, H)) - f(&step(model, q, &e, -H))) / (2.0 * H)
        })
        .collect();
    DMatrix::from_columns(&cols)
}

/// `∂f/∂x` by central differences (x a vector).
fn fd_x(x: &[f64], mut f: impl FnMut(&[f64]) -> DVector<f64>) -> DMatrix<f64> {
    let cols: Vec<DVector<f64>> = (0..x.len())
        .map(|k| {
            let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
            xp[k] += H;
            xm[k] -= H;
            (f(&xp) - f(&xm)) / (2.0 * H)
        })
        .collect();
    DMatrix::from_columns(&cols)
}

/// Random external wrenches, one per body.
fn wrenches(model: &Model, rng: &mut Rng) -> Vec<Wrench> {
    let mut r = || {
        Vec3::new(
            rng.uniform(-3.0, 3.0),
            rng.uniform(-3.0, 3.0),
            rng.uniform(-3.0, 3.0),
        )
    };
    (0..model.njoints())
        .map(|_| Wrench::new(r(), r()))
        .collect()
}

/// The largest relative errors `(∂τ/∂q, ∂τ/∂v)` of the RNEA derivatives at one state, and checks
/// `∂τ/∂a = M` and `τ = rnea` on the way.
fn rnea_errors(
    model: &Model,
    q: &[f64],
    v: &[f64],
    a: &[f64],
    fext: Option<&[Wrench]>,
) -> (f64, f64) {
    let mut data = Data::new(model);
    let mut fd = Data::new(model);
    let (dq, dv, da) = {
        let d = match fext {
            Some(f) => rnea_derivatives_with_external(model, &mut data, q, v, a, f),
            None => rnea_derivatives(model, &mut data, q, v, a),
        }
        .unwrap();
        (d.dtau_dq.clone(), d.dtau_dv.clone(), d.dtau_da.clone())
    };
    let tau = data.tau.clone();
    let mut id = |q: &[f64], v: &[f64]| match fext {
        Some(f) => rnea_with_external(model, &mut fd, q, v, a, f)
            .unwrap()
            .clone(),
        None => rnea(model, &mut fd, q, v, a).unwrap().clone(),
    };
    assert!(rel_err_v(&tau, &id(q, v)) < 1e-12, "{}: τ", model.name());
    let fd_dq = fd_q(model, q, |q| id(q, v));
    let fd_dv = fd_x(v, |v| id(q, v));
    let m = crba(model, &mut fd, q).unwrap().clone();
    assert!(
        rel(&da, &m) < 1e-12,
        "{}: ∂τ/∂a ≠ M: {}",
        model.name(),
        rel(&da, &m)
    );
    (rel(&dq, &fd_dq), rel(&dv, &fd_dv))
}

/// The largest relative errors `(∂q̈/∂q, ∂q̈/∂v, ∂q̈/∂τ)` of the ABA derivatives at one state.
fn aba_errors(
    model: &Model,
    q: &[f64],
    v: &[f64],
    tau: &[f64],
    fext: Option<&[Wrench]>,
) -> [f64; 3] {
    let mut data = Data::new(model);
    let mut fd = Data::new(model);
    let (dq, dv, dtau) = {
        let d = match fext {
            Some(f) => aba_derivatives_with_external(model, &mut data, q, v, tau, f),
            None => aba_derivatives(model, &mut data, q, v, tau),
        }
        .unwrap();
        (d.dqdd_dq.clone(), d.dqdd_dv.clone(), d.dqdd_dtau.clone())
    };
    let mut fd_ = |q: &[f64], v: &[f64], tau: &[f64]| match fext {
        Some(f) => aba_with_external(model, &mut fd, q, v, tau, f)
            .unwrap()
            .clone(),
        None => aba(model, &mut fd, q, v, tau).unwrap().clone(),
    };
    let fd_dq = fd_q(model, q, |q| fd_(q, v, tau));
    let fd_dv = fd_x(v, |v| fd_(q, v, tau));
    let fd_dtau = fd_x(tau, |tau| fd_(q, v, tau));
    [rel(&dq, &fd_dq), rel(&dv, &fd_dv), rel(&dtau, &fd_dtau)]
}

fn assert_small(what: &str, model: &Model, errors: &[f64]) {
    for (k, e) in errors.iter().enumerate() {
        assert!(
            *e < FD_TOLERANCE,
            "{}: {what}[{k}] differs from finite differences by {e:.2e} relative",
            model.name()
        );
    }
}

#[test]
fn rnea_derivatives_equal_finite_differences_on_every_model() {
    let mut rng = Rng::new(20);
    for model in models() {
        let mut worst: [f64; 2] = [0.0; 2];
        for s in 0..4 {
            let (q, v, a) = state(&model, &mut rng);
            let fext = wrenches(&model, &mut rng);
            let (eq, ev) = rnea_errors(&model, &q, &v, &a, (s % 2 == 1).then_some(&fext[..]));
            worst = [worst[0].max(eq), worst[1].max(ev)];
        }
        eprintln!(
            "{}: ∂τ/∂q {:.1e}, ∂τ/∂v {:.1e}",
            model.name(),
            worst[0],
            worst[1]
        );
        assert_small("rnea_derivatives", &model, &worst);
    }
}

#[test]
fn aba_derivatives_equal_finite_differences_on_every_model() {
    let mut rng = Rng::new(21);
    for model in models() {
        let mut worst = [0.0f64; 3];
        for s in 0..3 {
            let (q, v, tau) = state(&model, &mut rng);
            let fext = wrenches(&model, &mut rng);
            let e = aba_errors(&model, &q, &v, &tau, (s == 1).then_some(&fext[..]));
            worst = [worst[0].max(e[0]), worst[1].max(e[1]), worst[2].max(e[2])];
        }
        eprintln!(
            "{}: ∂q̈/∂q {:.1e}, ∂q̈/∂v {:.1e}, ∂q̈/∂τ {:.1e}",
            model.name(),
            worst[0],
            worst[1],
            worst[2]
        );
        assert_small("aba_derivatives", &model, &worst);
    }
}

#[test]
fn gravity_derivatives_equal_finite_differences_and_the_rnea_derivatives_at_rest() {
    let mut rng = Rng::new(22);
    for model in models() {
        let mut data = Data::new(&model);
        let mut fd = Data::new(&model);
        let (q, _, _) = state(&model, &mut rng);
        let dg = gravity_derivatives(&model, &mut data, &q).unwrap().clone();
        let g = data.g.clone();
        assert!(rel_err_v(&g, gravity_torques(&model, &mut fd, &q).unwrap()) < 1e-12);
        let fd_dg = fd_q(&model, &q, |q| {
            gravity_torques(&model, &mut fd, q).unwrap().clone()
        });
        assert!(
            rel(&dg, &fd_dg) < FD_TOLERANCE,
            "{}: {:.2e}",
            model.name(),
            rel(&dg, &fd_dg)
        );
        let zero = vec![0.0; model.nv()];
        let d = rnea_derivatives(&model, &mut data, &q, &zero, &zero).unwrap();
        assert!(rel(d.dtau_dq, &dg) < 1e-12, "{}", model.name());
        assert!(d.dtau_dv.amax() == 0.0, "{}: ∂τ/∂v at rest", model.name());
    }
}

#[test]
fn aba_derivatives_are_minus_minverse_times_the_rnea_derivatives_at_qdd() {
    let mut rng = Rng::new(23);
    for model in models() {
        let mut data = Data::new(&model);
        let (q, v, tau) = state(&model, &mut rng);
        let (dq, dv, minv) = {
            let d = aba_derivatives(&model, &mut data, &q, &v, &tau).unwrap();
            (d.dqdd_dq.clone(), d.dqdd_dv.clone(), d.dqdd_dtau.clone())
        };
        let ddq = data.ddq.clone();
        let mut other = Data::new(&model);
        let r = rnea_derivatives(&model, &mut other, &q, &v, ddq.as_slice()).unwrap();
        let (rq, rv) = (r.dtau_dq.clone(), r.dtau_dv.clone());
        let m = crba(&model, &mut other, &q).unwrap().clone();
        let eye = DMatrix::<f64>::identity(model.nv(), model.nv());
        assert!(rel(&(&m * &minv), &eye) < 1e-9, "{}: M M⁻¹", model.name());
        assert!(rel(&(&m * &dq), &(-rq)) < 1e-9, "{}: M ∂q̈/∂q", model.name());
        assert!(rel(&(&m * &dv), &(-rv)) < 1e-9, "{}: M ∂q̈/∂v", model.name());
        let x = aba(&model, &mut other, &q, &v, &tau).unwrap();
        assert!(rel_err_v(&ddq, x) < 1e-12, "{}: q̈", model.name());
    }
}

/// Derivatives between different branches of a tree are zero, and every call overwrites what a
/// previous state left (no stale entries).
#[test]
fn derivatives_keep_no_state_from_a_previous_call() {
    let mut rng = Rng::new(24);
    for model in [random_tree(9, 10, true), aligned_forest()] {
        let mut data = Data::new(&model);
        let mut fresh = Data::new(&model);
        for _ in 0..3 {
            let (q, v, a) = state(&model, &mut rng);
            rnea_derivatives(&model, &mut data, &q, &v, &a).unwrap();
            aba_derivatives(&model, &mut data, &q, &v, &a).unwrap();
        }
        let (q, v, a) = state(&model, &mut rng);
        let x = rnea_derivatives(&model, &mut data, &q, &v, &a)
            .unwrap()
            .dtau_dq
            .clone();
        let y = rnea_derivatives(&model, &mut fresh, &q, &v, &a)
            .unwrap()
            .dtau_dq
            .clone();
        assert_eq!(x, y, "{}", model.name());
        let x = aba_derivatives(&model, &mut data, &q, &v, &a)
            .unwrap()
            .dqdd_dv
            .clone();
        let y = aba_derivatives(&model, &mut fresh, &q, &v, &a)
            .unwrap()
            .dqdd_dv
            .clone();
        assert_eq!(x, y, "{}", model.name());
    }
}

#[test]
fn derivatives_reject_bad_inputs_with_the_argument_named() {
    let model = random_tree(3, 5, false);
    let mut data = Data::new(&model);
    let (q, v, a) = state(&model, &mut Rng::new(1));
    let e = rnea_derivatives(&model, &mut data, &q, &v[1..], &a).unwrap_err();
    assert!(e.to_string().contains('v'), "{e}");
    let mut bad = a.clone();
    bad[2] = f64::NAN;
    let e = aba_derivatives(&model, &mut data, &q, &v, &bad).unwrap_err();
    assert!(e.to_string().contains("tau[2]"), "{e}");
    let mut fext = vec![Wrench::zero(); model.njoints()];
    fext[1].f.x = f64::INFINITY;
    let e = rnea_derivatives_with_external(&model, &mut data, &q, &v, &a, &fext).unwrap_err();
    assert!(e.to_string().contains("fext[1]"), "{e}");
    let e = aba_derivatives_with_external(&model, &mut data, &q, &v, &a, &fext[1..]).unwrap_err();
    assert!(e.to_string().contains("fext"), "{e}");
    let mut qn = q.clone();
    qn[3] *= 1.1; // the free-flyer root's quaternion
    let e = gravity_derivatives(&model, &mut data, &qn).unwrap_err();
    assert!(e.to_string().contains("root"), "{e}");
    let other = random_tree(4, 7, false);
    let mut wrong = Data::new(&other);
    assert!(matches!(
        rnea_derivatives(&model, &mut wrong, &q, &v, &a),
        Err(MultibodyError::DataMismatch { .. })
    ));
}

/// The robots of example-robot-data (as in `tests/it/pinocchio.rs`, loaded with rigid's URDF
/// importer from the copies under `tests/fixtures/robots/`), against finite differences.
#[test]
fn derivatives_equal_finite_differences_on_example_robot_data() {
    const ROBOTS: [(&str, bool); 6] = [
        ("ur_description/urdf/ur5_robot.urdf", false),
        ("panda_description/urdf/panda.urdf", false),
        ("solo_description/robots/solo12.urdf", true),
        ("anymal_b_simple_description/robots/anymal.urdf", true),
        ("talos_data/robots/talos_reduced.urdf", true),
        ("talos_data/robots/talos_full_v2.urdf", true),
    ];
    let dir = example_robot_data();
    let mut rng = Rng::new(25);
    for (file, floating) in ROBOTS {
        let model = load_urdf(dir.join(file), floating).unwrap_or_else(|e| panic!("{file}: {e}"));
        let (q, v, a) = state(&model, &mut rng);
        let fext = wrenches(&model, &mut rng);
        let (eq, ev) = rnea_errors(&model, &q, &v, &a, Some(&fext));
        let e = aba_errors(&model, &q, &v, &a, None);
        eprintln!(
            "{file}: ∂τ/∂q {eq:.1e}, ∂τ/∂v {ev:.1e}, ∂q̈/∂q {:.1e}, ∂q̈/∂v {:.1e}, ∂q̈/∂τ {:.1e}",
            e[0], e[1], e[2]
        );
        assert_small("rnea_derivatives", &model, &[eq, ev]);
        assert_small("aba_derivatives", &model, &e);
    }
}

/// The batch entry points give the single calls' matrices (row-major) bit for bit, in order, on
/// 1 and 2 threads.
#[test]
fn batch_derivatives_equal_single_calls_bit_for_bit() {
    let model = random_tree(6, 7, true);
    let (nq, nv, n) = (model.nq(), model.nv(), 13);
    let nn = nv * nv;
    let mut rng = Rng::new(26);
    let (mut qs, mut vs, mut xs) = (vec![], vec![], vec![]);
    for _ in 0..n {
        let (q, v, x) = state(&model, &mut rng);
        qs.extend(q);
        vs.extend(v);
        xs.extend(x);
    }
    let mut data = Data::new(&model);
    let row_major = |m: &DMatrix<f64>| m.transpose().as_slice().to_vec();
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut out: Vec<Vec<f64>> = (0..5).map(|_| vec![0.0; n * nn]).collect();
        pool.install(|| {
            let [a, b, c, d, e] = &mut out[..] else {
                unreachable!()
            };
            batch::rnea_derivatives_batch(&model, &qs, &vs, &xs, a, b).unwrap();
            batch::aba_derivatives_batch(&model, &qs, &vs, &xs, c, d, e).unwrap();
        });
        for k in 0..n {
            let (q, v, x) = (
                &qs[k * nq..][..nq],
                &vs[k * nv..][..nv],
                &xs[k * nv..][..nv],
            );
            let r = rnea_derivatives(&model, &mut data, q, v, x).unwrap();
            assert_eq!(row_major(r.dtau_dq), &out[0][k * nn..][..nn]);
            assert_eq!(row_major(r.dtau_dv), &out[1][k * nn..][..nn]);
            let f = aba_derivatives(&model, &mut data, q, v, x).unwrap();
            assert_eq!(row_major(f.dqdd_dq), &out[2][k * nn..][..nn]);
            assert_eq!(row_major(f.dqdd_dv), &out[3][k * nn..][..nn]);
            assert_eq!(row_major(f.dqdd_dtau), &out[4][k * nn..][..nn]);
        }
    }
    let mut short = vec![0.0; nn];
    let e = batch::rnea_derivatives_batch(&model, &qs, &vs, &xs, &mut short.clone(), &mut short)
        .unwrap_err();
    assert!(e.to_string().contains("out"), "{e}");
}

#[test]
fn derivatives_of_a_model_without_joints_are_empty() {
    let model = ModelBuilder::new("empty").build().unwrap();
    let mut data = Data::new(&model);
    let d = rnea_derivatives(&model, &mut data, &[], &[], &[]).unwrap();
    assert_eq!(d.dtau_dq.shape(), (0, 0));
    let d = aba_derivatives(&model, &mut data, &[], &[], &[]).unwrap();
    assert_eq!(d.dqdd_dtau.shape(), (0, 0));
    assert_eq!(
        gravity_derivatives(&model, &mut data, &[]).unwrap().shape(),
        (0, 0)
    );
    let (mut a, mut b) = (DMatrix::zeros(0, 0), DMatrix::zeros(0, 0));
    integrate_jacobians(&model, &[], &[], 1.0, &mut a, &mut b).unwrap();
    difference_jacobians(&model, &[], &[], &mut a, &mut b).unwrap();
    let (mut x, mut y) = (vec![], vec![]);
    batch::rnea_derivatives_batch(&model, &[], &[], &[], &mut x, &mut y).unwrap();
}
