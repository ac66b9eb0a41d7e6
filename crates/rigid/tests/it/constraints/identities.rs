//! The equations each verb solves, checked on its own output: `M q̈ + c + g = τ + Jᵀ λ`,
//! `J q̈ + γ = 0`, the impact law, `γ = J̇ q̇` by central differences, the least-norm inverse
//! dynamics against a dense pseudo-inverse, and the errors.

use super::{fixtures, load, rel_err};
use nalgebra::{DMatrix, DVector};
use rigid::io::constraints::{parse_constraints, ConstraintFile};
use rigid::multibody::constraints::{
    constraint_dynamics, contact_inverse_dynamics, impulse_dynamics, jacobian_dynamics,
    jacobian_dynamics_from_terms, ConstraintData, ConstraintError, ConstraintKind, ConstraintModel,
    ProximalSettings,
};
use rigid::multibody::{
    crba, integrate, nonlinear_effects, Data, JointId, Model, MultibodyError, ReferenceFrame,
};
use rigid::spatial::{Transform, Vec3};
use serde_json::Value;

/// A fixture case: name, model, constraint file and states `(q, q̇, τ)` in rigid's layout.
type Case = (
    String,
    Model,
    ConstraintFile,
    Vec<(Vec<f64>, Vec<f64>, Vec<f64>)>,
);

/// Every fixture case as (name, model, constraint file), with a few states of rigid's layout
/// (the fixture's, made valid: the q of the fixture is Pinocchio's).
fn cases() -> Vec<Case> {
    let text = std::fs::read_to_string(fixtures().join("pinocchio.json")).expect("fixture");
    let doc: Value = serde_json::from_str(&text).expect("JSON");
    let nums = |v: &Value| -> Vec<f64> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    doc["cases"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| {
            let model = load(
                c["urdf"].as_str().unwrap(),
                c["floating"].as_bool().unwrap(),
            );
            let layout = rigid::interop::PinocchioLayout::new(&model);
            let file = parse_constraints(&c.to_string(), &model).unwrap();
            let states = c["states"]
                .as_array()
                .unwrap()
                .iter()
                .map(|s| {
                    let mut q = vec![0.0; model.nq()];
                    layout.q_from_pinocchio(&nums(&s["q"]), &mut q).unwrap();
                    let mut v = vec![0.0; model.nv()];
                    let mut tau = vec![0.0; model.nv()];
                    layout.permute_v(&nums(&s["v"]), &mut v);
                    layout.permute_v(&nums(&s["tau"]), &mut tau);
                    (q, v, tau)
                })
                .collect();
            (c["name"].as_str().unwrap().to_string(), model, file, states)
        })
        .collect()
}

/// `Jᵀ λ` (nv).
fn jt(cd: &ConstraintData, lambda: &DVector<f64>) -> DVector<f64> {
    let m = cd.dim();
    cd.jacobian.transpose() * lambda.rows(0, m)
}

