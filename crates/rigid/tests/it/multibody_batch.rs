//! Batch evaluation equals single calls bit for bit, in order, on 1 and 2 threads.

use crate::common;
use rigid::multibody::*;

fn states(model: &Model, n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut rng = Rng::new(11);
    let (mut qs, mut vs, mut as_) = (vec![], vec![], vec![]);
    for _ in 0..n {
        let (q, v, a) = common::state(model, &mut rng);
        qs.extend(q);
        vs.extend(v);
        as_.extend(a);
    }
    (qs, vs, as_)
}

#[test]
fn batch_results_equal_single_calls_bit_for_bit() {
    let model = common::random_tree(5, 9, true);
    let (nq, nv, n) = (model.nq(), model.nv(), 37);
    let (qs, vs, as_) = states(&model, n);
    let mut data = Data::new(&model);
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let (mut tau, mut ddq, mut mass) =
            (vec![0.0; n * nv], vec![0.0; n * nv], vec![0.0; n * nv * nv]);
        pool.install(|| {
            batch::rnea_batch(&model, &qs, &vs, &as_, &mut tau).unwrap();
            batch::aba_batch(&model, &qs, &vs, &as_, &mut ddq).unwrap();
            batch::crba_batch(&model, &qs, &mut mass).unwrap();
        });
        for k in 0..n {
            let (q, v, a) = (
                &qs[k * nq..][..nq],
                &vs[k * nv..][..nv],
                &as_[k * nv..][..nv],
            );
            assert_eq!(
                rnea(&model, &mut data, q, v, a).unwrap().as_slice(),
                &tau[k * nv..][..nv]
            );
            assert_eq!(
                aba(&model, &mut data, q, v, a).unwrap().as_slice(),
                &ddq[k * nv..][..nv]
            );
            assert_eq!(
                crba(&model, &mut data, q).unwrap().as_slice(),
                &mass[k * nv * nv..][..nv * nv]
            );
        }
    }
}

#[test]
fn batch_rejects_ragged_inputs() {
    let model = puma560(Puma560Options::default());
    let mut tau = vec![0.0; 12];
    assert!(batch::rnea_batch(&model, &[0.0; 12], &[0.0; 12], &[0.0; 11], &mut tau).is_err());
    assert!(batch::rnea_batch(&model, &[0.0; 13], &[0.0; 12], &[0.0; 12], &mut tau).is_err());
    assert!(batch::rnea_batch(&model, &[0.0; 12], &[0.0; 12], &[0.0; 12], &mut tau[..6]).is_err());
    let mut m = vec![0.0; 72];
    assert!(batch::crba_batch(&model, &[0.0; 12], &mut m).is_ok());
}

/// A reused `Batch` gives the free functions' results bit for bit on every call (no state left
/// from the previous call: the second call's states differ), and refuses another model.
#[test]
fn a_reused_batch_equals_fresh_calls_and_checks_the_model() {
    let model = common::random_tree(4, 8, true);
    let nv = model.nv();
    let mut b = batch::Batch::new(&model);
    for (seed, n) in [(1, 23), (2, 40)] {
        let mut rng = Rng::new(seed);
        let (mut qs, mut vs, mut as_) = (vec![], vec![], vec![]);
        for _ in 0..n {
            let (q, v, a) = common::state(&model, &mut rng);
            qs.extend(q);
            vs.extend(v);
            as_.extend(a);
        }
        let (mut t1, mut t2) = (vec![0.0; n * nv], vec![0.0; n * nv]);
        b.rnea(&model, &qs, &vs, &as_, &mut t1).unwrap();
        batch::rnea_batch(&model, &qs, &vs, &as_, &mut t2).unwrap();
        assert_eq!(t1, t2);
        b.aba(&model, &qs, &vs, &as_, &mut t1).unwrap();
        batch::aba_batch(&model, &qs, &vs, &as_, &mut t2).unwrap();
        assert_eq!(t1, t2);
        let (mut m1, mut m2) = (vec![0.0; n * nv * nv], vec![0.0; n * nv * nv]);
        b.crba(&model, &qs, &mut m1).unwrap();
        batch::crba_batch(&model, &qs, &mut m2).unwrap();
        assert_eq!(m1, m2);
    }
    let other = puma560(Puma560Options::default());
    let mut tau = vec![0.0; 6];
    assert!(matches!(
        b.rnea(&other, &[0.0; 6], &[0.0; 6], &[0.0; 6], &mut tau),
        Err(MultibodyError::DataMismatch { .. })
    ));
}

/// The packed lower triangle equals the full matrices' entries on and below the diagonal, state
/// by state, for a random tree (zero blocks between branches included), and ragged lengths are
/// refused.
#[test]
fn crba_lower_packs_the_full_matrices_lower_triangles() {
    let model = common::random_tree(5, 9, true);
    let (nq, nv, n) = (model.nq(), model.nv(), 17);
    let mut rng = Rng::new(11);
    let mut qs = vec![];
    for _ in 0..n {
        qs.extend(common::state(&model, &mut rng).0);
    }
    let per = nv * (nv + 1) / 2;
    let (mut full, mut packed) = (vec![0.0; n * nv * nv], vec![f64::NAN; n * per]);
    batch::crba_batch(&model, &qs, &mut full).unwrap();
    batch::crba_lower_batch(&model, &qs, &mut packed).unwrap();
    for k in 0..n {
        let m = &full[k * nv * nv..][..nv * nv];
        let want: Vec<f64> = (0..nv)
            .flat_map(|j| (j..nv).map(move |i| m[j * nv + i]))
            .collect();
        assert_eq!(&packed[k * per..][..per], want.as_slice(), "state {k}");
    }
    assert!(batch::crba_lower_batch(&model, &qs[..nq * n - 1], &mut packed).is_err());
    assert!(batch::crba_lower_batch(&model, &qs, &mut packed[..per * n - 1]).is_err());
}
