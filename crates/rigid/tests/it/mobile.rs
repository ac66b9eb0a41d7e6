//! Wheeled mobile robots (`rigid::mobile`, Lynch & Park ch. 13) and the product of exponentials
//! (`rigid::kinematics::poe`):
//! - `H(φ)` of every base equals the book's matrices (eq. 13.9, 13.10, §13.3) to 1e-12, and
//!   `F H(0) = I` on the motions the base can make;
//! - odometry equals the exponential of the constant body twist (a different formula: SE(3)'s exp)
//!   for straight, in-place and general increments to 1e-12, and the closed forms of §13.4;
//! - the capstone's milestone 3 (and random cases) against the Modern Robotics code library's
//!   functions, `FKinBody`/`JacobianBody`/`FKinSpace`/`JacobianSpace` and `ScrewTrajectory`/
//!   `CartesianTrajectory` to 1e-9 (`fixtures/mobile_mr.json`, written by `gen_mobile_mr.py`,
//!   regenerated live with `RIGID_CROSSCHECK=1`);
//! - a whole capstone run brings the end effector onto the reference and keeps it there;
//! - bad input: rank-deficient wheel geometry, nonpositive radii, wrong lengths.

use crate::common::json::{mat_of, vec_of};
use crate::common::reference;
use nalgebra::DMatrix;
use rigid::kinematics::poe;
use rigid::mobile::{
    chassis_velocity, Base, Capstone, Feedback, Kind, MobileError, MobileManipulator, MobileState,
    Wheel,
};
use rigid::simulation::{PosePath, PoseTrajectory, TimeScaling};
use rigid::spatial::{Mat6, Transform, Twist, Vec3};
use serde_json::Value;

fn book_rotation(phi: f64) -> DMatrix<f64> {
    let (s, c) = phi.sin_cos();
    DMatrix::from_row_slice(3, 3, &[1.0, 0.0, 0.0, 0.0, c, s, 0.0, -s, c])
}

/// H(φ) = H(0) R(φ)ᵀ with the H(0) typed from the book.
#[test]
fn every_base_has_the_books_h_matrix() {
    let (r, l, w, d, track) = (0.05, 0.3, 0.2, 0.25, 0.4);
    let s3 = (std::f64::consts::PI / 3.0).sin();
    let books: [(Base, DMatrix<f64>); 4] = [
        (
            Base::mecanum(r, l, w).unwrap(),
            DMatrix::from_row_slice(
                4,
                3,
                &[
                    -l - w,
                    1.0,
                    -1.0,
                    l + w,
                    1.0,
                    1.0,
                    l + w,
                    1.0,
                    -1.0,
                    -l - w,
                    1.0,
                    1.0,
                ],
            ) / r,
        ),
        (
            Base::omni3(r, d).unwrap(),
            DMatrix::from_row_slice(3, 3, &[-d, 1.0, 0.0, -d, -0.5, -s3, -d, -0.5, s3]) / r,
        ),
        (
            Base::diff_drive(r, track).unwrap(),
            DMatrix::from_row_slice(2, 3, &[-track / 2.0, 1.0, 0.0, track / 2.0, 1.0, 0.0]) / r,
        ),
        (
            Base::car(r, track, 1.2).unwrap(),
            DMatrix::from_row_slice(2, 3, &[-track / 2.0, 1.0, 0.0, track / 2.0, 1.0, 0.0]) / r,
        ),
    ];
    for (base, h0) in &books {
        for phi in [0.0, 0.7, -2.9] {
            let err = (base.H(phi) - h0 * book_rotation(phi)).amax();
            assert!(err < 1e-12, "{}: |H(φ) - book| = {err:e}", base.name());
        }
        // F H(0) is the identity on the chassis motions the base allows
        let fh = base.F() * h0;
        let allowed = if base.kind() == Kind::Omnidirectional {
            DMatrix::identity(3, 3)
        } else {
            DMatrix::from_row_slice(3, 3, &[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0])
        };
        assert!((fh - allowed).amax() < 1e-12, "{}: F H(0)", base.name());
    }
    // mecanum: the book's F written out (eq. 13.33)
    let k = 1.0 / (l + w);
    let f = DMatrix::from_row_slice(
        3,
        4,
        &[-k, k, k, -k, 1.0, 1.0, 1.0, 1.0, -1.0, 1.0, -1.0, 1.0],
    ) * (r / 4.0);
    assert!((books[0].0.F() - f).amax() < 1e-12);
}

