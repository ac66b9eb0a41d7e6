//! Identification on the built-in robots and random trees: the regressor against RNEA, the base
//! parameters against fresh motions, least squares on exact and noisy torques, the physically
//! consistent estimate, the CSV reader and its errors, the differentiator, the excitation.

use crate::common;
use nalgebra::{DMatrix, DVector};
use rigid::identification::excitation::{optimize, ExcitationOptions};
use rigid::identification::*;
use rigid::mass::{Consistency, SpatialInertia};
use rigid::multibody::*;

/// `‖Y π + armature ∘ a − rnea‖ ≤ 1e-12 ‖rnea‖` at random states of every built-in model and
/// random trees (every joint type, free-flyer roots, welded bodies, armature).
#[test]
fn regressor_times_parameters_is_rnea() {
    let mut worst = 0.0f64;
    for model in common::models() {
        let mut rng = Rng::new(7);
        let pi = model_parameters(&model);
        let mut reg = Regressor::new(&model);
        let mut data = Data::new(&model);
        for _ in 0..20 {
            let (q, v, a) = common::state(&model, &mut rng);
            let y = reg.compute(&model, &q, &v, &a).unwrap().clone();
            let tau = rnea(&model, &mut data, &q, &v, &a).unwrap().clone();
            let arm = DVector::from_iterator(
                model.nv(),
                (0..model.nv()).map(|k| model.armature()[k] * a[k]),
            );
            let e = (&y * &pi + arm - &tau).norm() / tau.norm().max(1e-300);
            worst = worst.max(e);
            assert!(e < 1e-12, "{}: relative error {e:e}", model.name());
        }
    }
    eprintln!("regressor vs rnea: worst relative error {worst:e}");
}

/// The stacked form is the single regressors one under the other, and a bad sample is refused
/// with its error.
#[test]
fn stacked_regressor_is_the_single_ones() {
    let model = builtin("puma560").unwrap();
    let mut rng = Rng::new(3);
    let (mut q, mut v, mut a) = (vec![], vec![], vec![]);
    for _ in 0..4 {
        let (qs, vs, as_) = common::state(&model, &mut rng);
        q.extend(qs);
        v.extend(vs);
        a.extend(as_);
    }
    let mut reg = Regressor::new(&model);
    let mut w = DMatrix::zeros(24, 60);
    reg.stack(&model, &q, &v, &a, &mut w).unwrap();
    for s in 0..4 {
        let y = reg
            .compute(
                &model,
                &q[6 * s..6 * s + 6],
                &v[6 * s..6 * s + 6],
                &a[6 * s..6 * s + 6],
            )
            .unwrap();
        assert_eq!(w.rows(6 * s, 6).clone_owned(), *y);
    }
    q[3] = f64::NAN;
    assert!(matches!(
        reg.stack(&model, &q, &v, &a, &mut w),
        Err(MultibodyError::NonFinite { what: "q", .. })
    ));
    let mut short = DMatrix::zeros(23, 60);
    assert!(reg.stack(&model, &q, &v, &a, &mut short).is_err());
}

/// `π ↔ (m, c, I_c)` and the pseudo-inertia: the round trip is exact and the parameters of a
/// body moved to another frame are those of the moved body.
#[test]
fn parameters_round_trip() {
    let mut rng = Rng::new(11);
    for _ in 0..50 {
        let g = common::inertia(&mut rng);
        let p = g.to_parameters();
        let back = SpatialInertia::from_parameters(&p);
        assert!((back.matrix() - g.matrix()).norm() < 1e-15 * g.matrix().norm());
        let j = back.pseudo_inertia();
        assert_eq!(j[(3, 3)], p[0]);
        assert!((SpatialInertia::from_pseudo_inertia(&j).matrix() - g.matrix()).norm() < 1e-14);
        assert!(Consistency::of(&back).is_consistent());
    }
}

