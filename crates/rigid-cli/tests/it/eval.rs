//! The `rigid eval` and `rigid model` command-line contract (docs/conventions.md): exact JSON keys,
//! hand-checkable values, and named errors with a non-zero exit on bad input.

use serde_json::Value;
use std::collections::BTreeSet;
use std::path::PathBuf;
use std::process::{Command, Output};

fn fixture(name: &str) -> String {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name);
    p.to_str().unwrap().to_string()
}

/// Writes `text` to a fresh file in the temporary directory and returns its path.
fn temp_file(tag: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("rigid-cli-eval-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(tag);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

fn rigid(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(args)
        .output()
        .expect("run rigid")
}

fn eval_json(model: &str, cases: &str, extra: &[&str]) -> Value {
    let mut args = vec!["eval", model, "--cases", cases, "--json"];
    args.extend_from_slice(extra);
    let out = rigid(&args);
    assert!(
        out.status.success(),
        "rigid {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("valid JSON")
}

fn keys(v: &Value) -> BTreeSet<&str> {
    v.as_object().unwrap().keys().map(String::as_str).collect()
}

fn set<'a>(k: &[&'a str]) -> BTreeSet<&'a str> {
    k.iter().copied().collect()
}

/// Runs a command expected to fail; returns its stderr.
fn fails(args: &[&str]) -> String {
    let out = rigid(args);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(!out.status.success(), "rigid {args:?} should fail");
    assert!(!err.contains("panicked"), "rigid {args:?} panicked: {err}");
    err
}

#[test]
fn eval_json_has_the_contract_keys_and_the_pendulum_values() {
    let q: f64 = 0.7;
    let cases = temp_file(
        "pendulum.json",
        &format!(
            r#"{{"cases": [{{"q": [{q}]}}, {{"q": [0.2], "v": [1.5], "a": [0.3], "tau": [1.0]}}]}}"#
        ),
    );
    let out = eval_json(&fixture("pendulum.urdf"), &cases, &[]);
    assert_eq!(keys(&out), set(&["model", "results"]));
    let model = &out["model"];
    assert_eq!(
        keys(model),
        set(&["name", "layout", "nq", "nv", "joints", "gravity"])
    );
    assert_eq!(model["layout"], "rigid");
    assert_eq!(model["name"], "pendulum");
    assert_eq!(
        (model["nq"].as_u64(), model["nv"].as_u64()),
        (Some(1), Some(1))
    );
    let j = &model["joints"][0];
    assert_eq!(
        keys(j),
        set(&["name", "type", "idx_q", "nq", "idx_v", "nv"])
    );
    assert_eq!(
        (j["name"].as_str(), j["type"].as_str()),
        (Some("hinge"), Some("revolute"))
    );
    assert_eq!(model["gravity"], serde_json::json!([0.0, 0.0, -9.81]));

    let results = out["results"].as_array().unwrap();
    assert_eq!(results.len(), 2);
    let r = &results[0];
    assert_eq!(
        keys(r),
        set(&[
            "rnea",
            "mass_matrix",
            "nonlinear_effects",
            "gravity_torques",
            "aba",
            "kinetic_energy",
            "potential_energy",
            "com",
            "total_mass",
            "placements"
        ])
    );
    let (m, g, l, i) = (2.0, 9.81, 0.5, 0.01);
    let num = |v: &Value| v.as_f64().unwrap();
    // g(q) = m g l sin q; at rest rnea = g(q); M = m l² + I.
    assert!((num(&r["gravity_torques"][0]) - m * g * l * q.sin()).abs() < 1e-12);
    assert!((num(&r["rnea"][0]) - m * g * l * q.sin()).abs() < 1e-12);
    assert!((num(&r["mass_matrix"][0][0]) - (m * l * l + i)).abs() < 1e-12);
    assert!((num(&r["aba"][0]) + m * g * l * q.sin() / (m * l * l + i)).abs() < 1e-12);
    assert!((num(&r["total_mass"]) - m).abs() < 1e-12);
    // The bob hangs from the hinge at z = 1: c = (-l sin q, 0, 1 - l cos q).
    let c = [-l * q.sin(), 0.0, 1.0 - l * q.cos()];
    for k in 0..3 {
        assert!((num(&r["com"][k]) - c[k]).abs() < 1e-12);
    }
    assert!((num(&r["potential_energy"]) - m * g * c[2]).abs() < 1e-12);
    assert_eq!(num(&r["kinetic_energy"]), 0.0);
    let p = &r["placements"]["hinge"];
    assert_eq!(keys(p), set(&["translation", "rotation"]));
    assert_eq!(p["translation"], serde_json::json!([0.0, 0.0, 1.0]));
    assert!((num(&p["rotation"][0][2]) - q.sin()).abs() < 1e-15);
    // Second case: v, a, tau given; τ = M a (no Coriolis for one joint) + g.
    let r = &results[1];
    let tau = (m * l * l + i) * 0.3 + m * g * l * 0.2f64.sin();
    assert!((num(&r["rnea"][0]) - tau).abs() < 1e-12);
    assert!((num(&r["kinetic_energy"]) - 0.5 * (m * l * l + i) * 1.5 * 1.5).abs() < 1e-12);
}

