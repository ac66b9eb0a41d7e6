//! Batches over parameters (issue 27): `regressor_batch` gives each state's regressor bit for
//! bit, on any number of threads, and `Y π` is `rnea` less the armature; a model with checked
//! parameters round-trips and names the first body that is not physical.

use crate::common::{every_joint_tree, models, state};
use rigid::identification::{
    model_parameters, model_with_checked_parameters, regressor_batch, ParameterError, Regressor,
};
use rigid::mass::{Consistency, Verdict};
use rigid::multibody::{rnea, Data, Model, Rng};

fn stacked(model: &Model, n: usize, seed: u64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut rng = Rng::new(seed);
    let (mut q, mut v, mut a) = (vec![], vec![], vec![]);
    for _ in 0..n {
        let (qi, vi, ai) = state(model, &mut rng);
        q.extend(qi);
        v.extend(vi);
        a.extend(ai);
    }
    (q, v, a)
}

#[test]
fn regressor_batch_is_the_single_regressor_bit_for_bit_on_any_thread_count() {
    let mut all = models();
    all.extend((0..2).map(|s| every_joint_tree(s, 10)));
    for model in &all {
        let (nq, nv, cols) = (model.nq(), model.nv(), 10 * model.njoints());
        let n = 23;
        let (q, v, a) = stacked(model, n, 5);
        let mut y = vec![f64::NAN; n * nv * cols]; // every entry written
        regressor_batch(model, &q, &v, &a, &mut y).unwrap();
        for threads in [1, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut y2 = vec![f64::NAN; y.len()];
            pool.install(|| regressor_batch(model, &q, &v, &a, &mut y2))
                .unwrap();
            assert!(y.iter().zip(&y2).all(|(x, z)| x.to_bits() == z.to_bits()));
        }
        let mut reg = Regressor::new(model);
        let mut data = Data::new(model);
        let pi = model_parameters(model);
        for k in 0..n {
            let (qk, vk, ak) = (
                &q[k * nq..(k + 1) * nq],
                &v[k * nv..(k + 1) * nv],
                &a[k * nv..(k + 1) * nv],
            );
            let single = reg.compute(model, qk, vk, ak).unwrap().clone();
            let tau = rnea(model, &mut data, qk, vk, ak).unwrap().clone();
            for r in 0..nv {
                let row = &y[(k * nv + r) * cols..(k * nv + r + 1) * cols];
                for c in 0..cols {
                    assert_eq!(row[c].to_bits(), single[(r, c)].to_bits());
                }
                let yp: f64 = row.iter().zip(pi.iter()).map(|(x, p)| x * p).sum();
                let armature = model.armature()[r] * ak[r];
                let scale = 1.0 + tau[r].abs();
                assert!(
                    (yp + armature - tau[r]).abs() < 1e-9 * scale,
                    "{}: Y pi != rnea",
                    model.name()
                );
            }
        }
    }
}

#[test]
fn regressor_batch_checks_lengths_and_takes_zero_states() {
    let model = &models()[0];
    let cols = 10 * model.njoints();
    regressor_batch(model, &[], &[], &[], &mut []).unwrap();
    let (q, v, a) = stacked(model, 2, 1);
    let mut y = vec![0.0; 2 * model.nv() * cols - 1];
    assert!(regressor_batch(model, &q, &v, &a, &mut y).is_err());
}

#[test]
fn checked_parameters_round_trip_and_name_the_bad_body() {
    for model in models() {
        // the models whose every body is physical (the PUMA 560's first link is a massless
        // rotor inertia: refused, as the test below of the model that has it)
        let physical = model.inertias().iter().all(|g| {
            !matches!(
                Consistency::of(g).verdict(),
                Verdict::BadMass
                    | Verdict::NonFinite
                    | Verdict::NotPositiveSemiDefinite
                    | Verdict::TriangleInequality
            )
        });
        let pi = model_parameters(&model);
        if !physical {
            assert!(model_with_checked_parameters(&model, pi.as_slice()).is_err());
            continue;
        }
        let back = model_with_checked_parameters(&model, pi.as_slice()).unwrap();
        let again = model_parameters(&back);
        for (x, y) in pi.iter().zip(again.iter()) {
            assert!((x - y).abs() <= 1e-15 * (1.0 + x.abs()), "{}", model.name());
        }
        if model.njoints() == 0 {
            continue;
        }
        let last = model.njoints() - 1;
        let mut bad = pi.clone();
        bad[10 * last] = -2.0;
        let e = model_with_checked_parameters(&model, bad.as_slice()).unwrap_err();
        assert!(
            matches!(&e, ParameterError::NotPhysical { body, joint, .. } if *body == last && *joint == model.joints()[last].name),
            "{e}"
        );
        assert!(e.to_string().contains("mass -2"), "{e}");
    }
}
