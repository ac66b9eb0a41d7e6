//! The batch entry points (states side by side in SIMD lanes, packs across threads) equal single
//! calls, in order, for every lane width, thread count and joint type, on every robot of
//! example-robot-data; they refuse what single calls refuse.

use crate::common;
use rigid::io::urdf::load_urdf;
use rigid::multibody::*;

/// Relative agreement asked of the lanes with the single calls: they take other steps in
/// another order in places (ABA's inertias in blocks; CRBA through the joint module for the
/// joints without a lane path), so round-off differs.
const TOLERANCE: f64 = 1e-13;

fn states(model: &Model, n: usize, seed: u64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut rng = Rng::new(seed);
    let (mut qs, mut vs, mut as_) = (vec![], vec![], vec![]);
    for _ in 0..n {
        let (q, v, a) = common::state(model, &mut rng);
        qs.extend(q);
        vs.extend(v);
        as_.extend(a);
    }
    (qs, vs, as_)
}

/// `‖x − y‖∞ / max(1, ‖y‖∞)`, infinite for NaN.
fn rel(x: &[f64], y: &[f64]) -> f64 {
    common::reference::rel(x, y, 1.0)
}

/// The largest relative difference, over `n` random states, between a batch of `width` lanes
/// and single calls, for RNEA, ABA, CRBA and CRBA's packed lower triangle.
fn worst(model: &Model, width: usize, n: usize, seed: u64) -> [f64; 4] {
    let (nq, nv) = (model.nq(), model.nv());
    let (qs, vs, as_) = states(model, n, seed);
    let mut b = batch::Batch::with_lanes(model, width);
    assert_eq!(b.lanes(), width);
    let per = nv * (nv + 1) / 2;
    let (mut tau, mut ddq) = (vec![f64::NAN; n * nv], vec![f64::NAN; n * nv]);
    let (mut mass, mut lower) = (vec![f64::NAN; n * nv * nv], vec![f64::NAN; n * per]);
    b.rnea(model, &qs, &vs, &as_, &mut tau).unwrap();
    // a massless subtree makes M singular: then the batch refuses as the single call does
    let aba_ok = b.aba(model, &qs, &vs, &as_, &mut ddq).is_ok();
    let mut single_aba_ok = true;
    b.crba(model, &qs, &mut mass).unwrap();
    b.crba_lower(model, &qs, &mut lower).unwrap();
    let mut data = Data::new(model);
    let mut e = [0.0f64; 4];
    for k in 0..n {
        let (q, v, a) = (
            &qs[k * nq..][..nq],
            &vs[k * nv..][..nv],
            &as_[k * nv..][..nv],
        );
        let t = rnea(model, &mut data, q, v, a).unwrap().clone();
        e[0] = e[0].max(rel(&tau[k * nv..][..nv], t.as_slice()));
        match aba(model, &mut data, q, v, a) {
            Ok(d) if aba_ok => {
                // where M is ill-conditioned (iCub: q̈ up to 2e8), two exact methods of the single
                // call (ABA, Cholesky) differ far more than 1e-13: there the batch must stay an
                // order of magnitude closer to the single call than that difference
                let d = d.clone();
                let c = forward_dynamics_cholesky(model, &mut data, q, v, a).unwrap();
                let spread = rel(d.as_slice(), c.as_slice());
                let e_aba = rel(&ddq[k * nv..][..nv], d.as_slice());
                e[1] = e[1].max(if e_aba > TOLERANCE && e_aba <= 0.1 * spread {
                    0.0
                } else {
                    e_aba
                });
            }
            Ok(_) => {}
            Err(_) => single_aba_ok = false,
        }
        let m = crba(model, &mut data, q).unwrap().clone();
        e[2] = e[2].max(rel(&mass[k * nv * nv..][..nv * nv], m.as_slice()));
        let mut packed = vec![0.0; per];
        batch::pack_lower(m.as_slice(), nv, &mut packed).unwrap();
        e[3] = e[3].max(rel(&lower[k * per..][..per], &packed));
    }
    assert_eq!(
        aba_ok,
        single_aba_ok,
        "{}: aba refused by one side only",
        model.name()
    );
    e
}

fn assert_close(what: &str, e: [f64; 4]) {
    assert!(
        e.iter().all(|x| *x <= TOLERANCE),
        "{what}: batch vs single calls, relative: rnea {:.1e}, aba {:.1e}, crba {:.1e}, crba_lower {:.1e}",
        e[0],
        e[1],
        e[2],
        e[3]
    );
}

/// Every built-in model, random trees (armature, every joint type among them) and the tree of
/// every joint type, in packs of 2, 4 and 8 lanes, with counts that leave a partial last pack.
#[test]
fn batch_results_equal_single_calls_for_every_width_and_joint_type() {
    let mut models = common::models();
    models.push(common::every_joint_tree(3, 14));
    models.push(common::every_joint_tree(8, 9));
    for model in &models {
        for width in [2, 4, 8] {
            for n in [1, width + 3, 37] {
                assert_close(
                    &format!("{} ({width} lanes, {n} states)", model.name()),
                    worst(model, width, n, 11 + n as u64),
                );
            }
        }
    }
}

