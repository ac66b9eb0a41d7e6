//! `rigid step MODEL --cases C --ground H [--derivatives] --json`: a URDF crate sliding on the
//! ground; the derivatives with respect to τ against central differences of the command's own
//! steps (cases τ ± ε e_k in one run), the readable summary, and named errors.

use serde_json::Value;
use std::process::Command;

const CRATE: &str = r#"<robot name="crate">
  <link name="crate">
    <inertial><mass value="2"/><inertia ixx="0.0167" iyy="0.0283" izz="0.0417" ixy="0" ixz="0" iyz="0"/></inertial>
    <collision><geometry><box size="0.4 0.3 0.1"/></geometry></collision>
  </link>
</robot>"#;

fn temp_file(tag: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("rigid-cli-step-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(tag);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

fn rigid(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(args)
        .output()
        .expect("run rigid")
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn step_derivatives_with_respect_to_tau_equal_central_differences_of_the_command() {
    let urdf = temp_file("crate.urdf", CRATE);
    // sliding along x at 1 m/s, 3 µm above the ground (the step closes the gap)
    let q = "[0, 0, 0.050003, 0, 0, 0, 1]";
    let v = "[0, 0, 0, 1.0, 0, 0]";
    let tau = [0.5, -0.3, 0.2, 1.0, 2.0, 0.0];
    let eps = 1e-4;
    let mut cases = vec![format!(r#"{{"q": {q}, "v": {v}, "tau": {tau:?}}}"#)];
    for k in 0..6 {
        for s in [1.0, -1.0] {
            let mut t = tau;
            t[k] += s * eps;
            cases.push(format!(r#"{{"q": {q}, "v": {v}, "tau": {t:?}}}"#));
        }
    }
    let file = temp_file(
        "cases.json",
        &format!(r#"{{"cases": [{}]}}"#, cases.join(", ")),
    );
    let args = [
        "step",
        &urdf,
        "--floating",
        "--cases",
        &file,
        "--ground",
        "0",
        "--friction",
    ];
    let out = rigid(&[&args[..], &["0.3", "--json"]].concat());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let all: Value = serde_json::from_slice(&out.stdout).unwrap();
    let results = all["results"].as_array().unwrap();
    assert_eq!(results.len(), 13);
    let one = temp_file("one.json", &format!(r#"{{"cases": [{}]}}"#, cases[0]));
    let d_args = [
        "step",
        &urdf,
        "--floating",
        "--cases",
        &one,
        "--ground",
        "0",
        "--friction",
    ];
    let out = rigid(&[&d_args[..], &["0.3", "--derivatives", "--json"]].concat());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: Value = serde_json::from_slice(&out.stdout).unwrap();
    let r = &doc["results"][0];
    let d = &r["step_derivatives"];
    assert_eq!(numbers(&r["v_next"]), numbers(&results[0]["v_next"]));
    let modes: Vec<&str> = d["modes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_str().unwrap())
        .collect();
    assert_eq!(
        modes.iter().filter(|m| **m == "sliding").count(),
        4,
        "{modes:?}"
    );
    for k in 0..6 {
        let (p, m) = (&results[1 + 2 * k], &results[2 + 2 * k]);
        let (vp, vm) = (numbers(&p["v_next"]), numbers(&m["v_next"]));
        for row in 0..6 {
            let fd = (vp[row] - vm[row]) / (2.0 * eps);
            let ours = d["dv_dtau"][row][k].as_f64().unwrap();
            assert!(
                (ours - fd).abs() < 1e-6,
                "dv_dtau[{row}][{k}]: {ours} vs {fd}"
            );
        }
    }
    // the readable summary, and errors named
    let out = rigid(&[&d_args[..], &["0.3", "--derivatives"]].concat());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("modes = [\"sliding\"") && text.contains("|dv_dtau|max"),
        "{text}"
    );
    let out = rigid(&["step", &urdf, "--floating", "--cases", &one]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("nothing can touch"));
    let bad = temp_file("bad.json", r#"{"cases": [{"q": [0, 0, 1]}]}"#);
    let out = rigid(&[
        "step",
        &urdf,
        "--floating",
        "--cases",
        &bad,
        "--ground",
        "0",
    ]);
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("case 0"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_case_that_does_not_continue_the_last_one_starts_cold() {
    // a crate 3 µm above the ground falling at 0.5 m/s with restitution 0.5: its gap closes in
    // the step (an impact the next step would rebound from, were it its continuation); the same
    // case twice gives the same result twice
    let urdf = temp_file("crate2.urdf", CRATE);
    let case = r#"{"q": [0, 0, 0.050003, 0, 0, 0, 1], "v": [0, 0, 0, 0, 0, -0.5]}"#;
    let file = temp_file("twice.json", &format!(r#"{{"cases": [{case}, {case}]}}"#));
    let out = rigid(&[
        "step",
        &urdf,
        "--floating",
        "--cases",
        &file,
        "--ground",
        "0",
        "--restitution",
        "0.5",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: Value = serde_json::from_slice(&out.stdout).unwrap();
    let r = doc["results"].as_array().unwrap();
    assert_eq!(numbers(&r[0]["v_next"]), numbers(&r[1]["v_next"]));
    assert_eq!(numbers(&r[0]["q_next"]), numbers(&r[1]["q_next"]));
}
