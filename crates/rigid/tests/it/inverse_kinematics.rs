//! Inverse kinematics (`rigid::kinematics::inverse`):
//!
//! - Modern Robotics' `IKinBody` run by hand on the PUMA 560 (built-in, standard DH) and the UR5
//!   (example-robot-data's URDF): the textbook's product of exponentials `T(θ) = M Π exp([B_i]θ_i)`
//!   and body Jacobian written out here from `M = T(0)` and the body screw axes `B_i` (columns of
//!   `J_b(0)`), with `θ ← θ + J_b† V_b` until `‖ω_b‖ ≤ ε_ω` and `‖v_b‖ ≤ ε_v`; rigid's solver with
//!   `damping = 0`, no limits and no restarts takes the same iterates (1e-9) in as many steps;
//! - the book's own `IKinBody` example (the RRP arm of its code's documentation) to its printed
//!   digits;
//! - forward kinematics on every checked-in robot of the description packages (and, with
//!   `RIGID_CROSSCHECK=1`, every URDF of the installed example-robot-data): targets `T(q*)` of
//!   the deepest frame at random `q*` within the limits, solved from the neutral configuration
//!   with the defaults (Levenberg-Marquardt, limits respected, restarts): the solution reaches
//!   the target to 1e-9 and stays within the limits;
//! - position-only targets, the space twist, typed errors.
#![allow(non_snake_case)]

use crate::common;
use nalgebra::{DMatrix, DVector};
use rigid::io::urdf::load_urdf;
use rigid::kinematics::{inverse, ErrorTwist, IkError, Options, Site, Target};
use rigid::mass::{RotationalInertia, SpatialInertia};
use rigid::multibody::*;
use rigid::spatial::{Mat3, Transform, Twist, Vec3};

/// Modern Robotics' `FKinBody` and `JacobianBody` for a chain given by `M` and the body screw
/// axes `B_i` (Lynch & Park §4.1.3, §5.1.2).
struct Textbook {
    M: Transform,
    B: Vec<Twist>,
}

impl Textbook {
    /// From a model: `M = T(0)` of `site` and `B_i` the columns of its body Jacobian at `q = 0`
    /// (every joint revolute or prismatic, `q = 0` the home configuration).
    fn of(model: &Model, site: Site) -> Self {
        let mut d = Data::new(model);
        let q0 = vec![0.0; model.nq()];
        forward_kinematics_q(model, &mut d, &q0).unwrap();
        let M = site.pose(model, &d);
        let J = match site {
            Site::Joint(j) => joint_jacobian(model, &mut d, &q0, j, ReferenceFrame::Body),
            Site::Frame(f) => frame_jacobian(model, &mut d, &q0, f, ReferenceFrame::Body),
        }
        .unwrap()
        .clone();
        let B = (0..model.nv())
            .map(|k| Twist::from_slice(J.column(k).as_slice()))
            .collect();
        Self { M, B }
    }

    /// `T(θ) = M exp([B_1]θ_1) ... exp([B_n]θ_n)`.
    fn fk(&self, theta: &[f64]) -> Transform {
        self.B
            .iter()
            .zip(theta)
            .fold(self.M, |T, (B, t)| T * Transform::exp(&(*B * *t)))
    }

    /// `J_b,n = B_n`, `J_b,i = [Ad_{exp(-[B_n]θ_n) ... exp(-[B_{i+1}]θ_{i+1})}] B_i`.
    fn jacobian(&self, theta: &[f64]) -> DMatrix<f64> {
        let n = self.B.len();
        let mut J = DMatrix::zeros(6, n);
        let mut T = Transform::identity();
        for i in (0..n).rev() {
            let col = T.act_twist(&self.B[i]).to_vector();
            J.column_mut(i).copy_from(&col);
            T = T * Transform::exp(&(self.B[i] * -theta[i]));
        }
        J
    }

    /// `IKinBody`: the iterates `θ_0, θ_1, ...` until the tolerances are met or `max` steps.
    fn ikin_body(
        &self,
        Tsd: &Transform,
        theta0: &[f64],
        eomg: f64,
        ev: f64,
        max: usize,
    ) -> Vec<Vec<f64>> {
        let mut theta = theta0.to_vec();
        let mut out = vec![theta.clone()];
        for _ in 0..max {
            let Vb = (self.fk(&theta).inverse() * *Tsd).log();
            if Vb.w.norm() <= eomg && Vb.v.norm() <= ev {
                break;
            }
            let J = self.jacobian(&theta);
            let svd = J.svd(true, true);
            let eps = svd.singular_values.max() * 1e-15;
            let pinv = svd.pseudo_inverse(eps).unwrap();
            let d = pinv * DVector::from_column_slice(Vb.to_vector().as_slice());
            for (t, x) in theta.iter_mut().zip(d.iter()) {
                *t += x;
            }
            out.push(theta.clone());
        }
        out
    }
}