/// The pendulum fixture with a 1 kg base (so that, on a free-flyer, the mass matrix is regular),
/// written to a temporary file `tag`.
fn pendulum_with_base(tag: &str) -> String {
    let urdf = std::fs::read_to_string(fixture("pendulum.urdf"))
        .unwrap()
        .replace(
            r#"<link name="base"/>"#,
            r#"<link name="base"><inertial><mass value="1"/>
             <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>"#,
        );
    temp_file(tag, &urdf)
}

#[test]
fn eval_floating_adds_a_free_flyer_root() {
    let cases = temp_file(
        "floating.json",
        r#"{"cases": [{"q": [0, 0, 0, 0, 0, 0, 1, 0.3]}]}"#,
    );
    let out = eval_json(
        &pendulum_with_base("floating.urdf"),
        &cases,
        &["--floating"],
    );
    assert_eq!(
        (out["model"]["nq"].as_u64(), out["model"]["nv"].as_u64()),
        (Some(8), Some(7))
    );
    let j = &out["model"]["joints"][0];
    assert_eq!(
        (j["name"].as_str(), j["type"].as_str()),
        (Some("root_joint"), Some("free_flyer"))
    );
    let aba = out["results"][0]["aba"].as_array().unwrap();
    assert_eq!(aba.len(), 7);
    let g = out["results"][0]["gravity_torques"].as_array().unwrap();
    // The base's generalized gravity force holds up both bodies: f_z = (1 + 2) g.
    assert!((g[5].as_f64().unwrap() - 3.0 * 9.81).abs() < 1e-12, "{g:?}");
    // Free fall: the base accelerates at g, the pendulum does not swing.
    let aba: Vec<f64> = aba.iter().map(|x| x.as_f64().unwrap()).collect();
    let expected = [0.0, 0.0, 0.0, 0.0, 0.0, -9.81, 0.0];
    for (x, e) in aba.iter().zip(expected) {
        assert!((x - e).abs() < 1e-12, "{aba:?}");
    }
}