/// A nonholonomic base's wheel speeds see only the motions its constraint allows:
/// `A(q) q̇ = 0` for `q̇ = R(φ) (ω, v, 0)`, and the car's steering angle is `atan(ℓ ω / v)`.
#[test]
fn diff_drive_and_car_obey_their_constraint() {
    let car = Base::car(0.3, 1.5, 2.5).unwrap();
    for phi in [0.0, 1.0, -2.5] {
        let qdot = chassis_velocity(phi, [0.4, 1.3, 0.0]);
        let a = car.constraint([phi, 1.0, 2.0]).unwrap();
        let dot: f64 = a.iter().zip(qdot).map(|(a, b)| a * b).sum();
        assert!(dot.abs() < 1e-15);
        let sideways = chassis_velocity(phi, [0.0, 0.0, 1.0]);
        assert!((a.iter().zip(sideways).map(|(a, b)| a * b).sum::<f64>() + 1.0).abs() < 1e-15);
    }
    assert!((car.steering([0.4, 2.0, 0.0]).unwrap() - (2.5f64 * 0.4 / 2.0).atan()).abs() < 1e-15);
    assert_eq!(
        car.steering([0.4, 0.0, 0.0]),
        None,
        "a car cannot turn in place"
    );
    assert!(Base::mecanum(0.05, 0.2, 0.2)
        .unwrap()
        .constraint([0.0; 3])
        .is_none());
}

