//! `rigid doctor`: the JSON report's keys and verdicts on a fixture with known faults, `--fix`
//! (only the bad `<inertial>` blocks change, each with a comment, and the result is clean), the
//! `--inertia` policies on the same file, and the real files the issue names (TIAGo's antenna,
//! Romeo's body: example-robot-data's files, checked in under
//! `crates/rigid/tests/fixtures/robots/` without their meshes).

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

fn fixture(name: &str) -> String {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name);
    p.to_str().unwrap().to_string()
}

fn rigid(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(args)
        .output()
        .expect("run rigid")
}

fn report(path: &str) -> Value {
    let out = rigid(&["doctor", path, "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn body<'a>(r: &'a Value, name: &str) -> &'a Value {
    r["bodies"]
        .as_array()
        .unwrap()
        .iter()
        .find(|b| b["name"] == name)
        .unwrap_or_else(|| panic!("no body {name}"))
}

#[test]
fn doctor_reports_each_body_with_a_cause_and_a_repair() {
    let r = report(&fixture("doctor_arm.urdf"));
    let upper = body(&r, "upper");
    for key in ["name", "status", "findings", "likely_cause", "repair"] {
        assert!(upper.get(key).is_some(), "key {key} missing: {upper}");
    }
    assert_eq!(upper["status"], "ok");
    assert!(upper["repair"].is_null() && upper["likely_cause"].is_null());

    let lower = body(&r, "lower");
    assert_eq!(lower["status"], "warning");
    assert_eq!(lower["likely_cause"], "units_grams");
    let codes: Vec<&str> = lower["findings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["code"].as_str().unwrap())
        .collect();
    assert!(codes.contains(&"density"), "{codes:?}");
    assert!((lower["repair"]["mass"].as_f64().unwrap() - 2.0).abs() < 1e-12);

    let hand = body(&r, "hand");
    assert_eq!(hand["status"], "invalid");
    assert_eq!(hand["line"], 31);
    let rep = &hand["repair"];
    assert_eq!(rep["mass"], 0.5);
    // the repair is a physical inertia: principal moments satisfy the triangle inequality
    let i: Vec<Vec<f64>> = serde_json::from_value(rep["inertia"].clone()).unwrap();
    let (a, b, c) = (i[0][0], i[1][1], i[2][2]);
    assert!(a + b >= c && a + c >= b && b + c >= a, "{i:?}");
}

#[test]
fn fix_replaces_only_the_bad_inertial_blocks() {
    let src = fixture("doctor_arm.urdf");
    let dir = std::env::temp_dir().join(format!("rigid-doctor-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("fixed.urdf");
    let run = rigid(&["doctor", &src, "--fix", out.to_str().unwrap()]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let before = std::fs::read_to_string(&src).unwrap();
    let after = std::fs::read_to_string(&out).unwrap();
    assert!(after.contains("<!-- rigid doctor: units_grams:"), "{after}");
    assert!(after.contains("<!-- rigid doctor: digit_typo:"), "{after}");
    // the valid link's block and everything outside the inertial blocks is unchanged
    let upper = |t: &str| {
        t[t.find("<link name=\"upper\">").unwrap()..t.find("<!-- the same box").unwrap()]
            .to_string()
    };
    assert_eq!(upper(&before), upper(&after));
    assert!(after.ends_with(&before[before.find("<joint name=\"shoulder\"").unwrap()..]));
    // no temporary file left beside the output
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert_eq!(left.len(), 1, "{left:?}");
    // the fixed file is clean
    let r = report(out.to_str().unwrap());
    for b in r["bodies"].as_array().unwrap() {
        assert_eq!(b["status"], "ok", "{b}");
    }
}

#[test]
fn inertia_policies_on_the_command_line() {
    let src = fixture("doctor_arm.urdf");
    // strict: the triangle violation is a warning (as before), so the file loads
    let out = rigid(&["model", &src, "--inertia", "strict"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("link \"hand\"") && text.contains("triangle"),
        "{text}"
    );
    // repair: the hand's inertia is replaced, and the model is physical
    let out = rigid(&["model", &src, "--inertia", "repair"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("repaired"), "{text}");
    assert!(
        text.contains("inertias of the 3 moving bodies: all physical"),
        "{text}"
    );
    let out = rigid(&["model", &src, "--inertia", "sloppy"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("strict, warn or repair"));
}

#[test]
fn the_issues_real_files_tiago_antenna_and_romeo_body() {
    let erd = crate::common::example_robot_data();
    for (file, link, line) in [
        (
            "tiago_description/robots/tiago.urdf",
            "base_antenna_left_link",
            176,
        ),
        (
            "tiago_description/robots/tiago_dual.urdf",
            "base_antenna_left_link",
            176,
        ),
        (
            "tiago_description/robots/tiago_no_hand.urdf",
            "base_antenna_left_link",
            177,
        ),
        ("romeo_description/urdf/romeo_laas_small.urdf", "body", 328),
    ] {
        let path = erd.join(file);
        let path = path.to_str().unwrap();
        // the default policy loads it (as Pinocchio does); strict refuses it, naming link and line
        assert!(rigid(&["model", path]).status.success());
        let out = rigid(&["model", path, "--inertia", "strict"]);
        assert_eq!(out.status.code(), Some(2), "{file}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.starts_with("error:")
                && err.contains(&format!("link \"{link}\""))
                && err.contains(&format!("line {line}"))
                && !err.contains("panicked"),
            "{err}"
        );
        // the doctor gives a cause (or `unknown` with what rules each out) and a valid repair
        let r = report(path);
        let b = body(&r, link);
        assert_eq!(b["status"], "invalid");
        let cause = b["likely_cause"].as_str().unwrap();
        let why = b["explanation"].as_str().unwrap();
        if cause == "unknown" {
            for c in [
                "units_grams",
                "units_millimetres",
                "about_link_origin",
                "digit_typo",
            ] {
                assert!(why.contains(c), "{why}");
            }
        }
        assert!(b["repair"].is_object(), "{b}");
        eprintln!("{file} {link}: {cause}: {why}");
    }
}