/// For fresh random motions (another seed than the one the base parameters came from),
/// `W π = W_B β(π)` to round-off, for random parameters `π` (not only the model's), with and
/// without joint terms.
#[test]
fn base_parameters_reproduce_the_torques_of_any_motion() {
    for model in common::models() {
        for terms in [
            JointTerms::default(),
            JointTerms {
                friction: true,
                rotor_inertia: true,
            },
        ] {
            let base = BaseParameters::of_model(&model, terms, 1).unwrap();
            let layout = ParameterLayout::new(&model, terms);
            let mut rng = Rng::new(99);
            let pi = DVector::from_fn(layout.len(), |_, _| rng.uniform(-1.0, 1.0));
            let beta = base.project(&pi);
            let mut reg = Regressor::new(&model);
            let nv = model.nv();
            let mut w = DMatrix::zeros(10 * nv, layout.len());
            for s in 0..10 {
                let (q, v, a) = common::state(&model, &mut rng);
                let y = reg.compute(&model, &q, &v, &a).unwrap();
                layout.fill_rows(y, &v, &a, w.rows_mut(s * nv, nv));
            }
            let full = &w * &pi;
            let e = (&full - base.columns(&w) * &beta).norm() / full.norm();
            assert!(e < 1e-10, "{} {terms:?}: {e:e}", model.name());
            // fewer base parameters than parameters, and the lift keeps them
            assert!(base.len() < layout.len());
            let lifted = base.lift(&beta, &layout.model_values(&model));
            assert!((base.project(&lifted) - &beta).norm() < 1e-10 * beta.norm());
        }
    }
}

/// Closed forms: a pendulum about a horizontal axis has three base parameters (the inertia
/// about the axis and the two components of the first moment across it); a planar double
/// pendulum six (`Izz`, `mx`, `my` of each link, the second's mass grouped into the first's).
#[test]
fn base_parameter_counts_of_closed_forms() {
    let count = |n| {
        BaseParameters::of_model(&builtin(n).unwrap(), JointTerms::default(), 1)
            .unwrap()
            .len()
    };
    assert_eq!(count("pendulum"), 3);
    assert_eq!(count("double_pendulum"), 6);
    let base =
        BaseParameters::of_model(&builtin("puma560").unwrap(), JointTerms::default(), 1).unwrap();
    eprintln!("PUMA 560: {} base parameters\n{base}", base.len());
    // the second link's mass is grouped into the first: "m2" never stands alone
    assert!(base.expression(1).starts_with("mx2 + 0.4318 m3"));
}

/// Samples of the model itself (exact torques, plus optional joint terms), as a CSV would hold.
fn synthetic(model: &Model, n: usize, seed: u64, terms: (&[f64], &[f64], &[f64])) -> Samples {
    let mut rng = Rng::new(seed);
    let mut data = Data::new(model);
    let mut s = Samples::default();
    let (fv, fc, ia) = terms;
    for k in 0..n {
        let (q, v, a) = common::state(model, &mut rng);
        let tau = rnea(model, &mut data, &q, &v, &a).unwrap();
        s.t.push(k as f64 * 0.01);
        for i in 0..model.nv() {
            let sign = if v[i] > 0.0 { 1.0 } else { -1.0 };
            s.tau
                .push(tau[i] + fv[i] * v[i] + fc[i] * sign + ia[i] * a[i]);
        }
        s.q.extend(q);
        s.v.extend(v);
        s.a.extend(a);
    }
    s
}

