//! The explicit model's derivation: the Lagrange derivation (composite inertias, Christoffel
//! symbols, `∂U/∂q`) and the symbolic RNEA agree term by term; both equal rigid's numeric CRBA,
//! `nonlinear_effects` and `gravity_torques` on random chains and trees with revolute and
//! prismatic joints on random axes; locking joints keeps the free joints' rows; the errors say
//! why a model has no explicit form.

use rigid::explicit::{
    lock_joints, symbolic_rnea, ExplicitError, ExplicitModel, Expr, TableOptions,
};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::multibody::*;
use rigid::spatial::{Transform, Vec3};

use crate::explicit_support;
use explicit_support::{random_model, rel, states};

/// `max |a - b|` over the terms (coefficient times parameter values).
fn difference(a: &Expr, b: &Expr, values: &[f64]) -> f64 {
    a.sub(b).max_abs(values)
}

fn rnea_agrees_with_lagrange(model: &Model) {
    let ex = ExplicitModel::derive(model).unwrap();
    let values = ex.parameters().values();
    let n = ex.n();
    let z = vec![0.0; n];
    let e = |k: usize| -> Vec<f64> { (0..n).map(|i| f64::from(u8::from(i == k))).collect() };
    // differences relative to the largest term of M or g
    let scale = (0..n * n)
        .map(|k| ex.mass(k / n, k % n).max_abs(&values))
        .chain((0..n).map(|i| ex.gravity(i).max_abs(&values)))
        .fold(0.0, f64::max);
    let mut worst: f64 = 0.0;
    let g = symbolic_rnea(model, &z, &z, true).unwrap();
    for (i, gi) in g.iter().enumerate() {
        worst = worst.max(difference(gi, ex.gravity(i), &values));
    }
    for k in 0..n {
        let col = symbolic_rnea(model, &z, &e(k), false).unwrap();
        let cen = symbolic_rnea(model, &e(k), &z, false).unwrap();
        for i in 0..n {
            worst = worst.max(difference(&col[i], ex.mass(i, k), &values));
            worst = worst.max(difference(&cen[i], ex.centrifugal(i, k), &values));
        }
        for l in k + 1..n {
            let v: Vec<f64> = (0..n)
                .map(|i| f64::from(u8::from(i == k || i == l)))
                .collect();
            let both = symbolic_rnea(model, &v, &z, false).unwrap();
            for (i, bi) in both.iter().enumerate() {
                let b = bi.sub(ex.centrifugal(i, k)).sub(ex.centrifugal(i, l));
                worst = worst.max(difference(&b, ex.coriolis(i, k, l), &values));
            }
        }
    }
    let worst = worst / scale;
    eprintln!(
        "{}: Lagrange vs symbolic RNEA, largest term difference {worst:.1e} of the largest term",
        model.name()
    );
    assert!(worst < 1e-12, "{}: {worst}", model.name());
}

#[test]
fn lagrange_and_symbolic_rnea_agree_term_by_term() {
    rnea_agrees_with_lagrange(&double_pendulum());
    rnea_agrees_with_lagrange(&puma560(Puma560Options { armature: true }));
    rnea_agrees_with_lagrange(&random_model(3, 4, false));
    rnea_agrees_with_lagrange(&random_model(4, 4, true));
}

fn equals_crba(model: &Model) {
    let ex = ExplicitModel::derive(model).unwrap();
    let tables = ex.tables(&TableOptions::default());
    let values = ex.parameters().values();
    let n = ex.n();
    let mut data = Data::new(model);
    let mut worst = [0.0f64; 4];
    for (q, v) in states(model, 50, 9) {
        let m = crba(model, &mut data, &q).unwrap().clone();
        let nle = nonlinear_effects(model, &mut data, &q, &v).unwrap().clone();
        let g = gravity_torques(model, &mut data, &q).unwrap().clone();
        let (mut me, mut mt, mut ce, mut ge) = (vec![], vec![], vec![0.0; n], vec![]);
        for (i, ci) in ce.iter_mut().enumerate() {
            for j in 0..n {
                me.push(ex.mass(i, j).eval(&q, &values));
                let entry = tables.entry(rigid::explicit::EntryKind::Mass(i.min(j), i.max(j)));
                mt.push(tables.eval(entry.unwrap(), &q));
                let c = ex.centrifugal(i, j).eval(&q, &values) * v[j] * v[j];
                let b: f64 = (j + 1..n)
                    .map(|k| ex.coriolis(i, j, k).eval(&q, &values) * v[j] * v[k])
                    .sum();
                *ci += c + b;
            }
            ge.push(ex.gravity(i).eval(&q, &values));
        }
        let nle_e: Vec<f64> = ce.iter().zip(&ge).map(|(c, g)| c + g).collect();
        let mref: Vec<f64> = (0..n * n).map(|k| m[(k / n, k % n)]).collect();
        worst[0] = worst[0].max(rel(&me, &mref));
        worst[1] = worst[1].max(rel(&mt, &mref));
        worst[2] = worst[2].max(rel(&nle_e, nle.as_slice()));
        worst[3] = worst[3].max(rel(&ge, g.as_slice()));
    }
    eprintln!(
        "{}: M {:.1e}, M (tables) {:.1e}, nle {:.1e}, g {:.1e}",
        model.name(),
        worst[0],
        worst[1],
        worst[2],
        worst[3]
    );
    assert!(
        worst.iter().all(|&w| w < 1e-12),
        "{}: {worst:?}",
        model.name()
    );
}