/// At every fixture state: `M q̈ + c + g = τ + Jᵀ λ` and `J q̈ + γ = 0` (the proximal cases to
/// their reported residual), `M (q̇⁺ − q̇⁻) = Jᵀ Λ` and `J q̇⁺ = −e J q̇⁻` (iterated to
/// convergence), relative to the size of the terms.
#[test]
fn solutions_satisfy_the_equations_of_motion_and_the_constraints() {
    for (name, model, file, states) in cases() {
        let mut cd = ConstraintData::new(&model, &file.constraints).unwrap();
        let mut data = Data::new(&model);
        let converged = ProximalSettings {
            max_iter: 5000,
            absolute_accuracy: 1e-13,
            ..file.settings
        };
        for (q, v, tau) in &states {
            constraint_dynamics(&model, &mut data, &mut cd, q, v, tau, &file.settings).unwrap();
            let ddq = cd.ddq.clone();
            let lhs = crba(&model, &mut data, q).unwrap() * &ddq
                + nonlinear_effects(&model, &mut data, q, v).unwrap();
            let rhs = DVector::from_column_slice(tau) + jt(&cd, &cd.lambda);
            assert!(
                rel_err(lhs.as_slice(), rhs.as_slice()) < 1e-12,
                "{name}: dynamics"
            );
            let res = (&cd.jacobian * &ddq + &cd.gamma).amax();
            let scale = 1.0 + cd.gamma.amax();
            assert!(
                res <= 1e-11 * scale || (res - cd.stats.absolute_residual).abs() < 1e-9 * scale,
                "{name}: J q̈ + γ = {res:e}, solver says {:e}",
                cd.stats.absolute_residual
            );
            let e = file.restitution;
            let vp = impulse_dynamics(&model, &mut data, &mut cd, q, v, e, &converged)
                .unwrap()
                .clone();
            let dv = &vp - DVector::from_column_slice(v);
            let lhs = crba(&model, &mut data, q).unwrap() * dv;
            let impulse = cd.impulse.clone();
            assert!(
                rel_err(lhs.as_slice(), jt(&cd, &impulse).as_slice()) < 1e-12,
                "{name}"
            );
            let after = &cd.jacobian * &vp;
            let law: Vec<f64> = cd.velocity.iter().map(|x| -e * x).collect();
            assert!(
                rel_err(after.as_slice(), &law) < 1e-9,
                "{name}: J q̇⁺ = −e J q̇⁻"
            );
        }
    }
}

/// `jacobian_dynamics` on each fixture state's own `J` and `γ` (those `constraint_dynamics`
/// made): `M q̈ + c + g = τ + Jᵀ λ` and `J q̈ + γ = −damping λ`; where `J M⁻¹ Jᵀ` is regular,
/// `q̈` and `λ` equal the constraint models' converged solve; redundant rows are refused with
/// `damping = 0` and solved with `damping > 0`. Bad shapes and values are errors.
#[test]
fn jacobian_dynamics_meets_its_equations_and_the_constraint_models() {
    let mut regular = 0;
    for (name, model, file, states) in cases() {
        let mut cd = ConstraintData::new(&model, &file.constraints).unwrap();
        let mut data = Data::new(&model);
        let converged = ProximalSettings {
            max_iter: 5000,
            absolute_accuracy: 1e-14,
            ..file.settings
        };
        for (q, v, tau) in &states {
            constraint_dynamics(&model, &mut data, &mut cd, q, v, tau, &converged).unwrap();
            let (J, gamma) = (cd.jacobian.clone(), cd.gamma.clone());
            let exact = jacobian_dynamics(&model, &mut data, q, v, tau, &J, gamma.as_slice(), 0.0);
            let damping = match exact {
                Ok(lambda) => {
                    regular += 1;
                    assert!(
                        rel_err(data.ddq.as_slice(), cd.ddq.as_slice()) < 1e-9,
                        "{name}: q̈"
                    );
                    assert!(
                        rel_err(lambda.as_slice(), cd.lambda.rows(0, cd.dim()).as_slice()) < 1e-8,
                        "{name}: λ"
                    );
                    0.0
                }
                Err(ConstraintError::Singular) => 1e-6,
                Err(e) => panic!("{name}: {e}"),
            };
            let lambda =
                jacobian_dynamics(&model, &mut data, q, v, tau, &J, gamma.as_slice(), damping)
                    .unwrap();
            let ddq = data.ddq.clone();
            let lhs = crba(&model, &mut data, q).unwrap() * &ddq
                + nonlinear_effects(&model, &mut data, q, v).unwrap();
            let rhs = DVector::from_column_slice(tau) + J.transpose() * &lambda;
            assert!(
                rel_err(lhs.as_slice(), rhs.as_slice()) < 1e-11,
                "{name}: dynamics"
            );
            let res = &J * &ddq + &gamma + damping * &lambda;
            assert!(
                res.amax() < 1e-10 * (1.0 + gamma.amax()),
                "{name}: J q̈ + γ + damping λ = {:e}",
                res.amax()
            );
        }
    }
    assert!(regular > 0, "no fixture state with regular constraints");
    let (_, model, _, states) = cases().remove(0);
    let mut data = Data::new(&model);
    let (q, v, tau) = &states[0];
    let nv = model.nv();
    let bad = |J: DMatrix<f64>, gamma: &[f64], damping: f64, data: &mut Data, says: &str| {
        let e = jacobian_dynamics(&model, data, q, v, tau, &J, gamma, damping).unwrap_err();
        assert!(matches!(e, ConstraintError::BadJacobian(_)), "{e}");
        assert!(e.to_string().contains(says), "{e}");
    };
    let cols = format!("J has {} columns, the model nv = {nv}", nv + 1);
    bad(DMatrix::zeros(2, nv + 1), &[0.0; 2], 0.0, &mut data, &cols);
    let rows = "gamma has 3 entries for the 2 rows of J";
    bad(DMatrix::zeros(2, nv), &[0.0; 3], 0.0, &mut data, rows);
    let mut nan = DMatrix::zeros(2, nv);
    nan[(1, nv - 1)] = f64::NAN;
    let at = format!("J[1, {}] is not finite", nv - 1);
    bad(nan, &[0.0; 2], 0.0, &mut data, &at);
    bad(
        DMatrix::zeros(2, nv),
        &[0.0, f64::INFINITY],
        0.0,
        &mut data,
        "gamma[1]",
    );
    bad(
        DMatrix::zeros(2, nv),
        &[0.0; 2],
        -1.0,
        &mut data,
        "damping -1 must be",
    );
    // a workspace of another model, refused before any index is read
    let mut other = Data::new(&rigid::multibody::double_pendulum());
    let e =
        jacobian_dynamics_from_terms(&model, &mut other, tau, &DMatrix::zeros(1, nv), &[0.0], 0.0);
    assert!(matches!(e, Err(ConstraintError::Multibody(_))), "{e:?}");
    // two equal rows: redundant
    let row = DMatrix::from_fn(1, nv, |_, c| 1.0 + c as f64);
    let J = DMatrix::from_fn(2, nv, |_, c| row[(0, c)]);
    assert_eq!(
        jacobian_dynamics(&model, &mut data, q, v, tau, &J, &[0.0; 2], 0.0),
        Err(ConstraintError::Singular)
    );
}

