//! The batch entry points (states side by side in SIMD lanes, packs across threads) equal single
//! calls, in order, for every lane width, thread count and joint type, on every robot of
//! example-robot-data; they refuse what single calls refuse.

use crate::common;
use rigid::io::urdf::load_urdf;
use rigid::multibody::*;
use rigid::spatial::{Mat3, Vec3};

/// Relative agreement asked of the batch ABA derivatives (single calls spread across the
/// cores, after a batch made for another model) with a fresh single call's.
const DERIVATIVES_TOLERANCE: f64 = 1e-12;

/// Which results [`worst`] compares, in its order.
const NAMES: [&str; 6] = ["rnea", "aba", "crba", "crba_lower", "dtau_dq", "dtau_dv"];

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
/// and single calls, for RNEA, ABA, CRBA, CRBA's packed lower triangle and the RNEA derivatives
/// `∂τ/∂q`, `∂τ/∂v` (those of a model the single call refuses, with a joint whose motion
/// subspace varies, must be refused with its error).
fn worst(model: &Model, width: usize, n: usize, seed: u64) -> [f64; 6] {
    worst_after(model, model, width, n, seed)
}

/// [`worst`] with a batch made for `first` and run on it once before `model`, a model of the
/// same shape (`nq`, `nv`, joints).
fn worst_after(first: &Model, model: &Model, width: usize, n: usize, seed: u64) -> [f64; 6] {
    let (nq, nv) = (model.nq(), model.nv());
    let (qs, vs, as_) = states(model, n, seed);
    let mut b = batch::Batch::with_lanes(first, width);
    assert_eq!(b.lanes(), width);
    if !std::ptr::eq(first, model) {
        let mut mass = vec![0.0; n * nv * nv];
        let mut tau = vec![0.0; n * nv];
        b.crba(first, &qs, &mut mass).unwrap();
        b.rnea(first, &qs, &vs, &as_, &mut tau).unwrap();
    }
    let per = nv * (nv + 1) / 2;
    let (mut tau, mut ddq) = (vec![f64::NAN; n * nv], vec![f64::NAN; n * nv]);
    let (mut mass, mut lower) = (vec![f64::NAN; n * nv * nv], vec![f64::NAN; n * per]);
    b.rnea(model, &qs, &vs, &as_, &mut tau).unwrap();
    // a massless subtree makes M singular: then the batch refuses as the single call does
    let aba_ok = b.aba(model, &qs, &vs, &as_, &mut ddq).is_ok();
    let mut single_aba_ok = true;
    b.crba(model, &qs, &mut mass).unwrap();
    b.crba_lower(model, &qs, &mut lower).unwrap();
    let (mut dq, mut dv) = (vec![f64::NAN; n * nv * nv], vec![f64::NAN; n * nv * nv]);
    let derivatives = b.rnea_derivatives(model, &qs, &vs, &as_, &mut dq, &mut dv);
    let mut data = Data::new(model);
    let mut e = [0.0f64; 6];
    for k in 0..n {
        let (q, v, a) = (
            &qs[k * nq..][..nq],
            &vs[k * nv..][..nv],
            &as_[k * nv..][..nv],
        );
        let t = rnea(model, &mut data, q, v, a).unwrap().clone();
        e[0] = e[0].max(rel(&tau[k * nv..][..nv], t.as_slice()));
        match aba(model, &mut data, q, v, a) {
            Ok(d) if aba_ok => e[1] = e[1].max(rel(&ddq[k * nv..][..nv], d.as_slice())),
            Ok(_) => {}
            Err(_) => single_aba_ok = false,
        }
        let m = crba(model, &mut data, q).unwrap().clone();
        e[2] = e[2].max(rel(&mass[k * nv * nv..][..nv * nv], m.as_slice()));
        let mut packed = vec![0.0; per];
        batch::pack_lower(m.as_slice(), nv, &mut packed).unwrap();
        e[3] = e[3].max(rel(&lower[k * per..][..per], &packed));
        match (rnea_derivatives(model, &mut data, q, v, a), &derivatives) {
            (Ok(d), Ok(())) => {
                let nn = nv * nv;
                e[4] = e[4].max(rel(&dq[k * nn..][..nn], &row_major(d.dtau_dq)));
                e[5] = e[5].max(rel(&dv[k * nn..][..nn], &row_major(d.dtau_dv)));
            }
            (Err(single), Err(batched)) => assert_eq!(single.to_string(), batched.to_string()),
            (single, batched) => panic!(
                "{}: rnea_derivatives: single {:?}, batch {batched:?}",
                model.name(),
                single.err()
            ),
        }
    }
    assert_eq!(
        aba_ok,
        single_aba_ok,
        "{}: aba refused by one side only",
        model.name()
    );
    e
}