/// Exact torques with friction and rotor inertia: least squares (ordinary and weighted) gives
/// back the base parameters, the joint terms among them, to 1e-9.
#[test]
fn least_squares_recovers_exact_parameters_and_joint_terms() {
    let model = builtin("puma560").unwrap();
    let fv = [0.5, 0.4, 0.3, 0.05, 0.04, 0.03];
    let fc = [0.9, 0.8, 0.7, 0.1, 0.09, 0.08];
    let ia = [0.3, 0.2, 0.1, 0.02, 0.02, 0.01];
    let s = synthetic(&model, 200, 4, (&fv, &fc, &ia));
    let terms = JointTerms {
        friction: true,
        rotor_inertia: true,
    };
    let id = Identification::new(&model, &s, terms).unwrap();
    let mut truth = id.prior.clone();
    let (f0, r0) = (
        id.layout.friction_start().unwrap(),
        id.layout.rotor_start().unwrap(),
    );
    for k in 0..6 {
        truth[f0 + 2 * k] = fv[k];
        truth[f0 + 2 * k + 1] = fc[k];
        truth[r0 + k] = ia[k];
    }
    let beta = id.base.project(&truth);
    for w in [Weighting::None, Weighting::PerJoint] {
        let est = id.least_squares(w).unwrap();
        let e = (&est.base - &beta).amax() / beta.amax();
        assert!(e < 1e-9, "{w:?}: {e:e}");
        assert!(est.relative_residual < 1e-10 && est.condition_number > 1.0);
        assert!(est.base_std.iter().all(|s| s.is_finite() && *s < 1e-6));
        // the viscous friction of joint 4 stands alone as a base parameter
        let i = id
            .base
            .independent
            .iter()
            .position(|&j| j == f0 + 6)
            .unwrap();
        assert!((est.base[i] - fv[3]).abs() < 1e-9);
    }
}

/// Too few samples, and a motion in which a joint never moves: the errors say which and what to
/// do.
#[test]
fn bad_motions_are_refused_with_the_reason() {
    let model = builtin("puma560").unwrap();
    let zeros = [0.0; 6];
    let s = synthetic(&model, 5, 1, (&zeros, &zeros, &zeros));
    let Err(e) = Identification::new(&model, &s, JointTerms::default()) else {
        panic!("5 samples accepted");
    };
    assert!(
        matches!(e, IdentificationError::TooFewSamples { .. }),
        "{e}"
    );
    assert!(e.to_string().contains("record at least 7 samples"), "{e}");
    let mut s = synthetic(&model, 100, 1, (&zeros, &zeros, &zeros));
    // joint 1 frozen at 0.3 rad: the inertia about its axis acts on nothing
    let mut data = Data::new(&model);
    for k in 0..s.len() {
        s.q[6 * k] = 0.3;
        s.v[6 * k] = 0.0;
        s.a[6 * k] = 0.0;
        let tau = rnea(
            &model,
            &mut data,
            &s.q[6 * k..6 * k + 6],
            &s.v[6 * k..6 * k + 6],
            &s.a[6 * k..6 * k + 6],
        )
        .unwrap();
        s.tau[6 * k..6 * k + 6].copy_from_slice(tau.as_slice());
    }
    let Err(e) = Identification::new(&model, &s, JointTerms::default()) else {
        panic!("a frozen joint was not noticed");
    };
    let text = e.to_string();
    assert!(
        matches!(e, IdentificationError::RankDeficient { .. }),
        "{e}"
    );
    assert!(
        text.contains("never move: joint1") && text.contains("rigid excite"),
        "{text}"
    );
}

