//! `rigid excite` and `rigid identify` end to end: a trajectory from `excite`, torques of a
//! "true" robot, identification against its "CAD" URDF (a link 50 % heavier, a welded tool of
//! another mass), the base parameters recovered, the physically consistent estimate written back
//! into the URDF (the composite into the main link, the welded link zeroed) and loaded again.

use rigid::identification::model_parameters;
use rigid::io::urdf::load_urdf;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

fn arm(link2_mass: f64, tool_mass: f64) -> String {
    format!(
        r#"<?xml version="1.0"?>
<robot name="arm">
  <link name="base"/>
  <link name="link1">
    <inertial>
      <origin xyz="0.2 0 0" rpy="0 0 0"/>
      <mass value="3"/>
      <inertia ixx="0.01" iyy="0.05" izz="0.05" ixy="0" ixz="0" iyz="0"/>
    </inertial>
  </link>
  <link name="link2">
    <inertial>
      <origin xyz="0.15 0.01 0" rpy="0 0 0"/>
      <mass value="{link2_mass}"/>
      <inertia ixx="0.005" iyy="0.02" izz="0.02" ixy="0.001" ixz="0" iyz="0"/>
    </inertial>
  </link>
  <link name="tool">
    <inertial>
      <origin xyz="0 0 0.02" rpy="0 0 0"/>
      <mass value="{tool_mass}"/>
      <inertia ixx="0.001" iyy="0.001" izz="0.0005" ixy="0" ixz="0" iyz="0"/>
    </inertial>
  </link>
  <joint name="shoulder" type="revolute">
    <origin xyz="0 0 0.5" rpy="0 0 0"/>
    <parent link="base"/>
    <child link="link1"/>
    <axis xyz="0 0 1"/>
    <limit lower="-2.5" upper="2.5" effort="100" velocity="3"/>
  </joint>
  <joint name="elbow" type="revolute">
    <origin xyz="0.4 0 0" rpy="0 0 0"/>
    <parent link="link1"/>
    <child link="link2"/>
    <axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="100" velocity="3"/>
  </joint>
  <joint name="flange" type="fixed">
    <origin xyz="0.3 0 0" rpy="0 1.5707963267948966 0"/>
    <parent link="link2"/>
    <child link="tool"/>
  </joint>
</robot>
"#
    )
}

fn tmp() -> PathBuf {
    let d = std::env::temp_dir().join(format!("rigid-identify-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn rigid(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(args)
        .output()
        .expect("run rigid");
    assert!(
        out.status.success(),
        "rigid {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn excite_then_identify_recovers_the_true_robot_and_writes_its_urdf() {
    let dir = tmp();
    let (cad, truth) = (dir.join("cad.urdf"), dir.join("true.urdf"));
    std::fs::write(&cad, arm(1.0, 0.2)).unwrap();
    std::fs::write(&truth, arm(1.5, 0.35)).unwrap();
    let traj = dir.join("traj.csv");
    let said = rigid(&[
        "excite",
        s(&truth),
        "--duration",
        "4",
        "--rate",
        "200",
        "--iterations",
        "30",
        "--out",
        s(&traj),
    ]);
    assert!(said.contains("condition number"), "{said}");
    let header = std::fs::read_to_string(&traj).unwrap();
    assert!(header.starts_with(
        "t,q_shoulder,q_elbow,v_shoulder,v_elbow,a_shoulder,a_elbow,tau_shoulder,tau_elbow\n"
    ));
    // the torques in traj.csv are those of the true robot: identify against the CAD one
    let out = dir.join("identified.urdf");
    // the physically consistent estimate when built with the feature `sdp` (CI), else least
    // squares, and `--physical` says how to build it in
    let sdp = cfg!(feature = "sdp");
    let mut args = vec![
        "identify",
        s(&cad),
        "--data",
        s(&traj),
        "--json",
        "--out",
        s(&out),
    ];
    if sdp {
        args.push("--physical");
    } else {
        let said = Command::new(env!("CARGO_BIN_EXE_rigid"))
            .args(&args)
            .arg("--physical")
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&said.stderr);
        assert!(
            !said.status.success() && err.contains("--features sdp"),
            "{err}"
        );
    }
    let json: Value = serde_json::from_str(&rigid(&args)).unwrap();
    let written = if sdp { "physical" } else { "least_squares" };
    let reference: Value = serde_json::from_str(&rigid(&[
        "identify",
        s(&truth),
        "--data",
        s(&traj),
        "--json",
    ]))
    .unwrap();
    let want = floats(&reference["model_values"]["base"]);
    let got = floats(&json["least_squares"]["base"]);
    let scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).abs() < 1e-9 * scale, "{got:?} vs {want:?}");
    }
    assert!(floats(&json["model_values"]["base"]) != want); // the CAD values are off
    if sdp {
        for b in json["physical"]["bodies"].as_array().unwrap() {
            assert_eq!(b["verdict"], "consistent", "{b}");
        }
    }
    // the written URDF: the estimate's bodies, the composite in link2, the tool zeroed
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains(if sdp {
        "rigid identify: physically consistent estimate"
    } else {
        "rigid identify: least-squares estimate"
    }));
    assert!(text.contains("links welded to it (tool)"));
    assert!(text.contains("zeroed; this link is welded to \"link2\""));
    let model = load_urdf(&out, false).unwrap();
    let pi = model_parameters(&model);
    let want = floats(&json[written]["parameters"]);
    for (k, (a, b)) in pi.iter().zip(&want).enumerate() {
        assert!(
            (a - b).abs() < 1e-9 * (1.0 + b.abs()),
            "parameter {k}: {a} vs {b}"
        );
    }
    // the joints are as they were
    let joints = |t: &str| {
        t.lines()
            .filter(|l| {
                ["<joint", "<parent", "<child", "<axis", "<limit", "<link"]
                    .iter()
                    .any(|k| l.contains(k))
            })
            .map(str::to_string)
            .collect::<Vec<_>>()
    };
    assert_eq!(joints(&arm(1.0, 0.2)), joints(&text));
    // the human report names the base parameters and the residuals
    let report = rigid(&["identify", s(&cad), "--data", s(&traj)]);
    assert!(
        report.contains("base parameter") && report.contains("residual RMS"),
        "{report}"
    );
}

#[test]
fn positions_only_are_differentiated() {
    let dir = tmp();
    let truth = dir.join("true2.urdf");
    std::fs::write(&truth, arm(1.5, 0.35)).unwrap();
    let traj = dir.join("traj2.csv");
    rigid(&[
        "excite",
        s(&truth),
        "--duration",
        "4",
        "--rate",
        "1000",
        "--iterations",
        "20",
        "--out",
        s(&traj),
    ]);
    // keep t, q, tau only
    let text = std::fs::read_to_string(&traj).unwrap();
    let cut: String = text
        .lines()
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            format!("{},{},{},{},{}\n", c[0], c[1], c[2], c[7], c[8])
        })
        .collect();
    let pos = dir.join("positions.csv");
    std::fs::write(&pos, cut).unwrap();
    let a: Value = serde_json::from_str(&rigid(&[
        "identify",
        s(&truth),
        "--data",
        s(&pos),
        "--json",
    ]))
    .unwrap();
    let want = floats(&a["model_values"]["base"]);
    let got = floats(&a["least_squares"]["base"]);
    let scale = want.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let err = got
        .iter()
        .zip(&want)
        .map(|(g, w)| (g - w).abs())
        .fold(0.0, f64::max)
        / scale;
    eprintln!("positions only (Savitzky-Golay, 1 kHz): base parameters to {err:.2e} relative");
    assert!(err < 1e-4, "{err}");
}
