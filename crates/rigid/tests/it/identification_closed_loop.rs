//! The tool on itself, closed loop: the PUMA 560 (built-in) and the Panda (example-robot-data,
//! fingers kept as two prismatic joints) follow an optimised exciting trajectory under a
//! computed-torque controller, simulated by ABA (RK4, 1 ms); the applied torques and the states
//! are sampled at 100 Hz (accelerations from ABA at each sample). They are identified against a
//! "CAD" model, the same robot with every inertial parameter off by up to ±20 % (the prior of
//! the regularisation), then:
//!
//! - noise-free, least squares recovers the base parameters to 1e-8 relative;
//! - with Gaussian noise of 1 % of each joint's torque RMS, the physically consistent estimate
//!   is valid for every body, its torque prediction on a held-out trajectory (another exciting
//!   motion, exact torques) is no worse than least squares' (to within 1 %), and where least squares gives
//!   non-physical bodies the consistent model still runs in ABA without NaN.

use rigid::identification::excitation::{optimize, ExcitationOptions, FourierTrajectory};
use rigid::identification::*;
use rigid::io::urdf::load_urdf;
#[cfg(feature = "sdp")]
use rigid::mass::{Consistency, SpatialInertia, Verdict};
use rigid::multibody::*;
use rigid::simulation::{Integrator, JointLimits, SimulationOptions, Simulator};

use crate::common;

/// Samples at 100 Hz of `model` tracking `traj` (computed torque, `K_p = 400`, `K_d = 40`).
fn closed_loop(model: &Model, traj: &FourierTrajectory) -> Samples {
    let nv = model.nv();
    let (mut qd, mut vd, mut ad) = (vec![0.0; nv], vec![0.0; nv], vec![0.0; nv]);
    traj.sample(0.0, &mut qd, &mut vd, &mut ad);
    let q0 = qd.clone();
    let mut data = Data::new(model);
    let mut cmd = vec![0.0; nv];
    let control = move |t: f64, q: &[f64], v: &[f64], tau: &mut [f64]| {
        traj.sample(t, &mut qd, &mut vd, &mut ad);
        for k in 0..nv {
            cmd[k] = ad[k] + 400.0 * (qd[k] - q[k]) + 40.0 * (vd[k] - v[k]);
        }
        let r = rnea(model, &mut data, q, v, &cmd).expect("a valid state");
        tau.copy_from_slice(r.as_slice());
    };
    let opts = SimulationOptions {
        dt: 1e-3,
        integrator: Integrator::Rk4,
        limits: JointLimits::Ignored,
        joint_dynamics: false,
        ..SimulationOptions::default()
    };
    let mut sim = Simulator::new(model, &q0, &vec![0.0; nv], opts, control).unwrap();
    let mut aba_data = Data::new(model);
    let mut s = Samples::default();
    let steps = (traj.period() / 1e-3).round() as u64;
    for k in 0..=steps {
        if k % 10 == 0 {
            let (q, v, t) = (sim.q().to_vec(), sim.v().to_vec(), sim.time());
            let tau = sim.torques().unwrap().1.to_vec();
            let a = aba(model, &mut aba_data, &q, &v, &tau).unwrap();
            s.t.push(t);
            s.a.extend(a.iter());
            s.q.extend(q);
            s.v.extend(v);
            s.tau.extend(tau);
        }
        if k < steps {
            sim.step().unwrap();
        }
    }
    s
}

#[cfg(feature = "sdp")]
fn body_verdicts(pi: &nalgebra::DVector<f64>, n: usize) -> Vec<Verdict> {
    (0..n)
        .map(|i| {
            let p: &[f64; 10] = pi.as_slice()[10 * i..10 * i + 10].try_into().unwrap();
            Consistency::of(&SpatialInertia::from_parameters(p)).verdict()
        })
        .collect()
}