/// Odometry (§13.4) against the exponential of the constant twist `(0, 0, ω, v_x, v_y, 0)` on
/// SE(3), started at the chassis pose; and the closed forms of straight and in-place motions.
#[test]
fn odometry_is_the_exponential_of_the_body_twist() {
    let bases = [
        Base::mecanum(0.0475, 0.235, 0.15).unwrap(),
        Base::omni3(0.05, 0.2).unwrap(),
        Base::diff_drive(0.1, 0.5).unwrap(),
        Base::car(0.3, 1.5, 2.5).unwrap(),
    ];
    let mut rng = rigid::multibody::Rng::new(13);
    for base in &bases {
        let m = base.wheels().len();
        for case in 0..40 {
            let q = [
                rng.uniform(-3.0, 3.0),
                rng.uniform(-2.0, 2.0),
                rng.uniform(-2.0, 2.0),
            ];
            let dtheta: Vec<f64> = match case {
                0 => vec![0.0; m],
                1 => vec![2.0; m], // mecanum, diff drive: straight ahead; omni3: turning in place
                _ => (0..m).map(|_| rng.uniform(-5.0, 5.0)).collect(),
            };
            let got = base.odometry(q, &dtheta).unwrap();
            let [w, vx, vy] = base.body_twist(&dtheta).unwrap();
            let t = Transform::new(
                rigid::spatial::so3::from_rpy(0.0, 0.0, q[0]),
                Vec3::new(q[1], q[2], 0.0),
            ) * Transform::exp(&Twist::new(Vec3::new(0.0, 0.0, w), Vec3::new(vx, vy, 0.0)));
            assert!((got[0] - q[0] - w).abs() < 1e-12);
            let (yaw, x, y) = (
                t.rotation[(1, 0)].atan2(t.rotation[(0, 0)]),
                t.translation.x,
                t.translation.y,
            );
            let dphi = (got[0] - yaw + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
                - std::f64::consts::PI;
            assert!(
                dphi.abs() < 1e-12 && (got[1] - x).abs() < 1e-12 && (got[2] - y).abs() < 1e-12,
                "{} case {case}: {got:?} vs ({yaw}, {x}, {y})",
                base.name()
            );
        }
    }
    // closed forms: a differential drive straight ahead by r Δθ, in place by r Δθ / d
    let dd = &bases[2];
    let q = dd.odometry([0.3, 1.0, -1.0], &[2.0, 2.0]).unwrap();
    assert!((q[0] - 0.3).abs() < 1e-15);
    assert!(
        (q[1] - 1.0 - 0.2 * 0.3f64.cos()).abs() < 1e-15
            && (q[2] + 1.0 - 0.2 * 0.3f64.sin()).abs() < 1e-15
    );
    let q = dd.odometry([0.3, 1.0, -1.0], &[-2.0, 2.0]).unwrap();
    assert!(
        (q[0] - 0.3 - 0.1 * 2.0 / 0.25).abs() < 1e-15
            && (q[1] - 1.0).abs() < 1e-15
            && (q[2] + 1.0).abs() < 1e-15
    );
    // mecanum sideways: wheels (-1, 1, -1, 1) Δθ drive v_by = r Δθ
    let mec = &bases[0];
    let q = mec.odometry([0.0; 3], &[-1.0, 1.0, -1.0, 1.0]).unwrap();
    assert!(q[0].abs() < 1e-15 && q[1].abs() < 1e-15 && (q[2] - 0.0475).abs() < 1e-15);
    // an arc: a differential drive turning ω = π/2 with v = 1 ends at (1, 1) from the origin
    let (r, d) = (0.1, 0.25);
    let (w, v) = (std::f64::consts::FRAC_PI_2, 1.0);
    let q = dd
        .odometry([0.0; 3], &[(v - d * w) / r, (v + d * w) / r])
        .unwrap();
    let radius = v / w;
    assert!(
        (q[0] - w).abs() < 1e-14 && (q[1] - radius).abs() < 1e-14 && (q[2] - radius).abs() < 1e-14
    );
}

fn transform_of(v: &Value) -> Transform {
    let m = mat_of(v);
    let r = m.fixed_view::<3, 3>(0, 0).into_owned();
    Transform::new(r, Vec3::new(m[(0, 3)], m[(1, 3)], m[(2, 3)]))
}

fn twists_of(v: &Value) -> Vec<Twist> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|b| Twist::from_slice(&vec_of(b)))
        .collect()
}

fn fixture() -> Value {
    reference::fixture("fixtures/mobile_mr.json")
}

