//! `rigid bench`: the JSON contract (keys never renamed), the table, and clean failures.

use std::process::{Command, Output};

fn rigid(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(args)
        .output()
        .unwrap()
}

#[test]
fn bench_json_has_the_contract_keys() {
    let out = rigid(&[
        "bench",
        "puma560",
        "--json",
        "--repetitions",
        "1",
        "--states",
        "10",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["model"], "puma560");
    assert_eq!(v["nq"], 6);
    assert_eq!(v["nv"], 6);
    let t = v["ns_per_call"].as_object().unwrap();
    for key in [
        "forward_kinematics",
        "jacobians",
        "rnea",
        "gravity",
        "nonlinear_effects",
        "crba",
        "aba",
        "minverse",
    ] {
        let x = t[key].as_f64().unwrap_or_else(|| panic!("{key} missing"));
        assert!(x > 0.0 && x.is_finite(), "{key} = {x}");
    }
}

#[test]
fn bench_table_names_every_algorithm() {
    let out = rigid(&[
        "bench",
        "double_pendulum",
        "--repetitions",
        "1",
        "--states",
        "5",
    ]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    for key in ["rnea", "crba", "aba", "minverse", "jacobians"] {
        assert!(text.contains(key), "{text}");
    }
}

#[test]
fn bench_unknown_model_fails_cleanly() {
    let out = rigid(&["bench", "no_such_robot", "--json"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no_such_robot"));
}
