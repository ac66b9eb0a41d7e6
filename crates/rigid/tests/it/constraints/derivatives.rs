//! The analytical derivatives of the constrained and impulse dynamics against central finite
//! differences of rigid's own verbs on the manifold (`q ⊕ ±h e_k`), for every constraint kind
//! (point, frame, joint coordinate), both reference frames, constraints to the world and between
//! two moving bodies, with Baumgarte gains, on a tree of every joint type whose motion subspace is
//! constant (free-flyer root, spherical, planar, prismatic, revolute, helical).

use crate::common::{inertia, step, transform};
use nalgebra::{DMatrix, DVector};
use rigid::multibody::constraints::{
    constraint_dynamics, constraint_dynamics_derivatives, impulse_dynamics,
    impulse_dynamics_derivatives, Baumgarte, ConstraintData, ConstraintDynamicsDerivatives,
    ConstraintKind, ConstraintModel, ImpulseDynamicsDerivatives, ProximalSettings,
};
use rigid::multibody::{
    random_configuration, Data, JointId, JointType, Model, ModelBuilder, ReferenceFrame, Rng,
};
use rigid::spatial::Vec3;

const H: f64 = 1e-6;
const TOLERANCE: f64 = 1e-6;

/// A free-flyer root with two branches of four joints each (spherical, planar, prismatic,
/// revolute; helical, revolute, prismatic, revolute), random placements and inertias.
fn two_branches() -> Model {
    let mut rng = Rng::new(11);
    let mut b = ModelBuilder::new("two_branches");
    b.set_gravity(Vec3::new(0.3, -0.2, -9.81));
    let root = b
        .add_joint(
            None,
            "root",
            JointType::FreeFlyer,
            transform(&mut rng),
            inertia(&mut rng),
        )
        .unwrap();
    let branches = [
        [
            JointType::Spherical,
            JointType::Planar,
            JointType::Prismatic {
                axis: Vec3::new(0.3, -0.4, 0.866).normalize(),
            },
            JointType::Revolute {
                axis: Vec3::new(-0.6, 0.0, 0.8),
            },
        ],
        [
            JointType::Helical {
                axis: Vec3::new(0.0, 0.6, 0.8),
                pitch: 0.2,
            },
            JointType::Revolute { axis: Vec3::x() },
            JointType::Prismatic { axis: Vec3::z() },
            JointType::Revolute {
                axis: Vec3::new(0.48, 0.6, 0.64),
            },
        ],
    ];
    for (t, kinds) in branches.iter().enumerate() {
        let mut parent = root;
        for (k, kind) in kinds.iter().enumerate() {
            parent = b
                .add_joint(
                    Some(parent),
                    &format!("b{t}j{k}"),
                    *kind,
                    transform(&mut rng),
                    inertia(&mut rng),
                )
                .unwrap();
            let arm: Vec<f64> = (0..kind.nv()).map(|_| rng.uniform(0.0, 0.2)).collect();
            b.set_armature(parent, &arm).unwrap();
        }
    }
    b.build().unwrap()
}