#[test]
fn eval_builtin_double_pendulum() {
    let cases = temp_file("builtin.json", r#"{"cases": [{"q": [0.4, -0.3]}]}"#);
    let out = eval_json("double_pendulum", &cases, &[]);
    assert_eq!(out["model"]["nv"].as_u64(), Some(2));
    let r = &out["results"][0];
    assert_eq!(r["rnea"], r["gravity_torques"]);
    assert_eq!(r["nonlinear_effects"], r["gravity_torques"]);
}

#[test]
fn eval_summary_is_readable() {
    let cases = temp_file("summary.json", r#"{"cases": [{"q": [0.1]}]}"#);
    let out = rigid(&["eval", &fixture("pendulum.urdf"), "--cases", &cases]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("rnea") && text.contains("mass matrix") && text.contains("case 0"));
}

#[test]
fn eval_bad_input_is_named_and_exits_non_zero() {
    let urdf = fixture("pendulum.urdf");
    let bad_len = temp_file(
        "bad_len.json",
        r#"{"cases": [{"q": [0.1]}, {"q": [0.1], "v": [1, 2]}]}"#,
    );
    let err = fails(&["eval", &urdf, "--cases", &bad_len]);
    assert!(
        err.contains("case 1") && err.contains("\"v\"") && err.contains("nv = 1"),
        "{err}"
    );

    let no_q = temp_file("no_q.json", r#"{"cases": [{"v": [1]}]}"#);
    let err = fails(&["eval", &urdf, "--cases", &no_q]);
    assert!(err.contains("case 0") && err.contains("\"q\""), "{err}");

    let not_num = temp_file("not_num.json", r#"{"cases": [{"q": ["x"]}]}"#);
    let err = fails(&["eval", &urdf, "--cases", &not_num]);
    assert!(
        err.contains("case 0") && err.contains("not a number"),
        "{err}"
    );

    let quat = temp_file(
        "quat.json",
        r#"{"cases": [{"q": [0, 0, 0, 0, 0, 0, 0.5, 0.3]}]}"#,
    );
    let err = fails(&["eval", &urdf, "--cases", &quat, "--floating"]);
    assert!(
        err.contains("case 0") && err.contains("root_joint") && err.contains("quaternion"),
        "{err}"
    );

    let malformed = temp_file("malformed.json", r#"{"cases": [{"q": [0.1]}"#);
    let err = fails(&["eval", &urdf, "--cases", &malformed]);
    assert!(err.contains("malformed JSON"), "{err}");

    let err = fails(&["eval", &urdf, "--cases", "/nonexistent/cases.json"]);
    assert!(err.contains("cannot read"), "{err}");

    let good = temp_file("good.json", r#"{"cases": [{"q": [0.1]}]}"#);
    let err = fails(&["eval", "no_such_robot", "--cases", &good]);
    assert!(
        err.contains("unknown model") && err.contains("no_such_robot"),
        "{err}"
    );

    let text = std::fs::read_to_string(&urdf).unwrap();
    let bad_urdf = temp_file(
        "bad.urdf",
        &text.replace("type=\"revolute\"", "type=\"hinge\""),
    );
    let err = fails(&["eval", &bad_urdf, "--cases", &good]);
    assert!(
        err.contains("joint \"hinge\"")
            && err.contains("line 13")
            && err.contains("unknown joint type"),
        "{err}"
    );
}

#[test]
fn model_summary_and_inertia_report() {
    let out = rigid(&["model", &fixture("pendulum.urdf")]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("hinge") && text.contains("total mass 2.000000 kg"),
        "{text}"
    );
    assert!(
        text.contains("nq = 1, nv = 1") && text.contains("inertia policy: warn; 0 warning(s)"),
        "{text}"
    );

    let out = rigid(&["model", "double_pendulum"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );

    let urdf = std::fs::read_to_string(fixture("pendulum.urdf")).unwrap();
    let bad = temp_file(
        "bad_inertia.urdf",
        &urdf.replace("ixx=\"0.01\"", "ixx=\"-0.01\""),
    );
    // Loaded as written under the default policy, with a warning; refused by --inertia strict.
    let out = rigid(&["model", &bad]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("warning") && text.contains("link \"bob\"") && text.contains("as written"),
        "{text}"
    );
    let out = rigid(&["model", &bad, "--inertia", "strict"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.starts_with("error:")
            && err.contains("link \"bob\"")
            && err.contains("line ")
            && err.contains("positive semi-definite"),
        "{err}"
    );

    let massless = urdf
        .replace("<mass value=\"2\"/>", "<mass value=\"0\"/>")
        .replace("0.01", "0");
    let massless = temp_file("massless.urdf", &massless);
    let out = rigid(&["model", &massless]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("warning") && text.contains("zero mass") && text.contains("\"hinge\""),
        "{text}"
    );
}

#[test]
fn eval_derivatives_adds_the_rnea_and_aba_derivatives_of_the_pendulum() {
    let q: f64 = 0.7;
    let cases = temp_file(
        "pendulum_derivatives.json",
        &format!(r#"{{"cases": [{{"q": [{q}], "v": [1.5], "a": [0.3], "tau": [1.0]}}]}}"#),
    );
    let out = eval_json(&fixture("pendulum.urdf"), &cases, &["--derivatives"]);
    let r = &out["results"][0];
    assert!(keys(r).is_superset(&set(&[
        "rnea",
        "aba",
        "rnea_derivatives",
        "aba_derivatives"
    ])));
    assert_eq!(keys(&r["rnea_derivatives"]), set(&["dtau_dq", "dtau_dv"]));
    assert_eq!(
        keys(&r["aba_derivatives"]),
        set(&["dqdd_dq", "dqdd_dv", "dqdd_dtau"])
    );
    // τ = M q̈ + m g l sin q with M = m l² + I: ∂τ/∂q = m g l cos q, ∂τ/∂v = 0,
    // ∂q̈/∂q = -m g l cos q / M, ∂q̈/∂v = 0, ∂q̈/∂τ = 1/M (1 x 1, row-major nested arrays)
    let (m, g, l, i) = (2.0, 9.81, 0.5, 0.01);
    let big_m = m * l * l + i;
    let num = |v: &Value| v.as_f64().unwrap();
    let d = &r["rnea_derivatives"];
    assert!((num(&d["dtau_dq"][0][0]) - m * g * l * q.cos()).abs() < 1e-12);
    assert_eq!(num(&d["dtau_dv"][0][0]), 0.0);
    let d = &r["aba_derivatives"];
    assert!((num(&d["dqdd_dq"][0][0]) + m * g * l * q.cos() / big_m).abs() < 1e-12);
    assert_eq!(num(&d["dqdd_dv"][0][0]), 0.0);
    assert!((num(&d["dqdd_dtau"][0][0]) - 1.0 / big_m).abs() < 1e-12);
}

#[test]
fn eval_derivatives_are_nv_by_nv_on_a_floating_base() {
    let q = r#"[0.1, -0.2, 0.3, 0.0, 0.0, 0.0, 1.0, 0.4]"#;
    let cases = temp_file(
        "floating_derivatives.json",
        &format!(r#"{{"cases": [{{"q": {q}, "v": [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7]}}]}}"#),
    );
    let urdf = pendulum_with_base("floating_derivatives.urdf");
    let out = eval_json(&urdf, &cases, &["--floating", "--derivatives"]);
    let r = &out["results"][0];
    for (group, key) in [
        ("rnea_derivatives", "dtau_dq"),
        ("rnea_derivatives", "dtau_dv"),
        ("aba_derivatives", "dqdd_dq"),
        ("aba_derivatives", "dqdd_dv"),
        ("aba_derivatives", "dqdd_dtau"),
    ] {
        let m = r[group][key].as_array().unwrap();
        assert_eq!(m.len(), 7, "{key}");
        assert!(
            m.iter().all(|row| row.as_array().unwrap().len() == 7),
            "{key}"
        );
    }
    // ∂q̈/∂τ = M⁻¹: times M (the contract's mass_matrix) is the identity
    let (minv, mm) = (&r["aba_derivatives"]["dqdd_dtau"], &r["mass_matrix"]);
    for i in 0..7 {
        for j in 0..7 {
            let x: f64 = (0..7)
                .map(|k| mm[i][k].as_f64().unwrap() * minv[k][j].as_f64().unwrap())
                .sum();
            assert!(
                (x - if i == j { 1.0 } else { 0.0 }).abs() < 1e-9,
                "({i}, {j}): {x}"
            );
        }
    }
}
