//! Agreement with Pinocchio on the robots of example-robot-data.
//!
//! For each robot (and for `tests/pinocchio/all_joints.urdf`, every URDF joint type rigid
//! imports), `tests/pinocchio/reference.py` (Pinocchio 4.1 and example-robot-data 6.0 from
//! PyPI, `scripts/requirements-test.txt`) loads the URDF with `pin.buildModelFromUrdf`, draws
//! random states with a fixed seed and prints Pinocchio's results already translated into rigid's
//! conventions (angular-first free-flyer velocities, one angle per continuous joint, symmetric
//! `M`). This test loads the same URDF with [`rigid::io::urdf::load_urdf`], matches the joints by
//! name (urdfdom orders siblings by name, rigid by file order) and evaluates the same states.
//!
//! Agreement is measured per quantity as `‖x_rigid - x_pin‖∞ / max(‖x_pin‖∞, 1e-6)` (the
//! infinity norm over the whole vector or matrix, SI units, with a 1e-6 floor so that a quantity
//! that is zero compares absolutely) and must be below 1e-9 for rnea, crba, aba, `M⁻¹`
//! (`computeMinverse`, symmetrised like `M`), nle, gravity, kinetic and potential energy, CoM,
//! total mass and every joint placement.
//!
//! Every run compares with the checked-in fixture `tests/pinocchio/reference.json`
//! (`tests/pinocchio/gen_reference.py` writes it with `reference.py`: 2 states per robot, the
//! first with the derivatives; TALOS one state without), loading the URDF files checked in under
//! `tests/fixtures/robots/`, to the same tolerance. `RIGID_CROSSCHECK=1` adds the live check:
//! `reference.py` run with `RIGID_PYTHON` (or `python3`) with `pin` and `example-robot-data`
//! (`bash scripts/test.sh` installs them), 8 states per robot, on the installed package's files,
//! and the fixture regenerated and compared with the committed one.

use nalgebra::DMatrix;
use rigid::io::urdf::load_urdf;
use rigid::multibody::{
    aba, center_of_mass, compute_minverse, crba, forward_kinematics_q, gravity_torques,
    kinetic_energy, nonlinear_effects, potential_energy, rnea, Data, Model,
};
use serde_json::Value;

use crate::common;
use common::json::vec_of;
use common::reference::{self, run_script, to_rigid};
use std::path::PathBuf;

/// Random states per robot of the live check.
const STATES: usize = 8;
/// Largest relative error accepted.
const TOLERANCE: f64 = 1e-9;
/// Absolute floor of the scale in the relative error.
const FLOOR: f64 = 1e-6;

/// Pinocchio's references for one robot: the checked-in fixture's and, with `RIGID_CROSSCHECK=1`,
/// the live one of `reference.py`; each with where it comes from.
fn references(robot: &str) -> Vec<(&'static str, Value)> {
    let fixture = reference::fixture("pinocchio/reference.json");
    let r = fixture["robots"][robot].clone();
    assert!(
        r.is_object(),
        "tests/pinocchio/reference.json has no {robot}: run tests/pinocchio/gen_reference.py"
    );
    let mut out = vec![("fixture", r)];
    if reference::live(&format!("{robot}: Pinocchio live")) {
        let states = STATES.to_string();
        let live = run_script(
            "pinocchio/reference.py",
            &[robot, "--states", &states, "--seed", "7", "--derivatives"],
        );
        let live = serde_json::from_slice(&live).expect("reference.py printed invalid JSON");
        out.push(("live", live));
    }
    out
}

/// The URDF file of a reference: the checked-in copy for the fixture's (a path under
/// example-robot-data's `robots/` folder, or `local:NAME` beside `tests/pinocchio/`), the
/// installed package's for a live one (an absolute path).
fn urdf(r: &Value) -> PathBuf {
    reference::record_file("example-robot-data", r["urdf"].as_str().unwrap())
}

fn mat_of(v: &Value) -> Vec<Vec<f64>> {
    v.as_array().expect("array").iter().map(vec_of).collect()
}

