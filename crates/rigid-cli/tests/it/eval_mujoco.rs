//! `rigid eval --layout mujoco` against the checked-in MuJoCo fixtures
//! (`crates/rigid/tests/mujoco`): MuJoCo's `qpos`, `qvel`, `qacc`, `qfrc` in; `mj_fullM`,
//! `qfrc_bias`, the gravity forces, `M qacc + qfrc_bias` and `M⁻¹ (qfrc - qfrc_bias)` out. Also a
//! case whose mass matrix is not positive definite: every output but ABA.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

fn mujoco_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../rigid/tests/mujoco")
}

fn rigid(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(args)
        .output()
        .expect("run rigid");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(a) => a.iter().flat_map(numbers).collect(),
        Value::Number(n) => vec![n.as_f64().unwrap()],
        _ => panic!("not numbers: {v}"),
    }
}

fn close(what: &str, a: &Value, b: &Value, tol: f64) {
    let (a, b) = (numbers(a), numbers(b));
    assert_eq!(a.len(), b.len(), "{what}");
    let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() <= tol * scale, "{what}: {x} vs {y}");
    }
}

fn temp(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigid-eval-mujoco-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn eval_in_mujocos_layout_prints_mujocos_arrays() {
    for name in ["ant", "features", "compiler"] {
        let fixture: Value = serde_json::from_str(
            &std::fs::read_to_string(mujoco_dir().join(format!("fixtures/{name}.json"))).unwrap(),
        )
        .unwrap();
        let states = fixture["states"].as_array().unwrap();
        let cases: Vec<Value> = states
            .iter()
            .map(|s| {
                serde_json::json!({"q": s["qpos"], "v": s["qvel"], "a": s["qacc"], "tau": s["qfrc"]})
            })
            .collect();
        let file = temp(
            &format!("{name}.json"),
            &serde_json::json!({ "cases": cases }).to_string(),
        );
        let model = mujoco_dir().join(fixture["file"].as_str().unwrap());
        let (ok, out, err) = rigid(&[
            "eval",
            model.to_str().unwrap(),
            "--layout",
            "mujoco",
            "--cases",
            file.to_str().unwrap(),
            "--json",
        ]);
        assert!(ok, "{err}");
        let out: Value = serde_json::from_str(&out).unwrap();
        assert_eq!(out["model"]["layout"], "mujoco");
        close(
            "qpos0",
            &out["model"]["qpos0"][0],
            &fixture["qpos0"][0],
            1e-12,
        );
        for (r, s) in out["results"].as_array().unwrap().iter().zip(states) {
            close("mass_matrix", &r["mass_matrix"], &s["mass_matrix"], 1e-9);
            close(
                "nonlinear_effects",
                &r["nonlinear_effects"],
                &s["bias"],
                1e-9,
            );
            close(
                "gravity_torques",
                &r["gravity_torques"],
                &s["gravity"],
                1e-9,
            );
            close("rnea", &r["rnea"], &s["rnea"], 1e-9);
            close("aba", &r["aba"], &s["aba"], 1e-8);
        }
    }
}

#[test]
fn derivatives_in_mujocos_layout_need_a_model_without_a_free_joint() {
    let cases = temp(
        "cheetah_cases.json",
        r#"{"cases": [{"q": [0,0,0,0,0,0,0,0,0]}]}"#,
    );
    let model = mujoco_dir().join("models/cheetah.xml");
    let args = |m: &Path| {
        vec![
            "eval".to_string(),
            m.to_str().unwrap().to_string(),
            "--layout".into(),
            "mujoco".into(),
            "--cases".into(),
            cases.to_str().unwrap().to_string(),
            "--json".into(),
            "--derivatives".into(),
        ]
    };
    let a = args(&model);
    let (ok, out, err) = rigid(&a.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(ok, "{err}");
    assert!(out.contains("rnea_derivatives"));
    let ant = mujoco_dir().join("models/ant.xml");
    let a = args(&ant);
    let (ok, _, err) = rigid(&a.iter().map(String::as_str).collect::<Vec<_>>());
    assert!(!ok && err.contains("free joint"), "{err}");
}

/// A non-physical inertia loaded as written (`--inertia warn`) can make `M` indefinite: the case
/// still gets RNEA, CRBA and the rest, and ABA is reported undefined instead of failing it.
#[test]
fn an_indefinite_mass_matrix_leaves_every_output_but_aba() {
    let urdf = temp(
        "indefinite.urdf",
        r#"<robot name="r"><link name="a"/>
  <link name="b"><inertial><mass value="1"/>
    <inertia ixx="-1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="1 0 0"/></joint>
</robot>"#,
    );
    let cases = temp(
        "indefinite.json",
        r#"{"cases": [{"q": [0.3], "tau": [1]}]}"#,
    );
    let (ok, out, err) = rigid(&[
        "eval",
        urdf.to_str().unwrap(),
        "--cases",
        cases.to_str().unwrap(),
        "--json",
    ]);
    assert!(ok, "{err}");
    let out: Value = serde_json::from_str(&out).unwrap();
    let r = &out["results"][0];
    assert!(r["aba"].is_null(), "{r}");
    assert!(r["aba_error"]
        .as_str()
        .unwrap()
        .contains("not positive definite"));
    assert_eq!(numbers(&r["mass_matrix"]), [-1.0]);
    assert_eq!(numbers(&r["rnea"]).len(), 1);
}
