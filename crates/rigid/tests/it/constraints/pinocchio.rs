//! rigid against Pinocchio 4.1's `constraintDynamics` and `impulseDynamics` on Solo-12, ANYmal,
//! TALOS and two loops: the fixture `tests/fixtures/constraints/pinocchio.json` (written by
//! `gen_pinocchio.py` beside it), and with `RIGID_CROSSCHECK=1` the generator run live
//! (`RIGID_PYTHON`, default `python3`, with `pin` 4.1).

use super::{fixtures, load, rel_err};
use crate::common::reference;
use rigid::interop::PinocchioLayout;
use rigid::io::constraints::parse_constraints;
use rigid::multibody::constraints::{
    constraint_dynamics, impulse_dynamics, ConstraintData, ConstraintKind, ConstraintModel,
    ProximalSettings,
};
use rigid::multibody::{forward_kinematics_qv, Data, Model, ReferenceFrame};
use rigid::spatial::Vec3;
use serde_json::Value;

/// The largest relative errors of one case over its states.
#[derive(Debug, Default)]
struct Errors {
    ddq: f64,
    lambda: f64,
    dq_plus: f64,
    impulse: f64,
    /// Pinocchio's impulse law for constraints between two moving bodies
    /// (`J q̇⁺ = J q̇⁻ − (1 + e) J_1 q̇⁻ − μ Λ`), checked on its own numbers.
    pinocchio_law: f64,
    states: usize,
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

/// rigid's `λ` in Pinocchio's layout: each frame constraint's wrench `(m, f)` as `(f, m)`.
fn lambda_to_pinocchio(constraints: &[ConstraintModel], lambda: &[f64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(lambda.len());
    let mut r = 0;
    for c in constraints {
        let x = &lambda[r..r + c.dim()];
        match c.kind {
            ConstraintKind::Frame => out.extend(x[3..].iter().chain(&x[..3])),
            _ => out.extend_from_slice(x),
        }
        r += c.dim();
    }
    out
}

/// `J_1 q̇`: the velocity of c1 on joint1's body alone (its body twist `[Ad_{P⁻¹}] V_i`: the
/// linear part for a point; in c1's axes, or rotated by `R_1`).
fn body1_velocity(
    model: &Model,
    constraints: &[ConstraintModel],
    q: &[f64],
    v: &[f64],
) -> Vec<f64> {
    let mut data = Data::new(model);
    forward_kinematics_qv(model, &mut data, q, v).expect("kinematics");
    let mut out = vec![];
    for c in constraints {
        let i = c.joint1.expect("a body").0;
        let Vc = c.placement1.inv_act_twist(&data.velocities[i]);
        let R = (data.placements[i] * c.placement1).rotation;
        let world = c.reference == ReferenceFrame::WorldAligned;
        let axes = |x: Vec3| if world { R * x } else { x };
        match c.kind {
            ConstraintKind::Point => out.extend(axes(Vc.v).iter()),
            ConstraintKind::Frame => out.extend(axes(Vc.w).iter().chain(axes(Vc.v).iter())),
            ConstraintKind::JointCoordinate { .. } => unreachable!("not in the fixture"),
        }
    }
    out
}

fn check_case(case: &Value) -> Errors {
    let urdf = case["urdf"].as_str().expect("urdf");
    let model = load(urdf, case["floating"].as_bool().expect("floating"));
    let layout = PinocchioLayout::new(&model);
    let file = parse_constraints(&case.to_string(), &model).expect("a valid constraint file");
    let (constraints, settings, e) = (&file.constraints, &file.settings, file.restitution);
    let two_bodies = constraints.iter().any(|c| c.joint2.is_some());
    let mut cd = ConstraintData::new(&model, constraints).expect("valid constraints");
    let mut data = Data::new(&model);
    let mut err = Errors::default();
    let nv = model.nv();
    let from_pin = |x: &[f64]| {
        let mut y = vec![0.0; nv];
        layout.permute_v(x, &mut y);
        y
    };
    for s in case["states"].as_array().expect("states") {
        let mut q = vec![0.0; model.nq()];
        layout
            .q_from_pinocchio(&numbers(&s["q"]), &mut q)
            .expect("q");
        let (v, tau) = (from_pin(&numbers(&s["v"])), from_pin(&numbers(&s["tau"])));
        let ddq = constraint_dynamics(&model, &mut data, &mut cd, &q, &v, &tau, settings)
            .expect("constraint dynamics")
            .clone();
        err.ddq = err
            .ddq
            .max(rel_err(&from_pin(ddq.as_slice()), &numbers(&s["ddq"])));
        let lambda = lambda_to_pinocchio(constraints, cd.lambda.as_slice());
        err.lambda = err.lambda.max(rel_err(&lambda, &numbers(&s["lambda"])));
        // Pinocchio's impulseDynamics does one (regularised, when μ > 0) solve
        let once = ProximalSettings {
            max_iter: 1,
            ..*settings
        };
        let dq_plus = impulse_dynamics(&model, &mut data, &mut cd, &q, &v, e, &once)
            .expect("impulse dynamics")
            .clone();
        if two_bodies {
            // Pinocchio solves (K + μ I) Λ = −(1 + e) J_1 q̇⁻ once, so that
            // J q̇⁺ = J q̇⁻ − (1 + e) J_1 q̇⁻ − μ Λ: check that on its q̇⁺ and Λ
            let jv = cd.velocity.clone();
            let j1v = body1_velocity(&model, constraints, &q, &v);
            let vp = from_pin(&numbers(&s["dq_plus"]));
            let impulse = lambda_to_pinocchio(constraints, &numbers(&s["impulse"]));
            let target: Vec<f64> = (0..cd.dim())
                .map(|r| jv[r] - (1.0 + e) * j1v[r] - settings.mu * impulse[r])
                .collect();
            let jvp: Vec<f64> = (0..cd.dim())
                .map(|r| (0..nv).map(|k| cd.jacobian[(r, k)] * vp[k]).sum())
                .collect();
            err.pinocchio_law = err.pinocchio_law.max(rel_err(&jvp, &target));
        } else {
            err.dq_plus = err.dq_plus.max(rel_err(
                &from_pin(dq_plus.as_slice()),
                &numbers(&s["dq_plus"]),
            ));
            let impulse = lambda_to_pinocchio(constraints, cd.impulse.as_slice());
            err.impulse = err.impulse.max(rel_err(&impulse, &numbers(&s["impulse"])));
        }
        err.states += 1;
    }
    err
}

/// Checks every case of a fixture document, prints the table, and fails above 1e-9 (relative
/// to `max(1, ‖reference‖∞)`).
fn check_document(doc: &Value) {
    let mut worst: f64 = 0.0;
    eprintln!("case | states | q̈ | λ | q̇⁺ | impulse | Pinocchio's two-body impulse law");
    for case in doc["cases"].as_array().expect("cases") {
        let e = check_case(case);
        let name = case["name"].as_str().expect("name");
        eprintln!(
            "{name} | {} | {:.1e} | {:.1e} | {:.1e} | {:.1e} | {:.1e}",
            e.states, e.ddq, e.lambda, e.dq_plus, e.impulse, e.pinocchio_law
        );
        for (what, x) in [
            ("ddq", e.ddq),
            ("lambda", e.lambda),
            ("dq_plus", e.dq_plus),
            ("impulse", e.impulse),
            ("Pinocchio's impulse law", e.pinocchio_law),
        ] {
            assert!(x <= 1e-9, "{name}: {what} differs from Pinocchio by {x:e}");
            worst = worst.max(x);
        }
    }
    eprintln!("worst relative difference: {worst:.1e}");
}

#[test]
fn constraint_and_impulse_dynamics_match_pinocchio_fixture() {
    let text = std::fs::read_to_string(fixtures().join("pinocchio.json")).expect("fixture");
    check_document(&serde_json::from_str(&text).expect("JSON"));
}

/// The generator run now (Pinocchio installed, `RIGID_CROSSCHECK=1`): the same comparison on
/// fresh numbers, and the checked-in fixture equal to them (`gen_pinocchio.py --check`).
#[test]
fn constraint_and_impulse_dynamics_match_live_pinocchio() {
    if !reference::live("constraint and impulse dynamics against live Pinocchio") {
        return;
    }
    let script = "fixtures/constraints/gen_pinocchio.py";
    check_document(
        &serde_json::from_slice(&reference::run_script(script, &["--print"])).expect("JSON"),
    );
    reference::check_generator(script);
}

/// The fixture's constraints at the feet equal the ones made from the frames' names
/// ([`ConstraintModel::on_frames`]): the named-frame constructor finds Pinocchio's frames.
#[test]
fn named_frames_give_pinocchio_placements() {
    let text = std::fs::read_to_string(fixtures().join("pinocchio.json")).expect("fixture");
    let doc: Value = serde_json::from_str(&text).expect("JSON");
    let case = &doc["cases"][0];
    let model = load(case["urdf"].as_str().unwrap(), true);
    let file = parse_constraints(&case.to_string(), &model).unwrap();
    for (c, foot) in file
        .constraints
        .iter()
        .zip(["FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT"])
    {
        let f =
            ConstraintModel::on_frames(&model, ConstraintKind::Point, foot, "universe").unwrap();
        assert_eq!(f.joint1, c.joint1, "{foot}");
        let d = f.placement1.inverse() * c.placement1;
        assert!(d.is_identity(1e-12), "{foot}: {d:?}");
        assert_eq!(
            (f.joint2, f.placement2),
            (None, rigid::spatial::Transform::identity())
        );
    }
}