fn textbook_options(max: usize) -> Options {
    Options {
        twist: ErrorTwist::Body,
        angular_tolerance: 1e-10,
        linear_tolerance: 1e-10,
        max_iterations: max,
        damping: 0.0,
        restarts: 0,
        seed: 0,
        respect_limits: false,
    }
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// rigid's iterates, one solve per step count, equal the textbook's.
fn same_iterates_as_ikin_body(model: &Model, site: Site, seed: u64) {
    let tb = Textbook::of(model, site);
    let mut d = Data::new(model);
    let mut rng = Rng::new(seed);
    for _ in 0..4 {
        let target_q: Vec<f64> = (0..model.nq()).map(|_| rng.uniform(-1.5, 1.5)).collect();
        let theta0: Vec<f64> = target_q
            .iter()
            .map(|t| t + rng.uniform(-0.3, 0.3))
            .collect();
        forward_kinematics_q(model, &mut d, &target_q).unwrap();
        let Tsd = site.pose(model, &d);
        // the textbook's forward kinematics is rigid's
        let e = (tb.fk(&target_q).inverse() * Tsd).log().norm();
        assert!(e < 1e-12, "product of exponentials differs by {e}");
        let iterates = tb.ikin_body(&Tsd, &theta0, 1e-10, 1e-10, 20);
        assert!(iterates.len() > 2, "too easy");
        for (k, theta) in iterates.iter().enumerate().skip(1) {
            let q = match inverse(
                model,
                &mut d,
                site,
                &Target::Pose(Tsd),
                &theta0,
                &textbook_options(k),
            ) {
                Ok(s) => s.q,
                Err(IkError::NotConverged { best }) => best.q,
                Err(e) => panic!("{e}"),
            };
            let diff = max_diff(&q, theta);
            assert!(
                diff < 1e-9,
                "step {k}: rigid's iterate differs by {diff:.2e}"
            );
        }
        let sol = inverse(
            model,
            &mut d,
            site,
            &Target::Pose(Tsd),
            &theta0,
            &textbook_options(20),
        )
        .unwrap();
        assert_eq!(sol.iterations, iterates.len() - 1, "number of steps");
        assert!(max_diff(&sol.q, iterates.last().unwrap()) < 1e-9);
    }
}

#[test]
fn newton_steps_equal_ikin_body_on_the_puma_560() {
    let model = puma560(Puma560Options::default());
    let site = Site::by_name(&model, "link6").unwrap();
    same_iterates_as_ikin_body(&model, site, 1);
}

#[test]
fn newton_steps_equal_ikin_body_on_the_ur5() {
    let path = common::example_robot_data().join("ur_description/urdf/ur5_robot.urdf");
    let model = load_urdf(&path, false).unwrap();
    let site = Site::by_name(&model, "tool0").unwrap();
    same_iterates_as_ikin_body(&model, site, 2);
}

/// Modern Robotics' code documents `IKinBody` on an RRP arm: `Blist = [[0, 0, -1, 2, 0, 0],
/// [0, 0, 0, 0, 1, 0], [0, 0, 1, 0, 0, 0.1]]` (rows (ω, v)), `M = [[-1, 0, 0, 0], [0, 1, 0, 6],
/// [0, 0, -1, 2]]`, `T = [[0, 1, 0, -5], [1, 0, 0, 4], [0, 0, -1, 1.6858]]`, `θ₀ = (1.5, 2.5, 3)`,
/// `ε_ω = 0.01`, `ε_v = 0.001`: `θ = (1.57073819, 2.999667, 3.14153913)`. The arm as a model: a
/// revolute joint about `-z` through `(0, -2, 0)` of the end frame, a prismatic joint along `y`,
/// a helical joint about `z` of pitch 0.1 m/rad; the textbook iteration written here and rigid's
/// solver both give the book's answer, and the same iterates.
#[test]
fn the_books_ikin_body_example_gives_its_answer() {
    let M = Transform::new(
        Mat3::new(-1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, -1.0),
        Vec3::new(0.0, 6.0, 2.0),
    );
    let B = [
        Twist::new(Vec3::new(0.0, 0.0, -1.0), Vec3::new(2.0, 0.0, 0.0)),
        Twist::new(Vec3::zeros(), Vec3::new(0.0, 1.0, 0.0)),
        Twist::new(Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.0, 0.0, 0.1)),
    ];
    let T = Transform::new(
        Mat3::new(0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0),
        Vec3::new(-5.0, 4.0, 1.6858),
    );
    let book = [1.57073819, 2.999667, 3.14153913];
    let tb = Textbook { M, B: B.to_vec() };
    let it = tb.ikin_body(&T, &[1.5, 2.5, 3.0], 0.01, 0.001, 20);
    assert!(
        max_diff(it.last().unwrap(), &book) < 5e-8,
        "{:?}",
        it.last()
    );

    let g = SpatialInertia::from_com(
        1.0,
        Vec3::zeros(),
        RotationalInertia::diagonal(1.0, 1.0, 1.0),
    );
    let r1 = Vec3::new(0.0, -2.0, 0.0);
    let mut b = ModelBuilder::new("rrp");
    let j1 = b
        .add_joint(
            None,
            "j1",
            JointType::Revolute { axis: -Vec3::z() },
            M * Transform::from_translation(r1),
            g,
        )
        .unwrap();
    let j2 = b
        .add_joint(
            Some(j1),
            "j2",
            JointType::Prismatic { axis: Vec3::y() },
            Transform::from_translation(-r1),
            g,
        )
        .unwrap();
    let j3 = b
        .add_joint(
            Some(j2),
            "j3",
            JointType::Helical {
                axis: Vec3::z(),
                pitch: 0.1,
            },
            Transform::identity(),
            g,
        )
        .unwrap();
    b.add_frame(Some(j3), "ee", Transform::identity()).unwrap();
    let model = b.build().unwrap();
    let site = Site::by_name(&model, "ee").unwrap();
    let mut d = Data::new(&model);
    let opts = Options {
        angular_tolerance: 0.01,
        linear_tolerance: 0.001,
        ..textbook_options(20)
    };
    let sol = inverse(
        &model,
        &mut d,
        site,
        &Target::Pose(T),
        &[1.5, 2.5, 3.0],
        &opts,
    )
    .unwrap();
    assert!(max_diff(&sol.q, &book) < 5e-8, "{:?}", sol.q);
    assert!(max_diff(&sol.q, it.last().unwrap()) < 1e-12);
    assert_eq!(sol.iterations, it.len() - 1);
    same_iterates_as_ikin_body(&model, site, 3);
}