/// The capstone's milestone 3, and random steps, against the code library's functions: X, J_e,
/// V, X_err and the speeds `J_e† V`. The published numbers (V = (0, 0, 0, 21.409, 0, 6.455), the
/// wheels at 157.2 rad/s, ...) are the first two cases, rounded.
#[test]
fn capstone_feedback_equals_the_code_library() {
    let youbot = MobileManipulator::youbot();
    let cases = fixture()["milestone3"].as_array().unwrap().clone();
    assert!(cases.len() >= 8);
    for (i, c) in cases.iter().enumerate() {
        let q = vec_of(&c["chassis"]);
        let theta = vec_of(&c["theta"]);
        let x = youbot.forward([q[0], q[1], q[2]], &theta).unwrap();
        let x_ref = transform_of(&c["X"]);
        assert!(
            (x.to_homogeneous() - x_ref.to_homogeneous()).amax() < 1e-12,
            "case {i}: X"
        );
        let je = youbot.jacobian(&theta).unwrap();
        assert!((&je - mat_of(&c["Je"])).amax() < 1e-12, "case {i}: J_e");
        let diag =
            |k: &str| Mat6::from_diagonal(&nalgebra::Vector6::from_column_slice(&vec_of(&c[k])));
        let mut fb = Feedback::new(diag("Kp"), diag("Ki")).unwrap();
        let dt = c["dt"].as_f64().unwrap();
        let cmd = fb
            .command(
                &youbot,
                &x,
                &transform_of(&c["Xd"]),
                &transform_of(&c["Xd_next"]),
                dt,
                &theta,
            )
            .unwrap();
        let close = |a: &[f64], b: &[f64], what: &str| {
            let e = reference::rel(a, b, 1.0);
            assert!(e < 1e-9, "case {i}: {what} off by {e:e}: {a:?} vs {b:?}");
        };
        close(cmd.V.to_vector().as_slice(), &vec_of(&c["V"]), "V");
        close(
            cmd.X_err.to_vector().as_slice(),
            &vec_of(&c["Xerr"]),
            "X_err",
        );
        close(&cmd.speeds, &vec_of(&c["speeds"]), "speeds");
    }
    // the course's published (rounded) answers, from rigid's own output
    let theta = [0.0, 0.0, 0.2, -1.6, 0.0];
    let x = youbot.forward([0.0; 3], &theta).unwrap();
    let mut fb = Feedback::new(Mat6::zeros(), Mat6::zeros()).unwrap();
    let cmd = fb
        .command(
            &youbot,
            &x,
            &transform_of(&cases[0]["Xd"]),
            &transform_of(&cases[0]["Xd_next"]),
            0.01,
            &theta,
        )
        .unwrap();
    let round =
        |x: &[f64], k: f64| -> Vec<f64> { x.iter().map(|s| (s * k).round() / k + 0.0).collect() };
    assert_eq!(
        round(&cmd.speeds, 10.0),
        [157.2, 157.2, 157.2, 157.2, 0.0, -652.9, 1398.6, -745.7, 0.0]
    );
    assert_eq!(
        round(cmd.V.to_vector().as_slice(), 1e3),
        [0.0, 0.0, 0.0, 21.409, 0.0, 6.455]
    );
    assert_eq!(
        round(cmd.X_err.to_vector().as_slice(), 1e3),
        [0.0, 0.171, 0.0, 0.08, 0.0, 0.107]
    );
}

#[test]
fn product_of_exponentials_equals_the_code_library() {
    for (i, c) in fixture()["poe"].as_array().unwrap().iter().enumerate() {
        let m = transform_of(&c["M"]);
        let (b, s) = (twists_of(&c["Blist"]), twists_of(&c["Slist"]));
        let theta = vec_of(&c["theta"]);
        let close = |a: DMatrix<f64>, key: &str| {
            let e = (&a - mat_of(&c[key])).amax();
            assert!(e < 1e-12, "case {i}: {key} off by {e:e}");
        };
        close(
            poe::fkin_body(&m, &b, &theta)
                .unwrap()
                .to_homogeneous()
                .resize(4, 4, 0.0),
            "FKinBody",
        );
        close(
            poe::fkin_space(&m, &s, &theta)
                .unwrap()
                .to_homogeneous()
                .resize(4, 4, 0.0),
            "FKinSpace",
        );
        close(poe::jacobian_body(&b, &theta).unwrap(), "JacobianBody");
        close(poe::jacobian_space(&s, &theta).unwrap(), "JacobianSpace");
    }
}

#[test]
fn pose_trajectories_equal_the_code_library() {
    for (i, c) in fixture()["trajectories"]
        .as_array()
        .unwrap()
        .iter()
        .enumerate()
    {
        for (key, path) in [
            ("screw", PosePath::Screw),
            ("cartesian", PosePath::Cartesian),
        ] {
            let traj = PoseTrajectory::new(
                transform_of(&c["Xstart"]),
                transform_of(&c["Xend"]),
                c["Tf"].as_f64().unwrap(),
                TimeScaling::Quintic,
                path,
            )
            .unwrap();
            let n = c["N"].as_u64().unwrap() as usize;
            for (k, (got, want)) in traj
                .samples(n)
                .iter()
                .zip(c[key].as_array().unwrap())
                .enumerate()
            {
                let e = (got.to_homogeneous() - transform_of(want).to_homogeneous()).amax();
                assert!(e < 1e-12, "case {i} {key} sample {k}: off by {e:e}");
            }
        }
    }
}