/// A column-major matrix's entries row by row.
fn row_major(m: &nalgebra::DMatrix<f64>) -> Vec<f64> {
    m.transpose().as_slice().to_vec()
}

/// `name x` for each of [`worst`]'s results.
fn sci(e: &[f64; 6]) -> String {
    let report: Vec<String> = NAMES
        .iter()
        .zip(e)
        .map(|(n, x)| format!("{n} {x:.1e}"))
        .collect();
    report.join(", ")
}

/// `e` all zero: the batch gave the single calls' bits.
fn assert_same_bits(what: &str, e: [f64; 6]) {
    assert!(
        e == [0.0; 6],
        "{what}: batch vs single calls, relative (bit for bit asked): {}",
        sci(&e)
    );
}

/// A tree of `n` joints drawn from every joint type the RNEA derivatives accept (revolute about
/// random and coordinate axes, with and without a rotated `X_T`, continuous, prismatic, helical,
/// spherical, planar and a free-flyer below the root), with random armature, under a free-flyer
/// root and beside a second tree whose root is the joint `root2`.
fn accepted_joint_forest(seed: u64, n: usize, root2: JointType) -> Model {
    let mut rng = Rng::new(seed);
    let mut b = ModelBuilder::new(&format!("accepted_joints_{seed}"));
    b.set_gravity(Vec3::new(0.3, -0.2, -9.81));
    for (t, root_kind) in [JointType::FreeFlyer, root2].into_iter().enumerate() {
        let root = b
            .add_joint(
                None,
                &format!("root{t}"),
                root_kind,
                common::transform(&mut rng),
                common::inertia(&mut rng),
            )
            .unwrap();
        let mut stack = vec![root];
        for k in 0..n {
            stack.truncate((1 + (rng.next_u64() as usize) % stack.len()).max(1));
            let kind = match (k + t) % 9 {
                0 => JointType::Helical {
                    axis: common::unit(&mut rng),
                    pitch: rng.uniform(-0.3, 0.3),
                },
                1 | 2 => JointType::Revolute {
                    axis: Vec3::ith(k % 3, if k % 2 == 0 { 1.0 } else { -1.0 }),
                },
                3 => JointType::Revolute {
                    axis: common::unit(&mut rng),
                },
                4 => JointType::Prismatic {
                    axis: common::unit(&mut rng),
                },
                5 => JointType::Prismatic {
                    axis: Vec3::ith(k % 3, 1.0),
                },
                6 => JointType::Spherical,
                7 => JointType::Planar,
                _ => JointType::FreeFlyer,
            };
            let mut x_t = common::transform(&mut rng);
            if (k + t) % 9 == 2 || (k + t) % 9 == 5 {
                x_t.rotation = Mat3::identity();
            }
            let id = b
                .add_joint(
                    Some(*stack.last().unwrap()),
                    &format!("j{t}_{k}"),
                    kind,
                    x_t,
                    common::inertia(&mut rng),
                )
                .unwrap();
            if k % 4 == 3 && matches!(kind, JointType::Revolute { .. }) {
                b.set_continuous(id).unwrap();
            }
            let arm: Vec<f64> = (0..kind.nv()).map(|_| rng.uniform(0.0, 0.2)).collect();
            b.set_armature(id, &arm).unwrap();
            stack.push(id);
        }
    }
    b.build().unwrap()
}