/// Noisy torques on a model whose inertias are made non-physical in the unidentifiable
/// directions: the physically consistent estimate has every body consistent, fits the samples
/// nearly as well as least squares, and its model runs in ABA.
#[cfg(feature = "sdp")]
#[test]
fn physically_consistent_estimate_is_valid_for_every_body() {
    let model = builtin("puma560").unwrap();
    let zeros = [0.0; 6];
    let mut s = synthetic(&model, 300, 8, (&zeros, &zeros, &zeros));
    let mut rng = Rng::new(2);
    let rms = (s.tau.iter().map(|x| x * x).sum::<f64>() / s.tau.len() as f64).sqrt();
    for x in &mut s.tau {
        *x += 0.01 * rms * rng.normal();
    }
    let id = Identification::new(&model, &s, JointTerms::default()).unwrap();
    let ls = id.least_squares(Weighting::None).unwrap();
    let pc = id
        .physically_consistent(&PhysicalOptions::default())
        .unwrap();
    for (i, p) in pc.parameters.as_slice().chunks(10).enumerate() {
        let g = SpatialInertia::from_parameters(p.try_into().unwrap());
        let c = Consistency::of(&g);
        assert_eq!(
            c.verdict(),
            rigid::mass::Verdict::Consistent,
            "body {i}: {c:?}"
        );
    }
    assert!(pc.residual_rms <= 1.05 * ls.residual_rms, "{pc:?} {ls:?}");
    let fitted = model_with_parameters(&model, pc.parameters.as_slice()).unwrap();
    let mut data = Data::new(&fitted);
    let x = aba(&fitted, &mut data, &[0.1; 6], &[0.2; 6], &[1.0; 6]).unwrap();
    assert!(x.iter().all(|v| v.is_finite()));
    // mass bounds hold, and infeasible ones are an error
    let bounds: Vec<(f64, f64)> = model
        .inertias()
        .iter()
        .map(|g| (0.9 * g.mass(), 1.1 * g.mass() + 0.1))
        .collect();
    let opts = PhysicalOptions {
        mass_bounds: Some(bounds.clone()),
        ..PhysicalOptions::default()
    };
    let bounded = id.physically_consistent(&opts).unwrap();
    for (i, (lo, hi)) in bounds.iter().enumerate() {
        let m = bounded.parameters[10 * i];
        assert!(
            m >= lo - 1e-6 && m <= hi + 1e-6,
            "body {i}: {m} not in [{lo}, {hi}]"
        );
    }
    let impossible = PhysicalOptions {
        mass_bounds: Some(vec![(-2.0, -1.0); 6]),
        ..PhysicalOptions::default()
    };
    assert!(matches!(
        id.physically_consistent(&impossible),
        Err(IdentificationError::Solver(_))
    ));
}

/// Built without the feature `sdp`, the physically consistent estimate still checks its options,
/// then says how to build it in.
#[cfg(not(feature = "sdp"))]
#[test]
fn without_sdp_the_physical_estimate_says_how_to_build_it() {
    let model = builtin("puma560").unwrap();
    let zeros = [0.0; 6];
    let s = synthetic(&model, 100, 8, (&zeros, &zeros, &zeros));
    let id = Identification::new(&model, &s, JointTerms::default()).unwrap();
    let bad = PhysicalOptions {
        regularization: f64::NAN,
        ..PhysicalOptions::default()
    };
    assert!(matches!(
        id.physically_consistent(&bad),
        Err(IdentificationError::Invalid(_))
    ));
    match id.physically_consistent(&PhysicalOptions::default()) {
        Err(IdentificationError::NotBuilt(m)) => {
            assert!(
                m.contains("--features sdp") && m.contains("libopenblas-dev"),
                "{m}"
            )
        }
        other => panic!("{other:?}"),
    }
}

/// The CSV reader: the three layouts, and every malformed input named by line and column.
#[test]
fn csv_layouts_and_errors() {
    let model = builtin("double_pendulum").unwrap();
    let full = Samples::from_csv(
        &model,
        "0,0.1,0.2,1,2,3,4,5,6\n0.1,0.1,0.2,1,2,3,4,5,6\n",
        None,
    )
    .unwrap();
    assert_eq!((full.len(), full.a[1], full.tau[1]), (2, 4.0, 6.0));
    // round trip through to_csv
    let again = Samples::from_csv(&model, &full.to_csv(&model), None).unwrap();
    assert_eq!(again, full);
    let cases = [
        ("0,1,2,3\n", "line 1", "columns"),
        (
            "0,1,2,3,4,5,6,7,8\n0.1,1,2\n",
            "line 2",
            "every row needs the same columns",
        ),
        (
            "0,1,2,3,4,5,6,7,8\n0.1,1,x,3,4,5,6,7,8\n",
            "line 2, column 3 (q_joint2)",
            "\"x\"",
        ),
        (
            "0,1,2,3,4,5,6,7,8\n0.1,1,2,inf,4,5,6,7,8\n",
            "column 4 (v_joint1)",
            "finite",
        ),
        (
            "0,1,2,3,4,5,6,7,8\n0,1,2,3,4,5,6,7,8\n",
            "line 2, column 1 (t)",
            "increase",
        ),
        (
            "t,q_joint2,q_joint1,tau_joint1,tau_joint2\n",
            "column 2",
            "joint order",
        ),
        ("", "line 1", "no samples"),
    ];
    for (text, place, what) in cases {
        let e = Samples::from_csv(&model, text, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains(place) && e.contains(what), "{text:?}: {e}");
    }
    // positions only, uneven steps
    let uneven: String = (0..30)
        .map(|k| {
            format!(
                "{},{},0,0,0\n",
                k as f64 * 0.01 + if k == 17 { 0.005 } else { 0.0 },
                k
            )
        })
        .collect();
    let e = Samples::from_csv(&model, &uneven, None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("line 18") && e.contains("uniform"), "{e}");
    // multi-dof joints cannot be differentiated from q alone
    let free = common::random_tree(1, 2, false);
    let cols = 1 + free.nq() + free.nv();
    let row = vec!["0"; cols].join(",");
    let e = Samples::from_csv(&free, &format!("{row}\n"), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("give the velocities"), "{e}");
}