/// With `RIGID_CROSSCHECK=1`: the fixture is what the code library computes today.
#[test]
fn the_code_library_fixture_is_current() {
    if reference::live("mobile_mr.json regenerated from modern_robotics") {
        reference::check_generator("fixtures/gen_mobile_mr.py");
    }
}

/// A whole run: 0.42 m and 30° off the reference at the start, `|X_err| < 1e-3` (m and rad)
/// after 5 s and until the end (a reference of 16 s: pick, carry, place); every
/// speed within the limit; the cube carried (gripper closed) in the middle.
#[test]
fn the_capstone_run_converges_onto_the_reference() {
    let c = Capstone::youbot();
    let x0 = c.robot.forward(c.start.chassis, &c.start.arm).unwrap();
    let e0 = (x0.inverse() * c.reference_start).log();
    assert!(
        e0.w.norm() > 30f64.to_radians() * 0.99
            && (x0.translation - c.reference_start.translation).norm() > 0.2
    );
    let run = c.run().unwrap();
    assert_eq!(run.states.len(), run.reference.len());
    assert_eq!(run.row(0).len(), 13);
    let settled = (5.0 / c.dt) as usize;
    let worst = run.errors[settled..]
        .iter()
        .map(Twist::norm)
        .fold(0.0, f64::max);
    assert!(worst < 1e-3, "X_err after 5 s: {worst:e}");
    let closed = run.states.iter().filter(|(_, g)| *g).count();
    assert!(closed > run.states.len() / 4 && closed < run.states.len());
    for w in run.states.windows(2) {
        for (a, b) in w[0].0.arm.iter().zip(&w[1].0.arm) {
            assert!((b - a).abs() <= c.max_speed * c.dt + 1e-12);
        }
    }
}

/// Joint limits as the capstone suggests: a joint about to leave its range stops (its column of
/// J_e zeroed), the others take over. Without limits joints 3 and 4 cross -0.2 rad (toward the
/// stretched arm); with them they never do, and the end effector still follows the reference.
/// A joint that starts outside its range may come back in; limits that are not a range are
/// refused.
#[test]
fn feedback_respects_joint_limits() {
    let free = Capstone {
        feedback: Capstone::youbot().feedback,
        ..Capstone::youbot_with_limits()
    };
    let highest = |run: &rigid::mobile::CapstoneRun| {
        run.states
            .iter()
            .map(|(s, _)| s.arm[2].max(s.arm[3]))
            .fold(f64::MIN, f64::max)
    };
    let unlimited = free.run().unwrap();
    assert!(highest(&unlimited) > -0.2, "{}", highest(&unlimited));
    let c = Capstone::youbot_with_limits();
    let run = c.run().unwrap();
    assert!(highest(&run) <= -0.2 + 1e-12, "{}", highest(&run));
    let late = run.errors[(5.0 / c.dt) as usize..]
        .iter()
        .map(Twist::norm)
        .fold(0.0, f64::max);
    eprintln!("with joints 3 and 4 below -0.2 rad: |X_err| after 5 s at most {late:.2e}");
    assert!(late < 1e-2, "{late}");
    // joint 3 starts at 0.2 rad, above its range: it may move back in, never further out
    let mut outside = Capstone::youbot_with_limits();
    outside.start.arm[2] = 0.2;
    let run = outside.run().unwrap();
    let third: Vec<f64> = run.states.iter().map(|(s, _)| s.arm[2]).collect();
    assert!(third.windows(2).all(|w| w[1] <= w[0].max(-0.2) + 1e-12));
    assert!(
        *third.last().unwrap() < 0.2 - 1e-3,
        "joint 3 stayed frozen at {}",
        third.last().unwrap()
    );
    let mut bad = Capstone::youbot_with_limits();
    bad.feedback.limits[1] = (1.0, -1.0);
    assert!(matches!(
        bad.run(),
        Err(MobileError::Limits { joint: 1, .. })
    ));
}