/// Every built-in model, random trees (armature, every joint type among them) and the tree of
/// every joint type, in packs of 2, 4 and 8 lanes, with counts that leave a partial last pack:
/// RNEA, ABA, CRBA and the RNEA derivatives bit for bit with the single calls.
#[test]
fn batch_results_equal_single_calls_for_every_width_and_joint_type() {
    let mut models = common::models();
    models.push(common::every_joint_tree(3, 14));
    models.push(common::every_joint_tree(8, 9));
    models.push(accepted_joint_forest(
        21,
        12,
        JointType::Revolute { axis: Vec3::z() },
    ));
    models.push(accepted_joint_forest(22, 10, JointType::Planar));
    models.push(accepted_joint_forest(23, 9, JointType::Spherical));
    let mut largest = [0.0f64; 6];
    for model in &models {
        for width in [2, 4, 8] {
            for n in [1, width + 3, 37] {
                let e = worst(model, width, n, 11 + n as u64);
                let name = format!("{} ({width} lanes, {n} states)", model.name());
                assert_same_bits(&name, e);
                // RNEA, ABA, CRBA and the RNEA derivatives take the single call's steps in its
                // order (ABA's single call is the kernel at one lane)
                assert_eq!(e, [0.0; 6], "{name}: not bit for bit");
                for (l, x) in largest.iter_mut().zip(e) {
                    *l = l.max(x);
                }
            }
        }
    }
    eprintln!("largest relative differences: {}", sci(&largest));
}

/// The bits a batch gives do not depend on its width (what `RIGID_LANES` relies on for the same
/// results on two machines): every built-in model, random trees of every joint type, 37 states
/// (a partial last pack at each width), RNEA, ABA, CRBA and the RNEA derivatives in 2, 4 and 8
/// lanes, compared bit for bit.
#[test]
fn every_width_gives_the_same_bits() {
    let mut models = common::models();
    models.push(common::every_joint_tree(3, 14));
    models.push(common::every_joint_tree(8, 9));
    models.push(accepted_joint_forest(22, 10, JointType::Planar));
    let n = 37;
    for model in &models {
        let nv = model.nv();
        let (qs, vs, as_) = states(model, n, 5);
        let run = |width: usize| {
            let mut b = batch::Batch::with_lanes(model, width);
            let (mut tau, mut ddq, mut mass) =
                (vec![0.0; n * nv], vec![0.0; n * nv], vec![0.0; n * nv * nv]);
            let (mut dq, mut dv) = (vec![0.0; n * nv * nv], vec![0.0; n * nv * nv]);
            b.rnea(model, &qs, &vs, &as_, &mut tau).unwrap();
            let aba = b.aba(model, &qs, &vs, &as_, &mut ddq).is_ok();
            b.crba(model, &qs, &mut mass).unwrap();
            let derivatives = b
                .rnea_derivatives(model, &qs, &vs, &as_, &mut dq, &mut dv)
                .is_ok();
            let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<u64>>();
            (
                aba,
                derivatives,
                [bits(&tau), bits(&ddq), bits(&mass), bits(&dq), bits(&dv)],
            )
        };
        let two = run(2);
        for width in [4, 8] {
            let other = run(width);
            for (k, name) in ["rnea", "aba", "crba", "dtau_dq", "dtau_dv"]
                .iter()
                .enumerate()
            {
                assert!(
                    two.2[k] == other.2[k],
                    "{}: {name} in {width} lanes differs from 2 lanes",
                    model.name()
                );
            }
            assert_eq!((two.0, two.1), (other.0, other.1), "{}", model.name());
        }
    }
}