/// `J q̇` at `q ⊕ ±h q̇`: the velocity `cdata.velocity` of a solve (regularised, so that any set
/// solves).
fn constraint_velocity(
    model: &Model,
    cd: &mut ConstraintData,
    q: &[f64],
    v: &[f64],
) -> DVector<f64> {
    let mut data = Data::new(model);
    let tau = vec![0.0; model.nv()];
    let s = ProximalSettings::new(1e-12, 1e-6, 1);
    constraint_dynamics(model, &mut data, cd, q, v, &tau, &s).unwrap();
    cd.velocity.clone()
}

/// `γ = J̇ q̇` (no Baumgarte term) equals the central difference of `J(q) q̇` along
/// `q ⊕ t q̇`, for every constraint of the fixtures: at any `q̇` for the point constraints in
/// world-aligned axes, the frame constraints in local axes and the joint coordinates (there `γ`
/// is the exact derivative of `J q̇`), and at a `q̇` with `J q̇ = 0` for every kind (Pinocchio's
/// point-local and frame-world-aligned drifts leave out terms that vanish there).
#[test]
fn drift_is_the_time_derivative_of_the_constraint_velocity() {
    let h = 1e-6;
    let mut checked = 0;
    for (name, model, file, states) in cases() {
        let bare: Vec<ConstraintModel> = file
            .constraints
            .iter()
            .map(|c| c.clone().with_baumgarte(0.0, 0.0))
            .collect();
        let exact_at_any_v = bare.iter().all(|c| {
            matches!(
                (c.kind, c.reference),
                (ConstraintKind::Point, ReferenceFrame::WorldAligned)
                    | (ConstraintKind::Frame, ReferenceFrame::Body)
            )
        });
        let mut cd = ConstraintData::new(&model, &bare).unwrap();
        let (q, v0, _) = &states[0];
        // a velocity with J q̇ = 0: a plastic impact, iterated to convergence
        let mut data = Data::new(&model);
        let s = ProximalSettings::new(1e-14, 1e-6, 10_000);
        let tangent = impulse_dynamics(&model, &mut data, &mut cd, q, v0, 0.0, &s)
            .unwrap()
            .as_slice()
            .to_vec();
        let mut velocities = vec![tangent];
        if exact_at_any_v {
            velocities.push(v0.clone());
        }
        for v in velocities {
            let s = ProximalSettings::new(1e-12, 1e-6, 1);
            let tau = vec![0.0; model.nv()];
            constraint_dynamics(&model, &mut data, &mut cd, q, &v, &tau, &s).unwrap();
            let gamma = cd.gamma.clone();
            let mut qp = q.clone();
            let mut qm = q.clone();
            integrate(&model, q, &v, h, &mut qp).unwrap();
            integrate(&model, q, &v, -h, &mut qm).unwrap();
            let fd = (constraint_velocity(&model, &mut cd, &qp, &v)
                - constraint_velocity(&model, &mut cd, &qm, &v))
                / (2.0 * h);
            let err = rel_err(gamma.as_slice(), fd.as_slice());
            assert!(
                err < 1e-6,
                "{name}: γ vs finite differences {err:e}\n{gamma}\n{fd}"
            );
            checked += 1;
        }
    }
    assert!(checked >= 13);
}