fn check(model: &Model) {
    let name = model.name().to_string();
    let opts = ExcitationOptions {
        duration: 10.0,
        iterations: 40,
        ..ExcitationOptions::default()
    };
    let (traj, cond) = optimize(model, &opts).unwrap();
    let s = closed_loop(model, &traj);
    let nv = model.nv();
    // tracking: the robot did follow the reference
    let (mut qd, mut vd, mut ad) = (vec![0.0; nv], vec![0.0; nv], vec![0.0; nv]);
    let mut track = 0.0f64;
    for k in 0..s.len() {
        traj.sample(s.t[k], &mut qd, &mut vd, &mut ad);
        for (q, want) in s.q[k * nv..(k + 1) * nv].iter().zip(&qd) {
            track = track.max((q - want).abs());
        }
    }
    assert!(track < 1e-3, "{name}: tracking error {track}");

    // identified against a "CAD" model: the same kinematics, every inertial parameter off by
    // up to ±20 % (the prior the physically consistent estimate is regularised towards)
    let mut rng = Rng::new(17);
    let true_pi = model_parameters(model);
    let cad_pi: Vec<f64> = true_pi
        .iter()
        .map(|p| p * (1.0 + rng.uniform(-0.2, 0.2)))
        .collect();
    let cad = model_with_parameters(model, &cad_pi).unwrap();
    let model = &cad;

    // noise-free
    let id = Identification::new(model, &s, JointTerms::default()).unwrap();
    let truth = id.base.project(&true_pi);
    let ls = id.least_squares(Weighting::None).unwrap();
    let err = (&ls.base - &truth).amax() / truth.amax();
    eprintln!(
        "{name}: {} samples, {} base parameters, condition number {:.3e} (optimiser's {cond:.3e}), \
         tracking error {track:.2e} rad; noise-free: base parameters to {err:.2e} relative (max \
         |Δβ| / max |β|)",
        s.len(),
        id.base.len(),
        ls.condition_number
    );
    assert!(err < 1e-8, "{name}: noise-free error {err:e}");

    // noisy, the physically consistent estimate (the crate feature `sdp`)
    #[cfg(feature = "sdp")]
    {
        // noisy: 1 % of each joint's torque RMS
        let mut noisy = s.clone();
        let mut rng = Rng::new(42);
        for k in 0..nv {
            let rms = (s.tau.iter().skip(k).step_by(nv).map(|x| x * x).sum::<f64>()
                / s.len() as f64)
                .sqrt();
            for x in noisy.tau.iter_mut().skip(k).step_by(nv) {
                *x += 0.01 * rms * rng.normal();
            }
        }
        let id = Identification::new(model, &noisy, JointTerms::default()).unwrap();
        let ls = id.least_squares(Weighting::None).unwrap();
        let pc = id
            .physically_consistent(&PhysicalOptions::default())
            .unwrap();
        let n = model.njoints();
        let pc_verdicts = body_verdicts(&pc.parameters, n);
        assert!(
            pc_verdicts.iter().all(|v| *v == Verdict::Consistent),
            "{name}: {pc_verdicts:?}"
        );
        let ls_verdicts = body_verdicts(&ls.parameters, n);
        let ls_bad = ls_verdicts
            .iter()
            .filter(|v| !matches!(v, Verdict::Consistent | Verdict::RoundOff))
            .count();

        // held out: another exciting motion, exact torques
        let other = ExcitationOptions {
            duration: 8.0,
            iterations: 1,
            seed: 7,
            ..ExcitationOptions::default()
        };
        let (held, _) = optimize(model, &other).unwrap();
        let truth_model = model_with_parameters(model, true_pi.as_slice()).unwrap();
        let held = held.samples(&truth_model, 0.02).unwrap();
        let hid = Identification::new(model, &held, JointTerms::default()).unwrap();
        let e_ls = hid.evaluate(&ls.parameters).unwrap().residual_rms;
        let e_pc = hid.evaluate(&pc.parameters).unwrap().residual_rms;
        let tau_rms = (held.tau.iter().map(|x| x * x).sum::<f64>() / held.tau.len() as f64).sqrt();
        eprintln!(
            "{name}: noisy: least squares {ls_bad} of {n} bodies non-physical ({ls_verdicts:?}); \
             physically consistent: all {n} consistent; held-out torque RMS error: least squares \
             {e_ls:.4e}, physical {e_pc:.4e} (held-out torque RMS {tau_rms:.3e}); training residual \
             RMS: least squares {:.4e}, physical {:.4e}",
            ls.residual_rms, pc.residual_rms
        );
        // no worse, to within 1 % (a held-out motion weighs the estimation errors differently
        // from the samples: only there is the constrained estimate guaranteed no further from a
        // consistent truth than least squares)
        assert!(
            e_pc <= 1.01 * e_ls,
            "{name}: physical {e_pc:e} > least squares {e_ls:e}"
        );

        // the consistent model runs in ABA along the held-out motion
        let fitted = model_with_parameters(model, pc.parameters.as_slice()).unwrap();
        let mut data = Data::new(&fitted);
        for k in 0..held.len() {
            let r = |x: &[f64], w| x[k * w..(k + 1) * w].to_vec();
            let x = aba(
                &fitted,
                &mut data,
                &r(&held.q, model.nq()),
                &r(&held.v, nv),
                &r(&held.tau, nv),
            )
            .unwrap();
            assert!(
                x.iter().all(|v| v.is_finite()),
                "{name}: ABA NaN at sample {k}"
            );
        }
        if ls_bad > 0 {
            eprintln!(
                "{name}: least squares is non-physical; the consistent model ran ABA on {} states \
                 without NaN",
                held.len()
            );
        }
    }
}

#[test]
fn puma560_closed_loop_identification() {
    check(&builtin("puma560").unwrap());
}

#[test]
fn panda_closed_loop_identification() {
    let dir = common::example_robot_data();
    let model = load_urdf(dir.join("panda_description/urdf/panda.urdf"), false).unwrap();
    check(&model);
}
