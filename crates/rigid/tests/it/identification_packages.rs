//! The joint-torque regressor on every URDF file of example-robot-data, fixed and floating:
//! `Y(q, v, a) π = rnea(q, v, a) − armature ∘ a` to 1e-12 relative, and `Y` equal to Pinocchio
//! 4.1's `computeJointTorqueRegressor` to 1e-9.
//!
//! `tests/pinocchio/regressor.py PACKAGE` walks the package's folder for `*.urdf` (no hand-picked
//! list, as `packages.py`), and prints, per file and random state, Pinocchio's regressor with its
//! rows in rigid's order (free-flyer rows angular first; Pinocchio's are linear first) and its
//! columns by Pinocchio's joints, which urdfdom orders by name among siblings: the columns are
//! matched to rigid's bodies by joint name. The parameter order inside a body is the same
//! (`toDynamicParameters`).
//!
//! Every run does this on the checked-in fixture `tests/pinocchio/regressor.json`
//! (`tests/pinocchio/gen_packages.py` writes it with `regressor.py`: the UR5, the Panda and the
//! double pendulum, one state each, fixed and floating, from the copies under
//! `tests/fixtures/robots/`); `RIGID_CROSSCHECK=1` adds the live check on every file of the
//! installed package, run with `RIGID_PYTHON` (or `python3`).

use nalgebra::{DMatrix, DVector};
use rigid::identification::{model_parameters, Regressor};
use rigid::io::urdf::load_urdf;
use rigid::multibody::{rnea, Data};
use serde_json::Value;

use crate::common;
use common::json::vec_of;
use common::reference::{self, index_maps, json_lines, record_file, to_rigid};

fn rel(a: &[f64], b: &[f64]) -> f64 {
    common::reference::rel(a, b, 1e-6)
}

/// `(‖Yπ + armature ∘ a − rnea‖ / ‖rnea‖, Pinocchio's Y vs rigid's)`, the worst over the states.
fn compare_file(r: &Value) -> Result<(f64, f64), String> {
    let file = record_file("example-robot-data", r["file"].as_str().unwrap());
    let floating = r["floating"].as_bool().unwrap();
    let model = load_urdf(file, floating).map_err(|e| format!("rigid refuses it: {e}"))?;
    let joints = r["joints"].as_array().unwrap();
    let (pq, pv) = index_maps(&model, joints)?;
    // Pinocchio's joint k (its order) is rigid's body col_of[k]
    let col_of: Vec<usize> = joints
        .iter()
        .map(|j| model.joint_id(j["name"].as_str().unwrap()).unwrap().0)
        .collect();
    let pi = model_parameters(&model);
    // Pinocchio's parameters of its joint k are rigid's of the same body
    for (k, p) in r["parameters"].as_array().unwrap().iter().enumerate() {
        let b = col_of[k];
        let e = rel(&pi.as_slice()[10 * b..10 * b + 10], &vec_of(p));
        if e > 1e-12 {
            return Err(format!(
                "body {}: parameters differ by {e:e}",
                joints[k]["name"]
            ));
        }
    }
    let mut reg = Regressor::new(&model);
    let mut data = Data::new(&model);
    let (mut e_rnea, mut e_pin) = (0.0f64, 0.0f64);
    for s in r["states"].as_array().unwrap() {
        let q = to_rigid(&vec_of(&s["q"]), &pq);
        let v = to_rigid(&vec_of(&s["v"]), &pv);
        let a = to_rigid(&vec_of(&s["a"]), &pv);
        let y = reg
            .compute(&model, &q, &v, &a)
            .map_err(|e| e.to_string())?
            .clone();
        let tau = rnea(&model, &mut data, &q, &v, &a).map_err(|e| e.to_string())?;
        let arm = DVector::from_iterator(
            model.nv(),
            (0..model.nv()).map(|k| model.armature()[k] * a[k]),
        );
        let e = (&y * &pi + arm - tau).norm() / tau.norm().max(1e-300);
        e_rnea = e_rnea.max(e);
        // Pinocchio's Y: rows already in rigid's layout order of Pinocchio's joints
        let rows: Vec<Vec<f64>> = s["regressor"]
            .as_array()
            .unwrap()
            .iter()
            .map(vec_of)
            .collect();
        let mut y_pin = DMatrix::zeros(model.nv(), y.ncols());
        for (i, row) in rows.iter().enumerate() {
            for (k, &b) in col_of.iter().enumerate() {
                for c in 0..10 {
                    y_pin[(pv[i], 10 * b + c)] = row[10 * k + c];
                }
            }
        }
        e_pin = e_pin.max(rel(y.as_slice(), y_pin.as_slice()));
    }
    Ok((e_rnea, e_pin))
}

#[test]
fn regressor_of_every_example_robot_data_urdf_is_rnea_and_pinocchio() {
    check_records(
        "fixture",
        &reference::fixture_lines("pinocchio/regressor.json"),
    );
    if reference::live("the regressor against Pinocchio live") {
        let records = json_lines(
            "pinocchio/regressor.py",
            &["example-robot-data", "--states", "2", "--seed", "3"],
        );
        check_records("live", &records);
    }
}

fn check_records(source: &str, records: &[Value]) {
    let (mut compared, mut failures) = (0, Vec::new());
    let (mut worst_rnea, mut worst_pin) = (0.0f64, 0.0f64);
    let mut loadable = 0;
    for r in records {
        let file = r["file"].as_str().unwrap();
        let floating = r["floating"].as_bool().unwrap();
        let short = file.rsplit("/robots/").next().unwrap_or(file);
        let tag = format!("{short}{}", if floating { " (floating)" } else { "" });
        if r.get("refused").is_some() {
            continue;
        }
        loadable += 1;
        match compare_file(r) {
            Ok((er, ep)) => {
                compared += 1;
                worst_rnea = worst_rnea.max(er);
                worst_pin = worst_pin.max(ep);
                if er > 1e-12 || ep > 1e-9 {
                    failures.push(format!(
                        "{tag}: Yπ vs rnea {er:.2e}, Y vs Pinocchio {ep:.2e}"
                    ));
                }
            }
            Err(e) => failures.push(format!("{tag}: {e}")),
        }
    }
    eprintln!(
        "example-robot-data ({source}): {compared} models (files x fixed/floating); worst Yπ vs \
         rnea {worst_rnea:.2e}, worst Y vs Pinocchio {worst_pin:.2e}"
    );
    if source == "live" {
        // the whole package
        assert!(compared > 50, "only {compared} models compared");
        assert!(failures.is_empty(), "{}", failures.join("\n"));
    } else {
        assert!(failures.is_empty(), "{}", failures.join("\n"));
        // the fixture's few files: every one
        assert!(
            compared > 0 && compared == loadable,
            "{compared} of {loadable} models compared"
        );
    }
}