/// The inverse dynamics returns the minimum-norm `(τ_a, λ)` of `[S_aᵀ Jᵀ] (τ_a, λ) = τ_ID`:
/// equal to the dense pseudo-inverse solution (SVD), with `τ = 0` on the unactuated dofs. For a
/// `q̈` made by torques on the actuated dofs only, it is exact and gives `q̈` back through the
/// forward dynamics; for one made with forces on a free-flyer too, it is the least-squares
/// answer (exact when the contacts can take the base's place).
#[test]
fn inverse_dynamics_is_the_least_norm_solution() {
    for (name, model, file, states) in cases() {
        let mut cd = ConstraintData::new(&model, &file.constraints).unwrap();
        let mut data = Data::new(&model);
        let (q, v, tau) = &states[0];
        let nv = model.nv();
        let actuated: Vec<f64> = (0..nv)
            .map(|k| if cd.unactuated()[k] { 0.0 } else { tau[k] })
            .collect();
        // with forces on the base too, q̈ may be out of reach (two point contacts): least squares
        for (tau, exact) in [(&actuated, true), (tau, false)] {
            let s = &ProximalSettings {
                max_iter: 10_000,
                absolute_accuracy: 1e-13,
                ..file.settings
            };
            let ddq = constraint_dynamics(&model, &mut data, &mut cd, q, v, tau, s)
                .unwrap()
                .clone();
            let tau_inv =
                contact_inverse_dynamics(&model, &mut data, &mut cd, q, v, ddq.as_slice())
                    .unwrap()
                    .clone();
            let stats = cd.stats;
            assert!(stats.absolute_residual < 1e-9, "{name}: q̈ consistent");
            let lambda = cd.lambda.clone();
            // dense check: A = [S_aᵀ Jᵀ], x = A⁺ τ_ID
            let m = cd.dim();
            let tau_id = rigid::multibody::rnea(&model, &mut data, q, v, ddq.as_slice())
                .unwrap()
                .clone();
            let mut a = DMatrix::zeros(nv, nv + m);
            for k in 0..nv {
                if !cd.unactuated()[k] {
                    a[(k, k)] = 1.0;
                }
            }
            a.view_mut((0, nv), (nv, m))
                .copy_from(&cd.jacobian.transpose());
            let x = a.clone().pseudo_inverse(1e-10).unwrap() * &tau_id;
            assert!(
                rel_err(tau_inv.as_slice(), x.rows(0, nv).as_slice()) < 1e-9,
                "{name}: τ"
            );
            assert!(
                rel_err(lambda.as_slice(), x.rows(nv, m).as_slice()) < 1e-9,
                "{name}: λ"
            );
            let residual = (&a * &x - &tau_id).amax();
            assert!(
                (stats.dynamics_residual - residual).abs() < 1e-9 * (1.0 + residual),
                "{name}"
            );
            for k in 0..nv {
                assert!(!cd.unactuated()[k] || tau_inv[k] == 0.0);
            }
            if exact {
                assert!(stats.dynamics_residual < 1e-9, "{name}: {stats:?}");
                // forward again with the returned τ: the same q̈
                constraint_dynamics(&model, &mut data, &mut cd, q, v, tau_inv.as_slice(), s)
                    .unwrap();
                assert!(
                    rel_err(cd.ddq.as_slice(), ddq.as_slice()) < 1e-9,
                    "{name}: forward(inverse)"
                );
            }
        }
    }
}

