//! `rigid eval --mimic`: Panda with its finger coupled, in Pinocchio's layout, against Pinocchio
//! 4.1's `mimic=True` (the `rigid` crate's fixture `tests/pinocchio/mimic.json`: `rnea`, `M`,
//! `nle` and `M⁻¹ (τ − nle)`); the joints listed with the mimic's `nq = nv = 0` and what it
//! follows; the errors.

use crate::common::rigid_tests;
use serde_json::Value;
use std::process::Command;

fn panda() -> String {
    rigid_tests("fixtures/robots/example-robot-data/robots/panda_description/urdf/panda.urdf")
        .display()
        .to_string()
}

fn vec_of(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn max_rel(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / scale
}

#[test]
fn eval_mimic_in_pinocchio_s_layout_equals_pinocchio_mimic_true() {
    let text = std::fs::read_to_string(rigid_tests("pinocchio/mimic.json")).unwrap();
    let rec: Value = serde_json::from_str(text.lines().next().unwrap()).unwrap();
    let cases: Vec<Value> = rec["cases"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| serde_json::json!({"q": c["q"], "v": c["v"], "a": c["a"], "tau": c["tau"]}))
        .collect();
    let dir = std::env::temp_dir().join(format!("rigid-eval-mimic-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("cases.json");
    std::fs::write(&file, serde_json::json!({ "cases": cases }).to_string()).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args([
            "eval",
            &panda(),
            "--mimic",
            "--layout",
            "pinocchio",
            "--json",
        ])
        .arg("--cases")
        .arg(&file)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let got: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (got["model"]["nq"].as_u64(), got["model"]["nv"].as_u64()),
        (Some(8), Some(8))
    );
    let finger2 = &got["model"]["joints"][8];
    assert_eq!(finger2["name"], "panda_finger_joint2");
    assert_eq!(
        (finger2["nq"].as_u64(), finger2["idx_v"].as_u64()),
        (Some(0), Some(7))
    );
    assert_eq!(finger2["mimic"]["joint"], "panda_finger_joint1");
    for (r, want) in got["results"]
        .as_array()
        .unwrap()
        .iter()
        .zip(rec["cases"].as_array().unwrap())
    {
        let m: Vec<f64> = r["mass_matrix"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(vec_of)
            .collect();
        let want_m: Vec<f64> = want["M"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(vec_of)
            .collect();
        for (what, a, b) in [
            ("rnea", vec_of(&r["rnea"]), vec_of(&want["rnea"])),
            ("nle", vec_of(&r["nonlinear_effects"]), vec_of(&want["nle"])),
            ("aba", vec_of(&r["aba"]), vec_of(&want["ddq"])),
            ("M", m, want_m),
        ] {
            let e = max_rel(&a, &b);
            assert!(e < 1e-9, "{what}: {e:e} from Pinocchio");
        }
    }
}

#[test]
fn eval_mimic_refuses_what_it_cannot_do_and_names_a_fixed_mimic() {
    let dir = std::env::temp_dir().join(format!("rigid-eval-mimic-err-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = dir.join("cases.json");
    std::fs::write(&cases, r#"{"cases": [{"q": [0.1]}]}"#).unwrap();
    let run = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_rigid"))
            .args(args)
            .arg("--cases")
            .arg(&cases)
            .output()
            .unwrap();
        assert!(!out.status.success());
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let e = run(&["eval", &panda(), "--mimic", "--layout", "mujoco"]);
    assert!(e.contains("--mimic with --layout mujoco"), "{e}");
    let link = |n: &str| {
        format!(
            r#"<link name="{n}"><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>"#
        )
    };
    let urdf = format!(
        r#"<robot name="r">{}{}{}
  <joint name="a" type="continuous"><parent link="l0"/><child link="l1"/></joint>
  <joint name="b" type="fixed"><parent link="l1"/><child link="l2"/>
    <mimic joint="a" multiplier="2"/></joint>
</robot>"#,
        link("l0"),
        link("l1"),
        link("l2")
    );
    let path = dir.join("fixed_mimic.urdf");
    std::fs::write(&path, urdf).unwrap();
    let e = run(&["eval", path.to_str().unwrap(), "--mimic"]);
    assert!(
        e.contains("line 3: joint \"b\": mimic: joint \"b\" is fixed"),
        "{e}"
    );
}

#[test]
fn simulate_mimic_keeps_panda_s_fingers_together() {
    // the start and velocity in the reduced coordinates (8 numbers for 9 joints)
    let csv = std::env::temp_dir().join(format!("rigid-sim-mimic-{}.csv", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(["simulate", &panda(), "--mimic", "--duration", "0.2"])
        .args([
            "--q0",
            "0,0.3,0,-1.5,0,1.5,0,0.02",
            "--v0",
            "0,0,0,0,0,0,0,0.1",
        ])
        .arg("--csv")
        .arg(&csv)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (f1, f2) = (col("q_panda_finger_joint1"), col("q_panda_finger_joint2"));
    let mut moved = 0.0f64;
    for line in text.lines().skip(1) {
        let x: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
        assert!((x[f1] - x[f2]).abs() < 1e-12, "{line}");
        moved = moved.max((x[f1] - 0.02).abs());
    }
    assert!(moved > 1e-3, "the fingers did not move");
    let e = Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(["simulate", &panda(), "--mimic", "--q0", "0,0"])
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&e.stderr);
    assert!(
        e.contains("with --mimic give the reduced coordinates (8) or every joint's (9)"),
        "{e}"
    );
}

/// A wheel (continuous: two coordinates in Pinocchio's `q`) before a finger pair, the second
/// finger following the first with an offset.
fn wheel_and_fingers(dir: &std::path::Path) -> std::path::PathBuf {
    let link = |n: &str| {
        format!(
            r#"<link name="{n}"><inertial><mass value="1"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>"#
        )
    };
    let urdf = format!(
        r#"<robot name="r">{}{}{}{}
  <joint name="a_wheel" type="continuous"><parent link="l0"/><child link="l1"/><axis xyz="0 0 1"/></joint>
  <joint name="b_finger" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0 0.1 0"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="c_finger" type="revolute"><parent link="l2"/><child link="l3"/><origin xyz="0 0.1 0"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
    <mimic joint="b_finger" multiplier="-0.5" offset="0.2"/></joint>
</robot>"#,
        link("l0"),
        link("l1"),
        link("l2"),
        link("l3")
    );
    let path = dir.join("wheel_fingers.urdf");
    std::fs::write(&path, urdf).unwrap();
    path
}

#[test]
fn a_mimic_sits_at_its_source_s_index_in_pinocchio_s_q_and_starts_closed_in_simulate() {
    let dir = std::env::temp_dir().join(format!("rigid-mimic-wheel-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = wheel_and_fingers(&dir);
    let cases = dir.join("cases.json");
    std::fs::write(&cases, r#"{"cases": [{"q": [1, 0, 0.3], "tau": [0, 1]}]}"#).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args([
            "eval",
            path.to_str().unwrap(),
            "--mimic",
            "--layout",
            "pinocchio",
            "--json",
        ])
        .args(["--derivatives", "--cases", cases.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let got: Value = serde_json::from_slice(&out.stdout).unwrap();
    let joints = &got["model"]["joints"];
    let idx = |k: usize| {
        (
            joints[k]["idx_q"].as_u64().unwrap(),
            joints[k]["nq"].as_u64().unwrap(),
        )
    };
    // the wheel's (cos, sin), then the finger; its mimic at the finger's index with nq 0
    assert_eq!((idx(0), idx(1), idx(2)), ((0, 2), (2, 1), (2, 0)));
    assert_eq!(got["model"]["nq"].as_u64(), Some(3));
    let d = &got["results"][0]["aba_derivatives"]["dqdd_dtau"];
    assert_eq!(d.as_array().unwrap().len(), 2);
    // simulate from the neutral start: the mimic starts at its offset, the coupling closed
    let csv = dir.join("sim.csv");
    let out = Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args([
            "simulate",
            path.to_str().unwrap(),
            "--mimic",
            "--duration",
            "0.1",
        ])
        .arg("--csv")
        .arg(&csv)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (b, c) = (col("q_b_finger"), col("q_c_finger"));
    for line in text.lines().skip(1) {
        let x: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
        assert!((x[c] - (-0.5 * x[b] + 0.2)).abs() < 1e-9, "{line}");
    }
}