/// `‖a - b‖∞ / max(‖b‖∞, FLOOR)`.
fn rel(a: &[f64], b: &[f64]) -> f64 {
    reference::rel(a, b, FLOOR)
}

/// Maximum relative errors, one per quantity, over all states.
#[derive(Default)]
struct Errors(Vec<(&'static str, f64)>);

impl Errors {
    fn record(&mut self, what: &'static str, e: f64) {
        let e = if e.is_nan() { f64::INFINITY } else { e };
        match self.0.iter_mut().find(|(w, _)| *w == what) {
            Some((_, m)) => *m = m.max(e),
            None => self.0.push((what, e)),
        }
    }
}

/// Index maps from the reference's layout (Pinocchio's joint order) into rigid's: `(q, v)`.
fn index_maps(model: &Model, joints: &[Value]) -> (Vec<usize>, Vec<usize>) {
    reference::index_maps(model, joints).unwrap_or_else(|e| panic!("{e}"))
}

/// `x` (rigid's layout) in the reference's layout.
fn from_rigid(x: &[f64], map: &[usize]) -> Vec<f64> {
    map.iter().map(|&r| x[r]).collect()
}

fn compare(robot: &str) {
    for (source, r) in references(robot) {
        compare_with(robot, source, &r);
    }
}

fn compare_with(robot: &str, source: &str, r: &Value) {
    let start = std::time::Instant::now();
    let floating = r["floating"].as_bool().unwrap();
    let model = load_urdf(urdf(r), floating).unwrap_or_else(|e| panic!("{robot}: {e}"));
    let mut data = Data::new(&model);
    let joints = r["joints"].as_array().unwrap();
    let (pq, pv) = index_maps(&model, joints);
    let mut err = Errors::default();
    let g = model.gravity();
    err.record("gravity", rel(&[g.x, g.y, g.z], &vec_of(&r["gravity"])));
    let m_ref = r["total_mass"].as_f64().unwrap();
    err.record("total_mass", rel(&[model.total_mass()], &[m_ref]));

    for s in r["states"].as_array().unwrap() {
        let q = to_rigid(&vec_of(&s["q"]), &pq);
        let v = to_rigid(&vec_of(&s["v"]), &pv);
        let a = to_rigid(&vec_of(&s["a"]), &pv);
        let tau = to_rigid(&vec_of(&s["tau"]), &pv);
        let back = |x: &nalgebra::DVector<f64>| from_rigid(x.as_slice(), &pv);

        let x = back(rnea(&model, &mut data, &q, &v, &a).unwrap());
        err.record("rnea", rel(&x, &vec_of(&s["rnea"])));
        let m: DMatrix<f64> = crba(&model, &mut data, &q).unwrap().clone();
        let m_ref = mat_of(&s["mass_matrix"]);
        let pvr = &pv;
        // a matrix of rigid's layout, row by row in the reference's layout
        let flat = |m: &DMatrix<f64>| -> Vec<f64> {
            (0..pv.len())
                .flat_map(|i| pvr.iter().map(move |&c| (pvr[i], c)))
                .map(|(r, c)| m[(r, c)])
                .collect()
        };
        err.record("crba", rel(&flat(&m), &m_ref.concat()));
        let minv = compute_minverse(&model, &mut data, &q).unwrap().clone();
        let minv_ref = mat_of(&s["minverse"]);
        err.record("minverse", rel(&flat(&minv), &minv_ref.concat()));
        let x = back(aba(&model, &mut data, &q, &v, &tau).unwrap());
        err.record("aba", rel(&x, &vec_of(&s["aba"])));
        let x = back(nonlinear_effects(&model, &mut data, &q, &v).unwrap());
        err.record("nle", rel(&x, &vec_of(&s["nonlinear_effects"])));
        let x = back(gravity_torques(&model, &mut data, &q).unwrap());
        err.record("gravity_torques", rel(&x, &vec_of(&s["gravity_torques"])));
        let ke = kinetic_energy(&model, &mut data, &q, &v).unwrap();
        err.record(
            "kinetic_energy",
            rel(&[ke], &[s["kinetic_energy"].as_f64().unwrap()]),
        );
        let pe = potential_energy(&model, &mut data, &q).unwrap();
        let pe_ref = s["potential_energy"].as_f64().unwrap();
        err.record("potential_energy", rel(&[pe], &[pe_ref]));
        let c = center_of_mass(&model, &mut data, &q).unwrap();
        err.record("com", rel(&[c.x, c.y, c.z], &vec_of(&s["com"])));

        forward_kinematics_q(&model, &mut data, &q).unwrap();
        let placements = s["placements"].as_object().unwrap();
        assert_eq!(placements.len(), model.joints().len());
        for (name, p) in placements {
            let id = model.joint_id(name).unwrap();
            let t = &data.placements[id.0];
            let mut ours: Vec<f64> = t.translation.iter().copied().collect();
            ours.extend(
                (0..3)
                    .flat_map(|i| (0..3).map(move |k| (i, k)))
                    .map(|ik| t.rotation[ik]),
            );
            let mut theirs = vec_of(&p["translation"]);
            theirs.extend(mat_of(&p["rotation"]).concat());
            err.record("placements", rel(&ours, &theirs));
        }
    }

    let line: Vec<String> = err.0.iter().map(|(w, e)| format!("{w} {e:.1e}")).collect();
    eprintln!(
        "{robot} ({source}; nq {}, nv {}, {} states, rigid {:.0} ms): max relative error: {}",
        model.nq(),
        model.nv(),
        r["states"].as_array().unwrap().len(),
        start.elapsed().as_secs_f64() * 1e3,
        line.join(", ")
    );
    for (what, e) in &err.0 {
        assert!(
            *e <= TOLERANCE,
            "{robot} ({source}): {what} differs from Pinocchio by {e:.3e} relative (tolerance \
             {TOLERANCE:e})"
        );
    }
}

#[test]
fn ur5_agrees_with_pinocchio() {
    compare("ur5");
}

#[test]
fn panda_agrees_with_pinocchio() {
    compare("panda");
}

#[test]
fn solo12_free_flyer_agrees_with_pinocchio() {
    compare("solo12");
}

#[test]
fn anymal_free_flyer_agrees_with_pinocchio() {
    compare("anymal");
}

#[test]
fn talos_free_flyer_agrees_with_pinocchio() {
    compare("talos");
}

#[test]
fn double_pendulum_agrees_with_pinocchio() {
    compare("double_pendulum");
}

#[test]
fn every_urdf_joint_type_agrees_with_pinocchio() {
    compare("all_joints");
}

#[test]
fn every_urdf_joint_type_on_a_free_flyer_agrees_with_pinocchio() {
    compare("all_joints_floating");
}

// --- analytical derivatives (issue 12) ---

/// A matrix of rigid's layout, row by row in the reference's layout (`pv` maps the reference's
/// velocity indices to rigid's).
fn flat_in_reference_layout(m: &DMatrix<f64>, pv: &[usize]) -> Vec<f64> {
    pv.iter()
        .flat_map(|&r| pv.iter().map(move |&c| m[(r, c)]))
        .collect()
}

/// Pinocchio's `computeRNEADerivatives` (with random external wrenches in the joint frames) and
/// `computeABADerivatives` against [`rnea_derivatives_with_external`] and [`aba_derivatives`],
/// on the states of [`compare`] that carry them: every matrix to 1e-9 relative (`rel`). Pinocchio's
/// derivatives are along its `integrate` (`q * exp(v)`, a free-flyer's `v` linear first, a
/// continuous joint's tangent the angle), rigid's along `q ⊕ δ`: the same columns once the
/// free-flyer halves are swapped, which `reference.py` does.
fn compare_derivatives(robot: &str) {
    for (source, r) in references(robot) {
        compare_derivatives_with(robot, source, &r);
    }
}

fn compare_derivatives_with(robot: &str, source: &str, r: &Value) {
    use rigid::multibody::{aba_derivatives, rnea_derivatives_with_external};
    use rigid::spatial::Wrench;
    let model = load_urdf(urdf(r), r["floating"].as_bool().unwrap())
        .unwrap_or_else(|e| panic!("{robot}: {e}"));
    let mut data = Data::new(&model);
    let joints = r["joints"].as_array().unwrap();
    let (pq, pv) = index_maps(&model, joints);
    let mut err = Errors::default();
    let mut compared = 0;
    // the fixture keeps the derivatives of its first state only (none for TALOS)
    for s in r["states"].as_array().unwrap() {
        let d = &s["derivatives"];
        if d.is_null() {
            continue;
        }
        compared += 1;
        let q = to_rigid(&vec_of(&s["q"]), &pq);
        let v = to_rigid(&vec_of(&s["v"]), &pv);
        let a = to_rigid(&vec_of(&s["a"]), &pv);
        let tau = to_rigid(&vec_of(&s["tau"]), &pv);
        let mut fext = vec![Wrench::zero(); model.njoints()];
        for (rj, f) in joints.iter().zip(d["fext"].as_array().unwrap()) {
            let id = model.joint_id(rj["name"].as_str().unwrap()).unwrap();
            fext[id.0] = Wrench::from_slice(&vec_of(f));
        }
        let reference = |key: &str| mat_of(&d[key]).concat();
        let x = rnea_derivatives_with_external(&model, &mut data, &q, &v, &a, &fext).unwrap();
        err.record(
            "dtau_dq",
            rel(
                &flat_in_reference_layout(x.dtau_dq, &pv),
                &reference("dtau_dq"),
            ),
        );
        err.record(
            "dtau_dv",
            rel(
                &flat_in_reference_layout(x.dtau_dv, &pv),
                &reference("dtau_dv"),
            ),
        );
        let x = aba_derivatives(&model, &mut data, &q, &v, &tau).unwrap();
        err.record(
            "dqdd_dq",
            rel(
                &flat_in_reference_layout(x.dqdd_dq, &pv),
                &reference("dqdd_dq"),
            ),
        );
        err.record(
            "dqdd_dv",
            rel(
                &flat_in_reference_layout(x.dqdd_dv, &pv),
                &reference("dqdd_dv"),
            ),
        );
        err.record(
            "dqdd_dtau",
            rel(
                &flat_in_reference_layout(x.dqdd_dtau, &pv),
                &reference("dqdd_dtau"),
            ),
        );
    }
    if compared == 0 {
        eprintln!("{robot} derivatives ({source}): none (the fixture keeps none for {robot})");
        return;
    }
    let line: Vec<String> = err.0.iter().map(|(w, e)| format!("{w} {e:.1e}")).collect();
    eprintln!(
        "{robot} derivatives ({source}, {compared} states): max relative error: {}",
        line.join(", ")
    );
    for (what, e) in &err.0 {
        assert!(
            *e <= TOLERANCE,
            "{robot} ({source}): {what} differs from Pinocchio by {e:.3e} relative (tolerance \
             {TOLERANCE:e})"
        );
    }
}

#[test]
fn derivatives_agree_with_pinocchio_on_every_robot_and_joint_type() {
    for robot in [
        "ur5",
        "panda",
        "solo12",
        "anymal",
        "talos",
        "double_pendulum",
        "all_joints",
        "all_joints_floating",
    ] {
        compare_derivatives(robot);
    }
}

/// The checked-in fixtures of the Pinocchio cross-checks (`tests/pinocchio/*.json`) are what
/// their generators write today with the pinned Pinocchio, to the tests' tolerance (live only:
/// it runs `gen_reference.py --check` and `gen_packages.py --check`).
#[test]
fn the_pinocchio_fixtures_are_what_their_generators_write() {
    if !reference::live("the Pinocchio fixtures' generators") {
        return;
    }
    reference::check_generator("pinocchio/gen_reference.py");
    reference::check_generator("pinocchio/gen_packages.py");
}