/// Every robot of example-robot-data that rigid loads, fixed and with a free-flyer, in the
/// CPU's own lanes: the checked-in files, and with `RIGID_CROSSCHECK=1` every file of the
/// installed package.
#[test]
fn batch_equals_single_calls_on_every_example_robot_data_robot() {
    let mut dirs = vec![common::example_robot_data()];
    if common::reference::live("example-robot-data: every installed URDF in batches") {
        let roots = common::reference::package_roots();
        dirs.push(roots["example-robot-data"].clone());
    }
    let width = batch::Batch::new(&common::random_tree(1, 3, false)).lanes();
    for dir in dirs {
        let files = common::urdfs_under(&dir);
        let (mut compared, mut bitwise) = (0, 0);
        for file in &files {
            for floating in [false, true] {
                let Ok(model) = load_urdf(file, floating) else {
                    continue;
                };
                if model.nv() == 0 {
                    continue;
                }
                let e = worst(&model, width, 2 * width + 1, 5);
                eprintln!(
                    "{}: {:.1e} {:.1e} {:.1e} {:.1e}",
                    file.display(),
                    e[0],
                    e[1],
                    e[2],
                    e[3]
                );
                assert_close(&format!("{} (floating {floating})", file.display()), e);
                // the batch CRBA takes the single call's steps in the same order (revolute,
                // prismatic and free-flyer joints in lanes): the same numbers, bit for bit
                if model.joints().iter().all(|j| {
                    matches!(
                        j.kind,
                        JointType::Revolute { .. }
                            | JointType::Prismatic { .. }
                            | JointType::FreeFlyer
                    )
                }) {
                    assert_eq!(
                        e[2..],
                        [0.0, 0.0],
                        "{}: CRBA not bit for bit",
                        file.display()
                    );
                    bitwise += 1;
                }
                compared += 1;
            }
        }
        eprintln!(
            "{}: {compared} models in {width} lanes, CRBA bit for bit on {bitwise}",
            dir.display()
        );
        assert!(compared >= 8, "{}: only {compared} models", dir.display());
    }
}

/// On 1 and 2 threads the results are the same, bit for bit, in the input order.
#[test]
fn batch_results_do_not_depend_on_the_thread_count() {
    let model = common::random_tree(5, 9, true);
    let (nv, n) = (model.nv(), 37);
    let (qs, vs, as_) = states(&model, n, 3);
    let run = |threads: usize| {
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
        (tau, ddq, mass)
    };
    assert_eq!(run(1), run(2));
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

/// A NaN or a non-unit quaternion in any state is refused with the single call's error (naming
/// the input and index, or the joint), and nothing is computed from it.
#[test]
fn batch_refuses_what_single_calls_refuse() {
    let model = common::every_joint_tree(3, 14);
    let (nq, nv, n) = (model.nq(), model.nv(), 9);
    let (qs, vs, as_) = states(&model, n, 4);
    let mut data = Data::new(&model);
    let mut out = vec![0.0; n * nv];
    let mut mass = vec![0.0; n * nv * nv];
    // a NaN in state 6's velocity, index 2
    let mut bad = vs.clone();
    bad[6 * nv + 2] = f64::NAN;
    let single = rnea(
        &model,
        &mut data,
        &qs[6 * nq..][..nq],
        &bad[6 * nv..][..nv],
        &as_[..nv],
    )
    .unwrap_err()
    .to_string();
    let batched = batch::rnea_batch(&model, &qs, &bad, &as_, &mut out).unwrap_err();
    assert_eq!(batched.to_string(), single);
    assert!(matches!(
        batch::aba_batch(&model, &qs, &vs, &bad, &mut out),
        Err(MultibodyError::NonFinite {
            what: "tau",
            index: 2
        })
    ));
    // a quaternion of norm 2 in state 8 (the tail of a pack)
    let o = model
        .joints()
        .iter()
        .find_map(|j| j.kind.quaternion_offset().map(|o| j.idx_q + o))
        .expect("the tree has a quaternion");
    let mut q2 = qs.clone();
    for x in &mut q2[8 * nq + o..][..4] {
        *x *= 2.0;
    }
    for e in [
        batch::crba_batch(&model, &q2, &mut mass).unwrap_err(),
        batch::aba_batch(&model, &q2, &vs, &as_, &mut out).unwrap_err(),
    ] {
        assert!(matches!(e, MultibodyError::NotUnitQuaternion { .. }), "{e}");
    }
}

/// A reused `Batch` gives the free functions' results bit for bit on every call (no state left
/// from the previous call: the second call's states differ), and refuses another model.
#[test]
fn a_reused_batch_equals_fresh_calls_and_checks_the_model() {
    let model = common::random_tree(4, 8, true);
    let nv = model.nv();
    let mut b = batch::Batch::new(&model);
    for (seed, n) in [(1, 23), (2, 40)] {
        let (qs, vs, as_) = states(&model, n, seed);
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
    let qs = states(&model, n, 11).0;
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