/// Bad input is a typed error, never a panic or a NaN.
#[test]
fn bad_input_is_an_error() {
    let model = load("fourbar.urdf", false);
    let (coupler, rocker) = (
        model.joint_id("coupler_joint"),
        model.joint_id("rocker_joint"),
    );
    let tip = |x: f64| Transform::from_translation(Vec3::new(x, 0.0, 0.0));
    let loop_ = ConstraintModel::point(coupler, tip(0.8), rocker, tip(0.6));
    let q = [0.3, -0.2, 0.4];
    let z = [0.0; 3];
    let mut data = Data::new(&model);
    // the planar loop's 3D point constraint is redundant (no motion along y): μ = 0 refuses it
    let mut cd = ConstraintData::new(&model, std::slice::from_ref(&loop_)).unwrap();
    let exact = ProximalSettings::default();
    let err = constraint_dynamics(&model, &mut data, &mut cd, &q, &z, &z, &exact);
    assert_eq!(err.unwrap_err(), ConstraintError::Singular);
    let prox = ProximalSettings::new(1e-12, 1e-4, 1000);
    constraint_dynamics(&model, &mut data, &mut cd, &q, &z, &z, &prox).unwrap();
    assert!(cd.ddq.iter().all(|x| x.is_finite()) && cd.stats.converged);
    // an error no motion can correct (the rocker's tip 0.1 m off the plane, Baumgarte on): μ > 0
    // gives a finite q̈ and λ, says it did not converge, and q̈ is the least-squares one: the
    // residual left is the part no motion reaches, kp · 0.1 along y
    let off = ConstraintModel::point(
        coupler,
        tip(0.8),
        rocker,
        Transform::from_translation(Vec3::new(0.6, 0.1, 0.0)),
    )
    .with_baumgarte(10.0, 0.0);
    let mut cd_off = ConstraintData::new(&model, &[off]).unwrap();
    constraint_dynamics(&model, &mut data, &mut cd_off, &q, &z, &z, &prox).unwrap();
    assert!(!cd_off.stats.converged);
    assert!(
        (cd_off.stats.absolute_residual - 1.0).abs() < 1e-9,
        "{:?}",
        cd_off.stats
    );
    assert!(cd_off
        .ddq
        .iter()
        .chain(cd_off.lambda.iter())
        .all(|x| x.is_finite()));
    // inputs
    let nan = [0.3, f64::NAN, 0.4];
    let e = constraint_dynamics(&model, &mut data, &mut cd, &nan, &z, &z, &prox).unwrap_err();
    assert!(matches!(
        e,
        ConstraintError::Multibody(MultibodyError::NonFinite {
            what: "q",
            index: 1
        })
    ));
    let e = constraint_dynamics(&model, &mut data, &mut cd, &q, &z, &[0.0; 2], &prox).unwrap_err();
    assert!(
        matches!(e, ConstraintError::Multibody(MultibodyError::Dimension(_))),
        "{e}"
    );
    let bad = ProximalSettings { mu: -1.0, ..prox };
    let e = constraint_dynamics(&model, &mut data, &mut cd, &q, &z, &z, &bad).unwrap_err();
    assert_eq!(e, ConstraintError::BadSettings);
    let e = impulse_dynamics(&model, &mut data, &mut cd, &q, &z, 1.5, &prox).unwrap_err();
    assert_eq!(e, ConstraintError::BadRestitution(1.5));
    let other = load("closed_chain.urdf", false);
    let e = constraint_dynamics(
        &other,
        &mut Data::new(&other),
        &mut cd,
        &[0.0; 7],
        &[0.0; 7],
        &[0.0; 7],
        &prox,
    );
    assert_eq!(e.unwrap_err(), ConstraintError::DataMismatch);
    // constraints
    let check = |c: ConstraintModel| ConstraintData::new(&model, &[loop_.clone(), c]).unwrap_err();
    let mut skew = tip(0.1);
    skew.rotation[(0, 1)] = 0.5;
    assert_eq!(
        check(ConstraintModel::point(coupler, skew, None, tip(0.0))),
        ConstraintError::BadPlacement {
            index: 1,
            which: "placement1"
        }
    );
    assert_eq!(
        check(ConstraintModel::frame(None, tip(0.0), None, tip(1.0))),
        ConstraintError::SameBody { index: 1 }
    );
    assert_eq!(
        check(loop_.clone().with_reference(ReferenceFrame::Spatial)),
        ConstraintError::SpatialReference { index: 1 }
    );
    assert!(matches!(
        check(loop_.clone().with_baumgarte(f64::NAN, 1.0)),
        ConstraintError::BadGains { index: 1, .. }
    ));
    assert_eq!(
        check(ConstraintModel::point(
            Some(JointId(7)),
            tip(0.0),
            None,
            tip(0.0)
        )),
        ConstraintError::JointOutOfRange { index: 1, joint: 7 }
    );
    let floating = load("closed_chain.urdf", true);
    let e = ConstraintData::new(
        &floating,
        &[ConstraintModel::joint_coordinate(
            JointId(0),
            Some(JointId(1)),
            [0.0, 1.0, 0.0, 0.0, 0.0],
        )],
    );
    assert!(matches!(
        e.unwrap_err(),
        ConstraintError::NotOneDof {
            index: 0,
            nv: 6,
            ..
        }
    ));
    // names
    let e = ConstraintModel::on_joints(
        &model,
        ConstraintKind::Point,
        "elbow",
        tip(0.0),
        "universe",
        tip(0.0),
    );
    assert_eq!(
        e.unwrap_err().to_string(),
        "no joint named \"elbow\" (\"universe\" is the world)"
    );
    let e = ConstraintModel::on_frames(&model, ConstraintKind::Frame, "crank", "hand");
    assert_eq!(e.unwrap_err().to_string(), "no frame named \"hand\"");
}

