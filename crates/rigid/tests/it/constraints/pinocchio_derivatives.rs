//! rigid's derivatives of the constrained and impulse dynamics against Pinocchio 4.1's
//! `computeConstraintDynamicsDerivatives` and `computeImpulseDynamicsDerivatives` on Solo-12 (4,
//! 3 and 2 feet), ANYmal, TALOS (two 6D soles), a spatial closed chain and a Panda with a 6D
//! loop, with Baumgarte gains, e = 0 and 0.5: the fixture
//! `tests/fixtures/constraints/pinocchio_derivatives.json` (written by
//! `gen_pinocchio_derivatives.py`), and with `RIGID_CROSSCHECK=1` the generator run live.
//!
//! Where Pinocchio's analytical `∂q̈/∂q`, `∂λ/∂q` are not the derivatives of its own
//! `constraintDynamics` (a point constraint between two moving bodies, a world-aligned frame
//! constraint between two moving bodies: off by O(1) from its own central differences), rigid's
//! are compared with those central differences. The impulse derivatives are compared for
//! constraints to the world only: between two moving bodies Pinocchio's impact law is another
//! one (see `impulse_dynamics`).

use super::load;
use crate::common::reference;
use nalgebra::DMatrix;
use rigid::interop::PinocchioLayout;
use rigid::io::constraints::parse_constraints;
use rigid::multibody::constraints::{
    constraint_dynamics_derivatives, impulse_dynamics_derivatives, ConstraintData,
    ConstraintDynamicsDerivatives, ImpulseDynamicsDerivatives,
};
use rigid::multibody::Data;
use serde_json::Value;