/// The constraint sets: each kind and reference frame, to the world and between the two
/// branches' tips, with Baumgarte gains; and two sets of several constraints.
fn sets(model: &Model, rng: &mut Rng) -> Vec<(&'static str, Vec<ConstraintModel>)> {
    let id = |n: &str| model.joint_id(n).unwrap();
    let (tip0, tip1, mid0) = (id("b0j3"), id("b1j3"), id("b0j1"));
    let gains = Baumgarte { kp: 7.0, kd: 3.0 };
    let mut c = |kind: ConstraintKind,
                 j1: Option<JointId>,
                 j2: Option<JointId>,
                 rf: ReferenceFrame| {
        let mut m = match kind {
            ConstraintKind::Point => ConstraintModel::point(j1, transform(rng), j2, transform(rng)),
            _ => ConstraintModel::frame(j1, transform(rng), j2, transform(rng)),
        };
        m.reference = rf;
        m.baumgarte = gains;
        m
    };
    let (local, world) = (ReferenceFrame::Body, ReferenceFrame::WorldAligned);
    let (point, frame) = (ConstraintKind::Point, ConstraintKind::Frame);
    let mut coupling = ConstraintModel::joint_coordinate(
        id("b1j1"),
        Some(id("b0j3")),
        [0.1, 0.5, 0.2, 0.05, -0.02],
    );
    coupling.baumgarte = gains;
    vec![
        (
            "point, local, to the world",
            vec![c(point, Some(tip0), None, local)],
        ),
        (
            "point, world-aligned, to the world",
            vec![c(point, Some(tip0), None, world)],
        ),
        (
            "point, local, two bodies",
            vec![c(point, Some(tip0), Some(tip1), local)],
        ),
        (
            "point, world-aligned, two bodies",
            vec![c(point, Some(tip1), Some(tip0), world)],
        ),
        (
            "point, local, the world first",
            vec![c(point, None, Some(tip1), local)],
        ),
        (
            "frame, local, to the world",
            vec![c(frame, Some(tip1), None, local)],
        ),
        (
            "frame, world-aligned, to the world",
            vec![c(frame, Some(tip1), None, world)],
        ),
        (
            "frame, local, two bodies",
            vec![c(frame, Some(tip0), Some(tip1), local)],
        ),
        (
            "frame, world-aligned, two bodies",
            vec![c(frame, Some(tip0), Some(tip1), world)],
        ),
        ("joint coordinate", vec![coupling]),
        (
            "point, frame and a coupling",
            vec![
                c(point, Some(mid0), None, world),
                c(frame, Some(tip1), Some(tip0), local),
                ConstraintModel::joint_coordinate(id("b1j1"), None, [0.3, 0.0, 0.0, 0.0, 0.0]),
            ],
        ),
    ]
}

/// `‖x − y‖max / max(‖y‖max, 1)`.
fn rel(x: &DMatrix<f64>, y: &DMatrix<f64>) -> f64 {
    (x - y).amax() / y.amax().max(1.0)
}

/// Central differences of `f` (ddq or v⁺ stacked over λ or Λ) along `q ⊕ ±h e_k` (`along_q`)
/// or `x ± h e_k`.
fn fd(
    model: &Model,
    x: &[f64],
    along_q: bool,
    mut f: impl FnMut(&[f64]) -> DVector<f64>,
) -> DMatrix<f64> {
    let nv = model.nv();
    let cols: Vec<DVector<f64>> = (0..nv)
        .map(|k| {
            let mut e = vec![0.0; nv];
            e[k] = 1.0;
            let (plus, minus) = if along_q {
                (step(model, x, &e, H), step(model, x, &e, -H))
            } else {
                let mut p = x.to_vec();
                let mut m = x.to_vec();
                p[k] += H;
                m[k] -= H;
                (p, m)
            };
            (f(&plus) - f(&minus)) / (2.0 * H)
        })
        .collect();
    DMatrix::from_columns(&cols)
}

/// The entry where `x` and `y` differ most: `(row, column): x vs y`.
fn worst(x: &DMatrix<f64>, y: &DMatrix<f64>) -> String {
    let d = x - y;
    let (mut r, mut c) = (0, 0);
    for i in 0..d.nrows() {
        for j in 0..d.ncols() {
            if d[(i, j)].abs() > d[(r, c)].abs() {
                (r, c) = (i, j);
            }
        }
    }
    format!("({r}, {c}): {:.6} vs {:.6}", x[(r, c)], y[(r, c)])
}

fn stack(a: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    let mut s = DMatrix::zeros(a.nrows() + b.nrows(), a.ncols());
    s.rows_mut(0, a.nrows()).copy_from(a);
    s.rows_mut(a.nrows(), b.nrows()).copy_from(b);
    s
}