/// Joints of these types, as a chain or all on the first joint.
fn joints_of(chain: bool, kinds: &[JointType], seed: u64) -> Model {
    let mut rng = Rng::new(seed);
    let mut b = ModelBuilder::new(&format!("{}_{seed}", if chain { "chain" } else { "star" }));
    let mut parent = None;
    for (k, &kind) in kinds.iter().enumerate() {
        let id = b
            .add_joint(
                parent,
                &format!("j{k}"),
                kind,
                common::transform(&mut rng),
                common::inertia(&mut rng),
            )
            .unwrap();
        if chain || k == 0 {
            parent = Some(id);
        }
    }
    b.build().unwrap()
}

/// ABA's derivatives of a batch made for `first` and run on it, then given `model`, against
/// single calls on `model`: the largest relative difference.
fn aba_derivatives_after(first: &Model, model: &Model, n: usize) -> f64 {
    let (nq, nv) = (model.nq(), model.nv());
    let (qs, vs, taus) = states(model, n, 9);
    let mut b = batch::Batch::new(first);
    let [mut dq, mut dv, mut dt] = [0, 1, 2].map(|_| vec![f64::NAN; n * nv * nv]);
    let mut worst = 0.0f64;
    for m in [first, model] {
        b.aba_derivatives(m, &qs, &vs, &taus, &mut dq, &mut dv, &mut dt)
            .unwrap();
    }
    let mut data = Data::new(model);
    for k in 0..n {
        let (q, v, t) = (
            &qs[k * nq..][..nq],
            &vs[k * nv..][..nv],
            &taus[k * nv..][..nv],
        );
        let d = aba_derivatives(model, &mut data, q, v, t).unwrap();
        // row-major blocks against the column-major matrices
        for (out, m) in [(&dq, &d.dqdd_dq), (&dv, &d.dqdd_dv), (&dt, &d.dqdd_dtau)] {
            let single: Vec<f64> = m.transpose().iter().copied().collect();
            worst = worst.max(rel(&out[k * nv * nv..][..nv * nv], &single));
        }
    }
    worst
}