/// `next_state`: speeds clipped, wheels and joints advanced by `speed dt`, the chassis by
/// odometry.
#[test]
fn next_state_is_one_euler_step() {
    let youbot = MobileManipulator::youbot();
    let s = MobileState {
        chassis: [0.1, 0.2, 0.3],
        arm: vec![0.0, 0.1, 0.2, 0.3, 0.4],
        wheels: vec![1.0, 2.0, 3.0, 4.0],
    };
    let speeds = [10.0, -10.0, 3.0, -3.0, 1.0, -1.0, 0.5, 20.0, -20.0];
    let n = youbot.next_state(&s, &speeds, 0.01, 5.0).unwrap();
    assert_eq!(n.wheels, vec![1.05, 1.95, 3.03, 3.97]);
    let want = [0.01, 0.09, 0.205, 0.35, 0.35];
    for (a, b) in n.arm.iter().zip(want) {
        assert!((a - b).abs() < 1e-15);
    }
    let c = youbot
        .base
        .odometry(s.chassis, &[0.05, -0.05, 0.03, -0.03])
        .unwrap();
    assert_eq!(n.chassis, c);
    assert!(matches!(
        youbot.next_state(&s, &speeds[..8], 0.01, 5.0),
        Err(MobileError::Dimension(_))
    ));
    assert!(matches!(
        youbot.next_state(&s, &speeds, 0.0, 5.0),
        Err(MobileError::NotPositive { what: "dt", .. })
    ));
}

#[test]
fn bad_geometry_is_refused_by_name() {
    assert!(matches!(
        Base::mecanum(0.05, 0.0, 0.0),
        Err(MobileError::RankDeficient {
            base: "mecanum",
            rank: 2,
            needed: 3
        })
    ));
    assert!(matches!(
        Base::mecanum(-0.05, 0.2, 0.2),
        Err(MobileError::Wheel { wheel: 0, .. })
    ));
    assert!(matches!(
        Base::omni3(f64::NAN, 0.2),
        Err(MobileError::Wheel { .. })
    ));
    assert!(matches!(
        Base::diff_drive(0.1, 0.0),
        Err(MobileError::NotPositive { what: "track", .. })
    ));
    // two omniwheels cannot make a base omnidirectional
    let two = Base::omni3(0.05, 0.2).unwrap().wheels()[..2].to_vec();
    let e = Base::new("two", Kind::Omnidirectional, two).unwrap_err();
    assert!(e.to_string().contains("rank 2"), "{e}");
    // rollers along the driving direction
    let w = Wheel {
        position: [0.1, 0.0],
        drive: 0.0,
        sliding: std::f64::consts::FRAC_PI_2,
        radius: 0.05,
    };
    assert!(matches!(
        Base::new("slides", Kind::Omnidirectional, vec![w; 3]),
        Err(MobileError::RollersAlongDrive { wheel: 0 })
    ));
    let mec = Base::mecanum(0.05, 0.2, 0.2).unwrap();
    assert!(matches!(
        mec.odometry([0.0; 3], &[1.0; 3]),
        Err(MobileError::Dimension(_))
    ));
    assert!(matches!(
        mec.odometry([0.0; 3], &[1.0, f64::NAN, 0.0, 0.0]),
        Err(MobileError::NotFinite { .. })
    ));
    let youbot = MobileManipulator::youbot();
    assert!(youbot.jacobian(&[0.0; 4]).is_err());
    let x = Transform::identity();
    let mut fb = Feedback::new(Mat6::identity(), Mat6::identity()).unwrap();
    assert!(fb.command(&youbot, &x, &x, &x, 0.0, &[0.0; 5]).is_err());
    let xd = Transform::from_translation(Vec3::new(0.1, 0.0, 0.0));
    assert!(fb
        .command(&youbot, &x, &xd, &xd, 0.01, &[0.0, f64::NAN, 0.0, 0.0, 0.0])
        .is_err());
    assert!(fb.command(&youbot, &x, &xd, &xd, 0.01, &[0.0; 4]).is_err());
    assert_eq!(
        fb.integral,
        Twist::zero(),
        "a refused call leaves the integral alone"
    );
    fb.Kp[(0, 0)] = f64::NAN;
    assert!(matches!(
        fb.command(&youbot, &x, &xd, &xd, 0.01, &[0.0; 5]),
        Err(MobileError::NotFinite { what: "Kp" })
    ));
    assert!(matches!(
        Base::new("none", Kind::Omnidirectional, Vec::new()),
        Err(MobileError::RankDeficient { rank: 0, .. })
    ));
    assert!(PoseTrajectory::new(x, x, 0.0, TimeScaling::Quintic, PosePath::Screw).is_err());
    assert!(rigid::mobile::chassis_motion(&[0.0; 3], &[0.0; 6]).is_err());
}