/// The Savitzky–Golay differentiator on a sampled smooth motion: `(q, τ)` samples give `v`, `a`
/// within 1e-6 of the exact values (degree 4, 0.05 s window, 1 kHz), the ends dropped.
#[test]
fn savitzky_golay_differentiates_sampled_motion() {
    let model = builtin("double_pendulum").unwrap();
    let mut text = String::new();
    let f = |t: f64| (0.8 * t).sin() + 0.3 * (2.1 * t).cos();
    let df = |t: f64| 0.8 * (0.8 * t).cos() - 0.63 * (2.1 * t).sin();
    let ddf = |t: f64| -0.64 * (0.8 * t).sin() - 1.323 * (2.1 * t).cos();
    for k in 0..1000 {
        let t = k as f64 * 1e-3;
        text += &format!("{t},{},{},0,0\n", f(t), -f(t));
    }
    let s = Samples::from_csv(&model, &text, None).unwrap();
    assert_eq!(s.len(), 1000 - 2 * 25);
    for k in 0..s.len() {
        let t = s.t[k];
        assert!((s.v[2 * k] - df(t)).abs() < 1e-6 && (s.v[2 * k + 1] + df(t)).abs() < 1e-6);
        assert!(
            (s.a[2 * k] - ddf(t)).abs() < 1e-4,
            "{} {}",
            s.a[2 * k],
            ddf(t)
        );
    }
}

/// The exciting trajectory starts and ends at rest, stays within the position and velocity
/// limits, and the optimiser lowers the condition number below that of its random start.
#[test]
fn excitation_is_within_limits_and_well_conditioned() {
    let model = builtin("puma560").unwrap();
    let start = ExcitationOptions {
        iterations: 1,
        duration: 6.0,
        ..Default::default()
    };
    let (_, c0) = optimize(&model, &start).unwrap();
    let (traj, c) = optimize(
        &model,
        &ExcitationOptions {
            iterations: 60,
            ..start.clone()
        },
    )
    .unwrap();
    assert!(c < c0, "{c} !< {c0}");
    let (mut q, mut v, mut a) = ([0.0; 6], [0.0; 6], [0.0; 6]);
    for i in 0..=6000 {
        let t = i as f64 * 1e-3;
        traj.sample(t, &mut q, &mut v, &mut a);
        for k in 0..6 {
            assert!(q[k] >= model.lower_limits()[k] && q[k] <= model.upper_limits()[k]);
            assert!(v[k].abs() <= model.velocity_limits()[k]);
        }
        if i == 0 || i == 6000 {
            assert!(v.iter().chain(&a).all(|x| x.abs() < 1e-9), "{v:?} {a:?}");
        }
    }
    // the samples carry the model's torques: identifying from them gives the model back
    let s = traj.samples(&model, 0.02).unwrap();
    let id = Identification::new(&model, &s, JointTerms::default()).unwrap();
    let est = id.least_squares(Weighting::None).unwrap();
    let truth = id.base.project(&id.prior);
    assert!((est.base - &truth).amax() < 1e-8 * truth.amax());
    // a model with a free-flyer cannot be excited by joint trajectories
    let e = optimize(&common::random_tree(1, 3, false), &start).unwrap_err();
    assert!(e.to_string().contains("free-flyer") || e.to_string().contains("one degree"));
}