#[test]
fn explicit_models_of_random_chains_and_trees_equal_crba_nle_gravity() {
    for seed in 0..3 {
        equals_crba(&random_model(10 + seed, 5, false));
        equals_crba(&random_model(20 + seed, 5, true));
    }
}

#[test]
fn locked_joints_keep_the_rows_of_the_free_joints() {
    let full = random_model(31, 5, true);
    let locked = lock_joints(&full, &[("j1".into(), 0.4), ("j2".into(), -0.1)]).unwrap();
    assert_eq!(locked.nv(), 3);
    let keep = [0usize, 3, 4];
    let (mut df, mut dl) = (Data::new(&full), Data::new(&locked));
    for (q, v) in states(&locked, 20, 2) {
        let mut qf = vec![0.0; 5];
        let mut vf = vec![0.0; 5];
        for (k, &j) in keep.iter().enumerate() {
            qf[j] = q[k];
            vf[j] = v[k];
        }
        qf[1] = 0.4;
        qf[2] = -0.1;
        let mf = crba(&full, &mut df, &qf).unwrap().clone();
        let ml = crba(&locked, &mut dl, &q).unwrap().clone();
        let nf = nonlinear_effects(&full, &mut df, &qf, &vf).unwrap().clone();
        let nl = nonlinear_effects(&locked, &mut dl, &q, &v).unwrap().clone();
        for (a, &i) in keep.iter().enumerate() {
            assert!((nl[a] - nf[i]).abs() < 1e-12 * nf.amax().max(1.0));
            for (b, &j) in keep.iter().enumerate() {
                assert!((ml[(a, b)] - mf[(i, j)]).abs() < 1e-12 * mf.amax());
            }
        }
    }
    let err = lock_joints(&full, &[("nope".into(), 0.0)]).unwrap_err();
    assert!(err.to_string().contains("nope"), "{err}");
}

#[test]
fn models_without_an_explicit_form_get_an_error_that_says_why() {
    // a free-flyer root
    let mut b = ModelBuilder::new("floating");
    let body = SpatialInertia::from_com(
        1.0,
        Vec3::zeros(),
        RotationalInertia::diagonal(0.1, 0.1, 0.1),
    );
    b.add_joint(
        None,
        "root",
        JointType::FreeFlyer,
        Transform::identity(),
        body,
    )
    .unwrap();
    let e = ExplicitModel::derive(&b.build().unwrap()).unwrap_err();
    assert!(matches!(e, ExplicitError::UnsupportedJoint { .. }));
    assert!(
        e.to_string().contains("'root' is of type free_flyer"),
        "{e}"
    );
    // a spherical joint
    let mut b = ModelBuilder::new("ball");
    b.add_joint(
        None,
        "ball",
        JointType::Spherical,
        Transform::identity(),
        body,
    )
    .unwrap();
    let e = ExplicitModel::derive(&b.build().unwrap()).unwrap_err();
    assert!(e.to_string().contains("'ball' is of type spherical"), "{e}");
    // 13 joints
    let mut b = ModelBuilder::new("long");
    let mut parent = None;
    for k in 0..13 {
        let t = Transform::from_translation(Vec3::new(0.0, 0.0, 0.1));
        parent = Some(
            b.add_joint(
                parent,
                &format!("j{k}"),
                JointType::Revolute { axis: Vec3::y() },
                t,
                body,
            )
            .unwrap(),
        );
    }
    let e = ExplicitModel::derive(&b.build().unwrap()).unwrap_err();
    assert_eq!(e, ExplicitError::TooManyJoints { n: 13 });
    assert!(e.to_string().contains("at most 12 joints"), "{e}");
}