/// The joint with the most ancestors, and a frame fixed in its body (its link), else the
/// joint's own frame.
fn deepest_site(model: &Model) -> Site {
    let depth = |mut j: Option<JointId>| {
        let mut n = 0;
        while let Some(i) = j {
            n += 1;
            j = model.joints()[i.0].parent;
        }
        n
    };
    let (deepest, _) = (0..model.njoints())
        .map(|i| (i, depth(Some(JointId(i)))))
        .max_by_key(|&(i, d)| (d, i))
        .unwrap();
    model
        .frames()
        .iter()
        .rposition(|f| f.parent == Some(JointId(deepest)))
        .map_or(Site::Joint(JointId(deepest)), |f| Site::Frame(FrameId(f)))
}

/// Targets reached on one robot: (trials, converged, worst residual, mean steps, mean attempts).
fn ik_round_trip(model: &Model, trials: usize, seed: u64) -> (usize, usize, f64, f64, f64) {
    let site = deepest_site(model);
    let mut d = Data::new(model);
    let mut rng = Rng::new(seed);
    let q0 = neutral(model);
    let (mut ok, mut worst, mut steps, mut attempts) = (0, 0.0f64, 0usize, 0usize);
    let (lo, up) = (model.lower_limits(), model.upper_limits());
    for t in 0..trials {
        let q_star = random_configuration(model, &mut rng);
        forward_kinematics_q(model, &mut d, &q_star).unwrap();
        let Tsd = site.pose(model, &d);
        let opts = Options {
            seed: seed + t as u64,
            ..Options::default()
        };
        match inverse(model, &mut d, site, &Target::Pose(Tsd), &q0, &opts) {
            Ok(s) => {
                ok += 1;
                steps += s.total_iterations;
                attempts += s.attempts;
                forward_kinematics_q(model, &mut d, &s.q).unwrap();
                let V = (site.pose(model, &d).inverse() * Tsd).log();
                worst = worst.max(V.w.norm()).max(V.v.norm());
                for (k, x) in s.q.iter().enumerate() {
                    assert!(
                        *x >= lo[k] - 1e-12 && *x <= up[k] + 1e-12,
                        "{}: q[{k}] = {x} outside [{}, {}]",
                        model.name(),
                        lo[k],
                        up[k]
                    );
                }
            }
            Err(IkError::NotConverged { best }) => {
                steps += best.total_iterations;
                attempts += best.attempts;
            }
            Err(e) => panic!("{}: {e}", model.name()),
        }
    }
    (
        trials,
        ok,
        worst,
        steps as f64 / trials as f64,
        attempts as f64 / trials as f64,
    )
}