/// A batch made for one model and then given another of the same shape (`nq`, `nv`, joints)
/// computes that model's results, as single calls do: its workspaces keep nothing of the first
/// model (the constant motion subspaces, the tree of the derivatives, the mass matrix's entries
/// outside the subtrees, which the kernel never writes). Pairs that differ in the tree and the
/// axes, in the axes only, in the tree only, and in which joint's subspace varies.
#[test]
fn a_batch_given_another_model_of_the_same_shape_computes_that_model() {
    let r = |x: f64, y: f64, z: f64| JointType::Revolute {
        axis: Vec3::new(x, y, z).normalize(),
    };
    let (z, y, x) = (r(0.0, 0.0, 1.0), r(0.0, 1.0, 0.0), r(1.0, 0.0, 0.0));
    let (a1, a2) = (Vec3::new(1.0, 2.0, 3.0).normalize(), Vec3::x());
    let universal = |axis1, axis2| JointType::Universal { axis1, axis2 };
    let pairs = [
        // another tree and other axes
        (
            joints_of(true, &[z, y, y, x], 1),
            joints_of(false, &[r(1.0, 2.0, 3.0), x, r(-1.0, 0.5, 0.2), z], 2),
        ),
        // the same chain about other axes
        (
            joints_of(true, &[z, y, y, x], 3),
            joints_of(true, &[r(1.0, 2.0, 3.0), x, r(-1.0, 0.5, 0.2), z], 3),
        ),
        // the same axes on another tree
        (
            joints_of(true, &[z, y, y, x], 4),
            joints_of(false, &[z, y, y, x], 4),
        ),
        // a universal joint at the root, then below it: the same constant columns
        (
            joints_of(true, &[universal(a1, a2), r(0.0, 0.6, 0.8)], 5),
            joints_of(
                true,
                &[
                    JointType::Revolute { axis: a1 },
                    universal(a2, Vec3::new(0.0, 0.6, 0.8)),
                ],
                5,
            ),
        ),
    ];
    for (one, other) in &pairs {
        assert_eq!(
            (one.nq(), one.nv(), one.njoints()),
            (other.nq(), other.nv(), other.njoints())
        );
        for width in [2, 4, 8] {
            for (first, then) in [(one, other), (other, one)] {
                let e = worst_after(first, then, width, 2 * width + 1, 3);
                assert_same_bits(
                    &format!("{} after {} ({width} lanes)", then.name(), first.name()),
                    e,
                );
            }
        }
        let universal = |m: &Model| m.joints().iter().any(|j| j.kind.nv() == 2);
        if !universal(one) {
            for (first, then) in [(one, other), (other, one)] {
                let e = aba_derivatives_after(first, then, 5);
                assert!(
                    e <= DERIVATIVES_TOLERANCE,
                    "{} after {}: ABA derivatives {e:e}",
                    then.name(),
                    first.name()
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
        let mut compared = 0;
        let mut largest = [0.0f64; 6];
        for file in &files {
            for floating in [false, true] {
                let Ok(model) = load_urdf(file, floating) else {
                    continue;
                };
                if model.nv() == 0 {
                    continue;
                }
                let e = worst(&model, width, 2 * width + 1, 5);
                eprintln!("{} (floating {floating}): {}", file.display(), sci(&e));
                for (l, x) in largest.iter_mut().zip(e) {
                    *l = l.max(x);
                }
                assert_same_bits(&format!("{} (floating {floating})", file.display()), e);
                // every kernel takes the single calls' steps in the same order (ABA's single call
                // is its kernel at one lane), whatever the joint types: the same numbers
                assert_eq!(
                    [e[0], e[2], e[3], e[4], e[5]],
                    [0.0; 5],
                    "{}: not bit for bit",
                    file.display()
                );
                compared += 1;
            }
        }
        eprintln!(
            "{}: {compared} models in {width} lanes, RNEA, ABA, CRBA and the RNEA derivatives bit \
             for bit; largest relative differences {}",
            dir.display(),
            sci(&largest)
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
        let (mut dq, mut dv) = (vec![0.0; n * nv * nv], vec![0.0; n * nv * nv]);
        pool.install(|| {
            batch::rnea_batch(&model, &qs, &vs, &as_, &mut tau).unwrap();
            batch::aba_batch(&model, &qs, &vs, &as_, &mut ddq).unwrap();
            batch::crba_batch(&model, &qs, &mut mass).unwrap();
            batch::rnea_derivatives_batch(&model, &qs, &vs, &as_, &mut dq, &mut dv).unwrap();
        });
        (tau, ddq, mass, dq, dv)
    };
    assert_eq!(run(1), run(2));
}

/// On one thread (two tasks) a task's 100 states span two of the chunks of 64 that it checks
/// and then computes: every state still equals its single call, and a NaN in a later chunk is
/// refused with the single call's error.
#[test]
fn batch_chunks_join_and_check_each_state() {
    let model = common::every_joint_tree(3, 14);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let (nq, nv, n) = (model.nq(), model.nv(), 200);
    pool.install(|| {
        for width in [2, 4, 8] {
            let e = worst(&model, width, n, 21);
            assert_same_bits(&format!("{width} lanes, {n} states"), e);
        }
        let (qs, mut vs, as_) = states(&model, n, 22);
        vs[170 * nv + 3] = f64::NAN;
        let single = rnea(
            &model,
            &mut Data::new(&model),
            &qs[170 * nq..][..nq],
            &vs[170 * nv..][..nv],
            &as_[170 * nv..][..nv],
        )
        .unwrap_err()
        .to_string();
        let mut tau = vec![0.0; n * nv];
        let batched = batch::rnea_batch(&model, &qs, &vs, &as_, &mut tau).unwrap_err();
        assert_eq!(batched.to_string(), single);
    });
}

/// Rows of `nv = order.len()` numbers in the caller's order: entry `k` is `x[order[k]]`.
fn in_order(x: &[f64], order: &[usize]) -> Vec<f64> {
    x.chunks(order.len())
        .flat_map(|r| order.iter().map(|&o| r[o]))
        .collect()
}

/// Row-major `nv x nv` matrices in the caller's order: entry `(r, c)` is `(order[r], order[c])`.
fn square_in_order(m: &[f64], order: &[usize]) -> Vec<f64> {
    let nv = order.len();
    let mut out = Vec::with_capacity(m.len());
    for m in m.chunks(nv * nv) {
        for &r in order {
            out.extend(order.iter().map(|&c| m[r * nv + c]));
        }
    }
    out
}

/// A batch with a velocity order takes and gives every velocity-space number in that order:
/// its results are those of rigid's order with inputs and outputs permuted, bit for bit, for
/// every entry point (for an order that moves every dof, one that moves a few among dofs left
/// in place, and the identity), at every width, across chunks (one thread:
/// a task's 100+ states span two chunks of 64) and packs; a NaN is named by the caller's
/// index; an order that is not a permutation of `0..nv` is refused.
#[test]
fn a_velocity_order_permutes_inputs_and_results() {
    rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(velocity_order_cases);
}

fn velocity_order_cases() {
    let model = common::every_joint_tree(3, 14);
    let (nv, n) = (model.nv(), 230);
    let mut reversed: Vec<usize> = (0..nv).rev().collect();
    reversed.swap(0, 3);
    let (qs, vs, as_) = states(&model, n, 8);
    // every entry moved, and (as Pinocchio's layout) a few moved among entries left in place
    for (order, width) in [reversed, blocks_swapped(nv), (0..nv).collect()]
        .iter()
        .flat_map(|o| [2, 4, 8].map(|w| (o, w)))
    {
        let permute = |x: &[f64]| in_order(x, order);
        let square = |m: &[f64]| square_in_order(m, order);
        let (vs_c, as_c) = (permute(&vs), permute(&as_));
        let mut plain = batch::Batch::with_lanes(&model, width);
        let mut ordered = batch::Batch::with_lanes(&model, width)
            .with_velocity_order(&model, order)
            .unwrap();
        // NaN first: every entry must be written
        let (mut x, mut y) = (vec![f64::NAN; n * nv], vec![f64::NAN; n * nv]);
        plain.rnea(&model, &qs, &vs, &as_, &mut x).unwrap();
        ordered.rnea(&model, &qs, &vs_c, &as_c, &mut y).unwrap();
        assert_eq!(y, permute(&x), "rnea, {width} lanes");
        let tau = x.clone();
        let tau_c = permute(&tau);
        plain.aba(&model, &qs, &vs, &tau, &mut x).unwrap();
        ordered.aba(&model, &qs, &vs_c, &tau_c, &mut y).unwrap();
        assert_eq!(y, permute(&x), "aba, {width} lanes");
        let (mut m, mut mc) = (vec![f64::NAN; n * nv * nv], vec![f64::NAN; n * nv * nv]);
        plain.crba(&model, &qs, &mut m).unwrap();
        ordered.crba(&model, &qs, &mut mc).unwrap();
        assert_eq!(mc, square(&m), "crba, {width} lanes");
        let per = nv * (nv + 1) / 2;
        let mut packed = vec![f64::NAN; n * per];
        ordered.crba_lower(&model, &qs, &mut packed).unwrap();
        let mut want = vec![0.0; per];
        for (p, m) in packed.chunks(per).zip(mc.chunks(nv * nv)) {
            // M is symmetric: its row-major rows are its columns
            batch::pack_lower(m, nv, &mut want).unwrap();
            assert_eq!(p, &want[..], "crba_lower, {width} lanes");
        }
    }
    // the RNEA and ABA derivatives, on a tree whose joints they take
    let model = accepted_joint_forest(4, 7, JointType::Planar);
    let (nv, n) = (model.nv(), 210);
    let (qs, vs, as_) = states(&model, n, 9);
    let rotated: Vec<usize> = (0..nv).map(|k| (k + 5) % nv).collect();
    for order in [blocks_swapped(nv), rotated, (0..nv).collect()] {
        for width in [2, 4, 8] {
            velocity_order_derivatives(&model, &order, width, &qs, &vs, &as_);
        }
    }
}

/// `0..nv` with its first two blocks of three swapped and its last two entries swapped (as
/// Pinocchio's layout of a free-flyer moves 6 entries and leaves the rest in place).
fn blocks_swapped(nv: usize) -> Vec<usize> {
    assert!(nv >= 9, "{nv} velocities");
    let mut order: Vec<usize> = (0..nv)
        .map(|k| match k {
            0..3 => k + 3,
            3..6 => k - 3,
            _ => k,
        })
        .collect();
    order.swap(nv - 1, nv - 2);
    order
}

/// The RNEA and ABA derivatives through `order` against the plain ones, in `width` lanes, and a
/// NaN named by the caller's index.
fn velocity_order_derivatives(
    model: &Model,
    order: &[usize],
    width: usize,
    qs: &[f64],
    vs: &[f64],
    as_: &[f64],
) {
    let (nv, n) = (model.nv(), vs.len() / model.nv());
    let permute = |x: &[f64]| in_order(x, order);
    let square = |m: &[f64]| square_in_order(m, order);
    let mut plain = batch::Batch::with_lanes(model, width);
    let mut ordered = batch::Batch::with_lanes(model, width)
        .with_velocity_order(model, order)
        .unwrap();
    let outs = || [(); 3].map(|_| vec![f64::NAN; n * nv * nv]); // every entry written
    let ([mut a, mut b, _], [mut ac, mut bc, _]) = (outs(), outs());
    plain
        .rnea_derivatives(model, qs, vs, as_, &mut a, &mut b)
        .unwrap();
    ordered
        .rnea_derivatives(model, qs, &permute(vs), &permute(as_), &mut ac, &mut bc)
        .unwrap();
    assert_eq!((ac, bc), (square(&a), square(&b)), "rnea_derivatives");
    let ([mut a, mut b, mut c], [mut ac, mut bc, mut cc]) = (outs(), outs());
    plain
        .aba_derivatives(model, qs, vs, as_, &mut a, &mut b, &mut c)
        .unwrap();
    let (vc, tc) = (permute(vs), permute(as_));
    ordered
        .aba_derivatives(model, qs, &vc, &tc, &mut ac, &mut bc, &mut cc)
        .unwrap();
    assert_eq!(
        (&ac, &bc, &cc),
        (&square(&a), &square(&b), &square(&c)),
        "aba_derivatives"
    );
    // a NaN at the caller's index 2 of state 150's v is named by that index
    let mut bad = vc.clone();
    bad[150 * nv + 2] = f64::NAN;
    let nan = MultibodyError::NonFinite {
        what: "v",
        index: 2,
    };
    let e = ordered.rnea(model, qs, &bad, &tc, &mut vec![0.0; n * nv]);
    assert_eq!(e.unwrap_err(), nan);
    let e = ordered.aba_derivatives(model, qs, &bad, &tc, &mut ac, &mut bc, &mut cc);
    assert_eq!(e.unwrap_err(), nan);
    // not permutations
    for bad in [vec![0; nv - 1], vec![0; nv], (1..=nv).collect::<Vec<_>>()] {
        let e = batch::Batch::new(model).with_velocity_order(model, &bad);
        assert!(
            matches!(
                e,
                Err(MultibodyError::Dimension(_) | MultibodyError::OutOfRange { .. })
            ),
            "{bad:?}"
        );
    }
    let e = batch::Batch::new(model)
        .with_velocity_order(model, &vec![0; nv])
        .unwrap_err();
    assert!(
        matches!(e, MultibodyError::OutOfRange { index: 1, .. }),
        "{e}"
    );
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
    // the RNEA derivatives refuse the tree's universal joints (their motion subspace varies)
    // with the single call's error, and then bad states as the single call does
    let mut dv = vec![0.0; n * nv * nv];
    let single = rnea_derivatives(&model, &mut data, &qs[..nq], &vs[..nv], &as_[..nv])
        .unwrap_err()
        .to_string();
    let batched =
        batch::rnea_derivatives_batch(&model, &qs, &vs, &as_, &mut mass, &mut dv).unwrap_err();
    assert!(matches!(batched, MultibodyError::Unsupported { .. }));
    assert_eq!(batched.to_string(), single);
    let model = accepted_joint_forest(4, 7, JointType::Planar);
    let (nq, nv) = (model.nq(), model.nv());
    let (qs, vs, as_) = states(&model, n, 4);
    let (mut dq, mut dv) = (vec![0.0; n * nv * nv], vec![0.0; n * nv * nv]);
    let mut bad = as_.clone();
    bad[6 * nv + 2] = f64::NAN;
    let mut data = Data::new(&model);
    let single = rnea_derivatives(
        &model,
        &mut data,
        &qs[..nq],
        &vs[..nv],
        &bad[6 * nv..][..nv],
    )
    .unwrap_err()
    .to_string();
    let batched = batch::rnea_derivatives_batch(&model, &qs, &vs, &bad, &mut dq, &mut dv);
    assert_eq!(batched.unwrap_err().to_string(), single);
    let o = model.joints()[0].kind.quaternion_offset().unwrap(); // the free-flyer root's
    let mut q2 = qs.clone();
    for x in &mut q2[8 * nq + o..][..4] {
        *x *= 2.0;
    }
    assert!(matches!(
        batch::rnea_derivatives_batch(&model, &q2, &vs, &as_, &mut dq, &mut dv),
        Err(MultibodyError::NotUnitQuaternion { .. })
    ));
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
        let (mut v1, mut v2) = (vec![0.0; n * nv * nv], vec![0.0; n * nv * nv]);
        b.rnea_derivatives(&model, &qs, &vs, &as_, &mut m1, &mut v1)
            .unwrap();
        batch::rnea_derivatives_batch(&model, &qs, &vs, &as_, &mut m2, &mut v2).unwrap();
        assert_eq!((m1, v1), (m2, v2));
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

/// A rough timing of the lane RNEA derivatives against a loop of single calls, one thread
/// (`cargo test -p rigid --test it rnea_derivatives_batch_timing -- --ignored --nocapture`;
/// the test profile is `opt-level = 1`, so only the ratio means anything).
#[test]
#[ignore]
fn rnea_derivatives_batch_timing() {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let dir = common::example_robot_data();
    for (file, floating) in [
        ("ur_description/urdf/ur5_robot.urdf", false),
        ("talos_data/robots/talos_reduced.urdf", true),
    ] {
        let model = load_urdf(dir.join(file), floating).unwrap();
        let (nq, nv, n) = (model.nq(), model.nv(), 256);
        let (qs, vs, as_) = states(&model, n, 9);
        let (mut dq, mut dv) = (vec![0.0; n * nv * nv], vec![0.0; n * nv * nv]);
        let mut data = Data::new(&model);
        let (single, lanes) = pool.install(|| {
            let mut b = batch::Batch::new(&model);
            let time = |f: &mut dyn FnMut()| {
                f();
                let t = std::time::Instant::now();
                for _ in 0..5 {
                    f();
                }
                t.elapsed().as_secs_f64() / (5 * n) as f64
            };
            let single = time(&mut || {
                for k in 0..n {
                    let (q, v, a) = (
                        &qs[k * nq..][..nq],
                        &vs[k * nv..][..nv],
                        &as_[k * nv..][..nv],
                    );
                    std::hint::black_box(rnea_derivatives(&model, &mut data, q, v, a).unwrap());
                }
            });
            let lanes = time(&mut || {
                b.rnea_derivatives(&model, &qs, &vs, &as_, &mut dq, &mut dv)
                    .unwrap();
            });
            (single, lanes)
        });
        eprintln!(
            "{file}: single call {:.2} µs/state, {} lanes {:.2} µs/state ({:.2}x)",
            single * 1e6,
            batch::Batch::new(&model).lanes(),
            lanes * 1e6,
            single / lanes
        );
    }
}
