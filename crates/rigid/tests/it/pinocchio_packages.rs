//! Every URDF file of whole robot-description packages, fixed and floating: what Pinocchio loads,
//! rigid loads (default inertia policy `warn`), and RNEA, CRBA and ABA agree at random states.
//!
//! `tests/pinocchio/packages.py PACKAGE` walks the package's folder for `*.urdf` (no hand-picked
//! list), loads each file with Pinocchio 4.1 (`buildModelFromUrdf`, with and without a free-flyer
//! root) and prints, per file, random states and Pinocchio's rnea, crba and aba in rigid's
//! conventions. This test loads the same file with [`load_urdf`], matches the joints by name
//! (rigid keeps the file's sibling order, urdfdom sorts siblings by name) and compares with
//! `‖x_rigid − x_pin‖∞ / max(‖x_pin‖∞, 1e-6) ≤ 1e-9`. ABA is compared where Pinocchio's `M` is
//! invertible (a moving subtree of zero mass makes it singular and ABA undefined: rigid must then
//! refuse, not return NaN silently).
//!
//! Every run does this on the checked-in fixture `tests/pinocchio/packages.json`
//! (`tests/pinocchio/gen_packages.py` writes it with `packages.py`: one state per file and base)
//! for a few files of each package, copied under `tests/fixtures/robots/` (not those of
//! icub-models and gym-ignition-models, whose copyleft licences keep them out of this
//! repository). `RIGID_CROSSCHECK=1` adds the live check that walks every file of the installed
//! packages (pinned in `scripts/requirements-test.txt`, installed by `scripts/test.sh`), run with
//! `RIGID_PYTHON` (or `python3`).

use rigid::io::urdf::{load_urdf, load_urdf_with, InertiaPolicy, UrdfOptions};
use rigid::multibody::{aba, crba, rnea, Data};
use serde_json::Value;

use crate::common;
use common::json::vec_of;
use common::reference::{self, index_maps, record_file, run_script, to_rigid};
use std::path::Path;

const TOLERANCE: f64 = 1e-9;
const FLOOR: f64 = 1e-6;

/// The references of one package, each a JSON record per (file, floating), with where they come
/// from: the checked-in fixture's (a few files; none for the packages not copied) and, with
/// `RIGID_CROSSCHECK=1`, the live one of `packages.py` (every file).
fn references(package: &str) -> Vec<(&'static str, Vec<Value>)> {
    let fixture: Vec<Value> = reference::fixture_lines("pinocchio/packages.json")
        .into_iter()
        .filter(|r| r["package"] == package)
        .collect();
    let mut out = Vec::new();
    if fixture.is_empty() {
        eprintln!("{package}: no file in tests/pinocchio/packages.json (live check only)");
    } else {
        out.push(("fixture", fixture));
    }
    if reference::live(&format!("{package}: Pinocchio live")) {
        let out_ = run_script(
            "pinocchio/packages.py",
            &[package, "--states", "3", "--seed", "11"],
        );
        let text = String::from_utf8(out_).expect("UTF-8");
        out.push((
            "live",
            text.lines()
                .map(|l| serde_json::from_str(l).expect("packages.py printed invalid JSON"))
                .collect(),
        ));
    }
    out
}

fn rel(a: &[f64], b: &[f64]) -> f64 {
    reference::rel(a, b, FLOOR)
}