fn report(files: &[std::path::PathBuf], trials: usize) {
    let (mut all, mut all_ok) = (0, 0);
    let mut failures = Vec::new();
    for (i, path) in files.iter().enumerate() {
        let Ok(model) = load_urdf(path, false) else {
            continue;
        };
        if model.nv() == 0 {
            continue;
        }
        let (n, ok, worst, steps, attempts) = ik_round_trip(&model, trials, 100 + i as u64);
        eprintln!(
            "ik {:<40} nv {:>2}: {ok}/{n} reached, residual ≤ {worst:.1e}, {steps:.1} steps and {attempts:.2} attempts per target",
            path.file_name().unwrap().to_string_lossy(),
            model.nv()
        );
        all += n;
        all_ok += ok;
        if worst > 1e-9 {
            failures.push(format!("{}: residual {worst:.2e}", path.display()));
        }
        if ok < n {
            failures.push(format!("{}: {ok}/{n} targets reached", path.display()));
        }
    }
    eprintln!("ik: {all_ok}/{all} targets reached");
    assert!(all > 0);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn every_checked_in_robot_reaches_targets_of_its_own_forward_kinematics() {
    let files = common::urdfs_under(&common::fixtures_dir().join("robots"));
    assert!(files.len() >= 10);
    report(&files, 6);
}

#[test]
fn every_robot_of_the_installed_example_robot_data_reaches_its_targets() {
    if !common::reference::live("IK on every URDF of the installed example-robot-data") {
        return;
    }
    let dir = rigid::io::robots::example_robot_data()
        .expect("example-robot-data not found (RIGID_CROSSCHECK=1 needs it installed)");
    report(&common::urdfs_under(&dir), 4);
}

#[test]
fn position_targets_and_the_space_twist_converge() {
    let model = puma560(Puma560Options::default());
    let site = Site::by_name(&model, "link6").unwrap();
    let mut d = Data::new(&model);
    let q_star = [0.3, -0.5, 0.4, 0.2, -0.6, 0.1];
    forward_kinematics_q(&model, &mut d, &q_star).unwrap();
    let T = site.pose(&model, &d);
    let p = inverse(
        &model,
        &mut d,
        site,
        &Target::Position(T.translation),
        &[0.0; 6],
        &Options::default(),
    )
    .unwrap();
    assert!(p.position_error <= 1e-9 && p.angular_error == 0.0);
    let opts = Options {
        twist: ErrorTwist::Space,
        ..Options::default()
    };
    let s = inverse(&model, &mut d, site, &Target::Pose(T), &[0.0; 6], &opts).unwrap();
    forward_kinematics_q(&model, &mut d, &s.q).unwrap();
    assert!((site.pose(&model, &d).inverse() * T).log().norm() < 1e-9);
}

#[test]
fn errors_are_typed_and_name_what_is_wrong() {
    let model = puma560(Puma560Options::default());
    let mut d = Data::new(&model);
    let site = Site::by_name(&model, "link6").unwrap();
    assert!(matches!(
        Site::by_name(&model, "nope"),
        Err(IkError::UnknownSite { .. })
    ));
    let far = Target::Position(Vec3::new(10.0, 0.0, 0.0));
    let opts = Options {
        restarts: 2,
        max_iterations: 30,
        ..Options::default()
    };
    match inverse(&model, &mut d, site, &far, &[0.0; 6], &opts) {
        Err(IkError::NotConverged { best }) => {
            assert_eq!(best.attempts, 3);
            assert!(best.linear_error > 8.0 && !best.converged);
        }
        other => panic!("{other:?}"),
    }
    let e = inverse(&model, &mut d, site, &far, &[0.0; 5], &opts).unwrap_err();
    assert!(
        matches!(e, IkError::Input(MultibodyError::Dimension(_))),
        "{e}"
    );
    let nan = Target::Position(Vec3::new(f64::NAN, 0.0, 0.0));
    assert!(matches!(
        inverse(&model, &mut d, site, &nan, &[0.0; 6], &opts),
        Err(IkError::BadTarget { .. })
    ));
    let bad = Options {
        angular_tolerance: -1.0,
        ..opts
    };
    let e = inverse(&model, &mut d, site, &far, &[0.0; 6], &bad).unwrap_err();
    assert!(e.to_string().contains("angular_tolerance"), "{e}");
}