/// The constraint file's messages name the constraint and the field.
#[test]
fn constraint_file_errors_name_the_field() {
    let model = load("fourbar.urdf", false);
    let msg = |text: &str| parse_constraints(text, &model).unwrap_err();
    assert_eq!(
        msg("{"),
        "malformed JSON: EOF while parsing an object at line 1 column 1"
    );
    assert_eq!(
        msg(r#"{"constraints": [{"joint1": "crank_joint"}]}"#),
        "constraint 0: \"type\" is missing"
    );
    assert_eq!(
        msg(r#"{"constraints": [{"type": "line", "joint1": "crank_joint"}]}"#),
        "constraint 0: \"type\" is \"line\" (expected \"point\", \"frame\" or \"joint_coordinate\")"
    );
    assert_eq!(
        msg(r#"{"constraints": [{"type": "point", "joint1": "crank_joint", "reference_frame": "world"}]}"#),
        "constraint 0: \"reference_frame\" is \"world\" (expected \"local\" or \"local_world_aligned\")"
    );
    assert_eq!(
        msg(
            r#"{"constraints": [{"type": "point", "joint1": "crank_joint", "placement1": {"rotation": [[1, 0, 0]]}}]}"#
        ),
        "constraint 0: \"placement1\": \"rotation\" is not a 3x3 array (row-major)"
    );
    assert_eq!(
        msg(r#"{"constraints": [], "restitution": 2}"#),
        "\"restitution\" 2 is not in [0, 1]"
    );
}