/// The largest relative errors of one file: `(rnea, crba, aba or None)`, or why it failed.
fn compare_file(file: &Path, r: &Value) -> Result<(f64, f64, Option<f64>), String> {
    let floating = r["floating"].as_bool().unwrap();
    let model = load_urdf(file, floating).map_err(|e| format!("rigid refuses it: {e}"))?;
    let (pq, pv) = index_maps(&model, r["joints"].as_array().unwrap())?;
    let mut data = Data::new(&model);
    let (mut e_rnea, mut e_crba, mut e_aba) = (0.0f64, 0.0f64, None::<f64>);
    for s in r["states"].as_array().unwrap() {
        let q = to_rigid(&vec_of(&s["q"]), &pq);
        let v = to_rigid(&vec_of(&s["v"]), &pv);
        let a = to_rigid(&vec_of(&s["a"]), &pv);
        let tau = to_rigid(&vec_of(&s["tau"]), &pv);
        let back = |x: &[f64]| pv.iter().map(|&i| x[i]).collect::<Vec<f64>>();
        let x = rnea(&model, &mut data, &q, &v, &a).map_err(|e| format!("rnea: {e}"))?;
        e_rnea = e_rnea.max(rel(&back(x.as_slice()), &vec_of(&s["rnea"])));
        let m = crba(&model, &mut data, &q).map_err(|e| format!("crba: {e}"))?;
        let flat: Vec<f64> = pv
            .iter()
            .flat_map(|&i| pv.iter().map(move |&k| (i, k)))
            .map(|ik| m[ik])
            .collect();
        let m_ref: Vec<f64> = s["mass_matrix"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(vec_of)
            .collect();
        e_crba = e_crba.max(rel(&flat, &m_ref));
        match (&s["aba"], aba(&model, &mut data, &q, &v, &tau)) {
            (Value::Null, _) => {}
            (x_ref, Ok(x)) => {
                let e = rel(&back(x.as_slice()), &vec_of(x_ref));
                e_aba = Some(e_aba.unwrap_or(0.0).max(e));
            }
            (_, Err(e)) => return Err(format!("aba refused where Pinocchio's is defined: {e}")),
        }
    }
    Ok((e_rnea, e_crba, e_aba))
}

/// Every file under the three inertia policies: `strict` loads it or refuses it with an error
/// naming the link or joint and the line; `repair` loads it, with no non-physical body left.
fn policies(file: &Path, tag: &str, failures: &mut Vec<String>) {
    let with = |inertia| {
        let opts = UrdfOptions {
            inertia,
            ..UrdfOptions::default()
        };
        load_urdf_with(file, &opts)
    };
    if let Err(e) = with(InertiaPolicy::Strict) {
        let msg = e.to_string();
        let named = msg.contains("link \"") || msg.contains("joint \"") || msg.contains("robot");
        if e.line().is_none() || !named {
            failures.push(format!(
                "{tag}: strict error without a line or a name: {msg}"
            ));
        }
    }
    let pinocchio_loads = load_urdf(file, false).is_ok();
    match with(InertiaPolicy::Repair) {
        Ok((model, _)) => {
            let bad: Vec<String> = model
                .inertia_issues()
                .iter()
                .filter(|(_, e)| !matches!(e, rigid::error::InertiaError::BadMass { .. }))
                .map(|(j, e)| format!("{}: {e}", model.joints()[j.0].name))
                .collect();
            if !bad.is_empty() {
                failures.push(format!("{tag}: repair left {bad:?}"));
            }
        }
        Err(e) if pinocchio_loads => failures.push(format!("{tag}: repair refuses it: {e}")),
        Err(_) => {}
    }
}

fn check_package(package: &str) {
    for (source, records) in references(package) {
        check_records(package, source, &records);
    }
}

fn check_records(package: &str, source: &str, records: &[Value]) {
    let (mut compared, mut failures) = (0, Vec::new());
    for r in records {
        let name = r["file"].as_str().unwrap();
        let file = record_file(package, name);
        let floating = r["floating"].as_bool().unwrap();
        let short = name.rsplit("/robots/").next().unwrap_or(name);
        let tag = format!("{short}{}", if floating { " (floating)" } else { "" });
        if !floating {
            policies(&file, &tag, &mut failures);
        }
        if let Some(why) = r.get("refused") {
            // Pinocchio refuses it: rigid may load it or give a clear error; it must not panic.
            let rigid = load_urdf(&file, floating)
                .map(|_| "loads")
                .unwrap_or("refuses");
            eprintln!(
                "{tag}: Pinocchio refuses ({}); rigid {rigid}",
                why.as_str().unwrap()
            );
            continue;
        }
        match compare_file(&file, r) {
            Ok((er, ec, ea)) => {
                compared += 1;
                let aba = ea.map_or("undefined (singular M)".into(), |e| format!("{e:.1e}"));
                eprintln!("{tag}: rnea {er:.1e}, crba {ec:.1e}, aba {aba}");
                if er > TOLERANCE || ec > TOLERANCE || ea.is_some_and(|e| e > TOLERANCE) {
                    failures.push(format!("{tag}: rnea {er:.2e}, crba {ec:.2e}, aba {aba}"));
                }
            }
            Err(e) => failures.push(format!("{tag}: {e}")),
        }
    }
    eprintln!(
        "{package} ({source}): {} files x (fixed, floating), {compared} compared with Pinocchio",
        records.len() / 2
    );
    assert!(compared > 0, "{package} ({source}): nothing compared");
    assert!(
        failures.is_empty(),
        "{package} ({source}): {} of {} disagree with Pinocchio (tolerance {TOLERANCE:e}):\n{}",
        failures.len(),
        records.len(),
        failures.join("\n")
    );
}

#[test]
fn every_example_robot_data_urdf_loads_and_agrees_with_pinocchio() {
    check_package("example-robot-data");
}

#[test]
fn every_icub_models_urdf_loads_and_agrees_with_pinocchio() {
    check_package("icub-models");
}

#[test]
fn every_upkie_description_urdf_loads_and_agrees_with_pinocchio() {
    check_package("upkie-description");
}

#[test]
fn every_jvrc_description_urdf_loads_and_agrees_with_pinocchio() {
    check_package("jvrc-description");
}

#[test]
fn every_gym_ignition_models_urdf_loads_and_agrees_with_pinocchio() {
    check_package("gym-ignition-models");
}

#[test]
fn every_airo_models_urdf_loads_and_agrees_with_pinocchio() {
    check_package("airo-models");
}

#[test]
fn every_cookie_description_urdf_loads_and_agrees_with_pinocchio() {
    check_package("cookie-description");
}