fn matrix(v: &Value) -> DMatrix<f64> {
    let rows: Vec<Vec<f64>> = v
        .as_array()
        .expect("rows")
        .iter()
        .map(|r| {
            r.as_array()
                .expect("a row")
                .iter()
                .map(|x| x.as_f64().expect("a number"))
                .collect()
        })
        .collect();
    DMatrix::from_fn(rows.len(), rows[0].len(), |i, j| rows[i][j])
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

/// `‖x − y‖max / max(1, ‖y‖max)`.
fn rel(x: &DMatrix<f64>, y: &DMatrix<f64>) -> f64 {
    assert_eq!(x.shape(), y.shape());
    (x - y).amax() / y.amax().max(1.0)
}

/// Checks one case; returns the worst error against Pinocchio's analytical derivatives and
/// against its central differences (0 where not used).
fn check_case(case: &Value) -> (f64, f64) {
    let name = case["name"].as_str().expect("name");
    let model = load(
        case["urdf"].as_str().expect("urdf"),
        case["floating"].as_bool().expect("floating"),
    );
    let l = PinocchioLayout::new(&model);
    let file = parse_constraints(&case.to_string(), &model).expect("a constraint file");
    let mut cd = ConstraintData::new(&model, &file.constraints).expect("constraints");
    let mut data = Data::new(&model);
    let nv = model.nv();
    let mut q = vec![0.0; model.nq()];
    l.q_from_pinocchio(&numbers(&case["q"]), &mut q).expect("q");
    let from_pin = |x: &[f64]| {
        let mut y = vec![0.0; nv];
        l.permute_v(x, &mut y);
        y
    };
    let (v, tau) = (
        from_pin(&numbers(&case["v"])),
        from_pin(&numbers(&case["tau"])),
    );
    // rigid's matrices in Pinocchio's layout: columns as velocities, rows as velocities or as
    // constraint rows (6D forces linear first)
    let to_pin = |x: &DMatrix<f64>, cd: &ConstraintData, rows_v: bool| {
        let mut y = DMatrix::zeros(x.nrows(), nv);
        for r in 0..x.nrows() {
            let row: Vec<f64> = x.row(r).iter().copied().collect();
            let mut p = vec![0.0; nv];
            l.permute_v(&row, &mut p);
            y.row_mut(r).iter_mut().zip(p).for_each(|(a, b)| *a = b);
        }
        let z = y.clone();
        for k in 0..nv {
            let c = z.column(k).as_slice().to_vec();
            let mut p = c.clone();
            if rows_v {
                l.permute_v(&c, &mut p);
            } else {
                cd.force_first(&c, &mut p);
            }
            y.column_mut(k).copy_from_slice(&p);
        }
        y
    };
    let mut d = ConstraintDynamicsDerivatives::new(&model, &cd);
    constraint_dynamics_derivatives(
        &model,
        &mut data,
        &mut cd,
        &q,
        &v,
        &tau,
        &file.settings,
        &mut d,
    )
    .expect("derivatives");
    let pin = &case["pinocchio"];
    let pinocchio_right = case["pinocchio_fd_error"].as_f64().expect("error") < 1e-6;
    let (mut worst, mut worst_fd) = (0.0f64, 0.0f64);
    let check = |what: &str, ours: DMatrix<f64>, theirs: DMatrix<f64>, tol: f64| {
        let e = rel(&ours, &theirs);
        eprintln!("  {name} {what}: {e:.1e}");
        assert!(e <= tol, "{name}: {what} differs by {e:.1e}");
        e
    };
    for (what, ours, by_q, rows_v) in [
        ("ddq_dq", &d.ddq_dq, true, true),
        ("ddq_dv", &d.ddq_dv, false, true),
        ("ddq_dtau", &d.ddq_dtau, false, true),
        ("dlambda_dq", &d.dlambda_dq, true, false),
        ("dlambda_dv", &d.dlambda_dv, false, false),
        ("dlambda_dtau", &d.dlambda_dtau, false, false),
    ] {
        if by_q && !pinocchio_right {
            continue;
        }
        worst = worst.max(check(
            what,
            to_pin(ours, &cd, rows_v),
            matrix(&pin[what]),
            1e-9,
        ));
    }
    if !pinocchio_right {
        // [∂q̈/∂q; ∂λ/∂q] against central differences of Pinocchio's constraintDynamics
        let fd = matrix(&case["central_differences_dq"]);
        let mut ours = DMatrix::zeros(nv + d.dlambda_dq.nrows(), nv);
        ours.rows_mut(0, nv)
            .copy_from(&to_pin(&d.ddq_dq, &cd, true));
        ours.rows_mut(nv, d.dlambda_dq.nrows())
            .copy_from(&to_pin(&d.dlambda_dq, &cd, false));
        worst_fd = worst_fd.max(check(
            "d(ddq, lambda)/dq vs central differences",
            ours,
            fd,
            1e-6,
        ));
    }
    if file.constraints.iter().all(|c| c.joint2.is_none()) {
        let mut d = ImpulseDynamicsDerivatives::new(&model, &cd);
        impulse_dynamics_derivatives(
            &model,
            &mut data,
            &mut cd,
            &q,
            &v,
            file.restitution,
            &file.settings,
            &mut d,
        )
        .expect("impulse derivatives");
        for (what, ours, rows_v) in [
            ("dvplus_dq", &d.dvplus_dq, true),
            ("dvplus_dv", &d.dvplus_dv, true),
            ("dimpulse_dq", &d.dimpulse_dq, false),
            ("dimpulse_dv", &d.dimpulse_dv, false),
        ] {
            worst = worst.max(check(
                what,
                to_pin(ours, &cd, rows_v),
                matrix(&pin[what]),
                1e-9,
            ));
        }
    }
    (worst, worst_fd)
}

fn check_document(doc: &Value) {
    let (mut worst, mut worst_fd) = (0.0f64, 0.0f64);
    for case in doc["cases"].as_array().expect("cases") {
        let (a, b) = check_case(case);
        worst = worst.max(a);
        worst_fd = worst_fd.max(b);
    }
    eprintln!(
        "worst relative difference: {worst:.1e} from Pinocchio's derivatives, {worst_fd:.1e} \
         from the central differences of Pinocchio's constraintDynamics"
    );
}

#[test]
fn constraint_and_impulse_derivatives_match_pinocchio_fixture() {
    let text = std::fs::read_to_string(super::fixtures().join("pinocchio_derivatives.json"))
        .expect("fixture");
    check_document(&serde_json::from_str(&text).expect("JSON"));
}

/// The generator run now (Pinocchio installed, `RIGID_CROSSCHECK=1`): the same comparison on
/// fresh numbers, and the checked-in fixture equal to them.
#[test]
fn constraint_and_impulse_derivatives_match_live_pinocchio() {
    if !reference::live("constrained-dynamics derivatives against live Pinocchio") {
        return;
    }
    let script = "fixtures/constraints/gen_pinocchio_derivatives.py";
    check_document(
        &serde_json::from_slice(&reference::run_script(script, &["--print"])).expect("JSON"),
    );
    reference::check_generator(script);
}