/// `examples/youbot.urdf` (the replay's model, its joints placed from the screw axes) has the
/// kinematics of `MobileManipulator::youbot()`: the frame `gripper` by the multibody forward
/// kinematics equals `T_sb(q) T_b0 M_0e e^{[B_1]θ_1} ⋯` to 1e-12 at random configurations.
#[test]
fn the_youbot_urdf_has_the_capstones_kinematics() {
    use rigid::multibody::{forward_kinematics_q, update_frame_placements, Data};
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/youbot.urdf");
    let model = rigid::io::urdf::load_urdf(&path, false).unwrap();
    let youbot = MobileManipulator::youbot();
    let at = |n: &str| model.joints()[model.joint_id(n).unwrap().0].idx_q;
    let gripper = model.frame_id("gripper").unwrap();
    let mut data = Data::new(&model);
    let mut rng = rigid::multibody::Rng::new(5);
    for _ in 0..20 {
        let chassis = [
            rng.uniform(-3.0, 3.0),
            rng.uniform(-2.0, 2.0),
            rng.uniform(-2.0, 2.0),
        ];
        let theta: Vec<f64> = (0..5).map(|_| rng.uniform(-2.0, 2.0)).collect();
        let mut q = vec![0.0; model.nq()];
        q[at("base_yaw")] = chassis[0];
        q[at("base_x")] = chassis[1];
        q[at("base_y")] = chassis[2];
        for (i, t) in theta.iter().enumerate() {
            q[at(&format!("arm_joint_{}", i + 1))] = *t;
        }
        forward_kinematics_q(&model, &mut data, &q).unwrap();
        update_frame_placements(&model, &mut data);
        let urdf = data.frame_placements[gripper.0];
        let poe = youbot.forward(chassis, &theta).unwrap();
        let e = (urdf.to_homogeneous() - poe.to_homogeneous()).amax();
        assert!(e < 1e-12, "{e:e}");
    }
}

/// The cube of a capstone run: at its initial pose before the grasp, in the gripper
/// (`T_sc = X T_ce,grasp⁻¹`) while it is closed, at its final pose after; the reference rows in
/// the course's 13-column format.
#[test]
fn the_cube_follows_the_gripper() {
    let c = Capstone::youbot();
    let run = c.run().unwrap();
    let cubes = c.cube_poses(&run).unwrap();
    assert_eq!(cubes.len(), run.states.len());
    let first_closed = run.states.iter().position(|(_, g)| *g).unwrap();
    assert_eq!(cubes[first_closed - 1], c.task.cube_initial);
    assert_eq!(*cubes.last().unwrap(), c.task.cube_final);
    // while carried the cube stays within 1 mm of where the task grasps and releases it
    let last_closed = run.states.iter().rposition(|(_, g)| *g).unwrap();
    for (k, want) in [
        (first_closed, c.task.cube_initial),
        (last_closed, c.task.cube_final),
    ] {
        let e = (cubes[k].translation - want.translation).norm();
        assert!(e < 1e-3, "state {k}: {e}");
    }
    let row = run.reference[0].row();
    let x = run.reference[0].X;
    assert_eq!(
        row[..3],
        [x.rotation[(0, 0)], x.rotation[(0, 1)], x.rotation[(0, 2)]]
    );
    assert_eq!(
        row[9..12],
        [x.translation.x, x.translation.y, x.translation.z]
    );
    assert_eq!(row[12], 0.0);
}