/// `∂q̈`, `∂λ` with respect to q, q̇ and τ equal central differences of `constraint_dynamics`.
#[test]
fn constraint_dynamics_derivatives_equal_finite_differences() {
    let model = two_branches();
    let mut rng = Rng::new(5);
    let settings = ProximalSettings::default();
    let mut failures = Vec::new();
    for (name, set) in sets(&model, &mut rng) {
        let mut data = Data::new(&model);
        let mut cd = ConstraintData::new(&model, &set).unwrap();
        let mut d = ConstraintDynamicsDerivatives::new(&model, &cd);
        for _ in 0..2 {
            let q = random_configuration(&model, &mut rng);
            let v: Vec<f64> = (0..model.nv()).map(|_| rng.uniform(-1.0, 1.0)).collect();
            let tau: Vec<f64> = (0..model.nv()).map(|_| rng.uniform(-3.0, 3.0)).collect();
            constraint_dynamics_derivatives(
                &model, &mut data, &mut cd, &q, &v, &tau, &settings, &mut d,
            )
            .unwrap_or_else(|e| panic!("{name}: {e}"));
            let m = cd.dim();
            let eval = |q: &[f64], v: &[f64], tau: &[f64]| {
                let mut data = Data::new(&model);
                let mut cd = ConstraintData::new(&model, &set).unwrap();
                constraint_dynamics(&model, &mut data, &mut cd, q, v, tau, &settings).unwrap();
                let mut x = DVector::zeros(model.nv() + m);
                x.rows_mut(0, model.nv()).copy_from(&cd.ddq);
                x.rows_mut(model.nv(), m).copy_from(&cd.lambda.rows(0, m));
                x
            };
            let by_q = fd(&model, &q, true, |q| eval(q, &v, &tau));
            let by_v = fd(&model, &v, false, |v| eval(&q, v, &tau));
            let by_tau = fd(&model, &tau, false, |t| eval(&q, &v, t));
            for (what, ours, theirs) in [
                ("q", stack(&d.ddq_dq, &d.dlambda_dq), by_q),
                ("v", stack(&d.ddq_dv, &d.dlambda_dv), by_v),
                ("tau", stack(&d.ddq_dtau, &d.dlambda_dtau), by_tau),
            ] {
                let e = rel(&ours, &theirs);
                if e >= TOLERANCE {
                    failures.push(format!(
                        "{name}: d/d{what} off by {e:.1e} at {}",
                        worst(&ours, &theirs)
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `∂q̇⁺`, `∂Λ` with respect to q and q̇⁻ equal central differences of `impulse_dynamics`, at
/// e = 0 and 0.5.
#[test]
fn impulse_dynamics_derivatives_equal_finite_differences() {
    let model = two_branches();
    let mut rng = Rng::new(8);
    let settings = ProximalSettings::default();
    let mut failures = Vec::new();
    for (name, set) in sets(&model, &mut rng) {
        let mut data = Data::new(&model);
        let mut cd = ConstraintData::new(&model, &set).unwrap();
        let mut d = ImpulseDynamicsDerivatives::new(&model, &cd);
        for e in [0.0, 0.5] {
            let q = random_configuration(&model, &mut rng);
            let v: Vec<f64> = (0..model.nv()).map(|_| rng.uniform(-1.0, 1.0)).collect();
            impulse_dynamics_derivatives(&model, &mut data, &mut cd, &q, &v, e, &settings, &mut d)
                .unwrap_or_else(|err| panic!("{name}: {err}"));
            let m = cd.dim();
            let eval = |q: &[f64], v: &[f64]| {
                let mut data = Data::new(&model);
                let mut cd = ConstraintData::new(&model, &set).unwrap();
                impulse_dynamics(&model, &mut data, &mut cd, q, v, e, &settings).unwrap();
                let mut x = DVector::zeros(model.nv() + m);
                x.rows_mut(0, model.nv()).copy_from(&cd.dq_plus);
                x.rows_mut(model.nv(), m).copy_from(&cd.impulse.rows(0, m));
                x
            };
            let by_q = fd(&model, &q, true, |q| eval(q, &v));
            let by_v = fd(&model, &v, false, |v| eval(&q, v));
            for (what, ours, theirs) in [
                ("q", stack(&d.dvplus_dq, &d.dimpulse_dq), by_q),
                ("v", stack(&d.dvplus_dv, &d.dimpulse_dv), by_v),
            ] {
                let err = rel(&ours, &theirs);
                if err >= TOLERANCE {
                    failures.push(format!(
                        "{name}, e = {e}: d/d{what} off by {err:.1e} at {}",
                        worst(&ours, &theirs)
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A redundant set (a point held twice, a frame held twice: consistent, of rank 9 in 18 rows)
/// under the proximal solver (`μ = 1e-6`, iterated to convergence): `∂q̈` equals central
/// differences, and `∂λ` is the derivative of the least-norm λ the iterations converge to.
#[test]
fn redundant_constraints_under_the_proximal_solver_equal_finite_differences() {
    let model = two_branches();
    let mut rng = Rng::new(11);
    let id = |n: &str| model.joint_id(n).unwrap();
    let (tip0, tip1) = (id("b0j3"), id("b1j3"));
    let at0 = transform(&mut rng);
    let at1 = transform(&mut rng);
    let mut held = ConstraintModel::point(Some(tip0), at0, None, transform(&mut rng));
    held.reference = ReferenceFrame::WorldAligned;
    let mut frame = ConstraintModel::frame(Some(tip1), at1, None, transform(&mut rng));
    frame.baumgarte = Baumgarte { kp: 4.0, kd: 2.0 };
    let sets = [
        ("a point twice", vec![held.clone(), held.clone()]),
        ("a frame twice", vec![frame.clone(), frame.clone()]),
        ("both twice", vec![held.clone(), held, frame.clone(), frame]),
    ];
    let settings = ProximalSettings::redundant();
    let mut failures = Vec::new();
    for (name, set) in &sets {
        let mut data = Data::new(&model);
        let mut cd = ConstraintData::new(&model, set).unwrap();
        let mut d = ConstraintDynamicsDerivatives::new(&model, &cd);
        for _ in 0..1 {
            let q = random_configuration(&model, &mut rng);
            let v: Vec<f64> = (0..model.nv()).map(|_| rng.uniform(-1.0, 1.0)).collect();
            let tau: Vec<f64> = (0..model.nv()).map(|_| rng.uniform(-3.0, 3.0)).collect();
            constraint_dynamics_derivatives(
                &model, &mut data, &mut cd, &q, &v, &tau, &settings, &mut d,
            )
            .unwrap();
            let m = cd.dim();
            let eval = |q: &[f64], v: &[f64], tau: &[f64]| {
                let mut data = Data::new(&model);
                let mut cd = ConstraintData::new(&model, set).unwrap();
                constraint_dynamics(&model, &mut data, &mut cd, q, v, tau, &settings).unwrap();
                let mut x = DVector::zeros(model.nv() + m);
                x.rows_mut(0, model.nv()).copy_from(&cd.ddq);
                // the least-norm λ shares each pair's force equally: the iterations' λ
                // projected so (their round-off drift along the pair's difference, b_⊥/μ per
                // iteration, is not the solution's, and central differences amplify it)
                for c in (0..set.len()).step_by(2) {
                    for (r1, r2) in cd.rows_of(c).zip(cd.rows_of(c + 1)) {
                        let mean = 0.5 * (cd.lambda[r1] + cd.lambda[r2]);
                        x[model.nv() + r1] = mean;
                        x[model.nv() + r2] = mean;
                    }
                }
                x
            };
            let by_q = fd(&model, &q, true, |q| eval(q, &v, &tau));
            let by_v = fd(&model, &v, false, |v| eval(&q, v, &tau));
            let by_tau = fd(&model, &tau, false, |t| eval(&q, &v, t));
            for (what, ours, theirs) in [
                ("q", stack(&d.ddq_dq, &d.dlambda_dq), by_q),
                ("v", stack(&d.ddq_dv, &d.dlambda_dv), by_v),
                ("tau", stack(&d.ddq_dtau, &d.dlambda_dtau), by_tau),
            ] {
                let e = rel(&ours, &theirs);
                let nv = model.nv();
                let e_ddq = rel(
                    &ours.rows(0, nv).into_owned(),
                    &theirs.rows(0, nv).into_owned(),
                );
                println!("{name}: d/d{what} {e:.1e} (q̈ alone {e_ddq:.1e})");
                if e >= TOLERANCE {
                    failures.push(format!(
                        "{name}: d/d{what} off by {e:.1e} at {}",
                        worst(&ours, &theirs)
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
