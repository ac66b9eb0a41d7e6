//! `rigid ik`: a reachable target is reached (the pose the command reports, and the pose of its
//! `q` by `rigid eval`, equal the target), an unreachable one exits 1 with the best attempt, and
//! bad flags exit 2 naming the flag.

use crate::common;
use serde_json::Value;
use std::process::{Command, Output};

fn rigid(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(args)
        .output()
        .expect("run rigid")
}

fn ur5() -> String {
    common::example_robot_data()
        .join("ur_description/urdf/ur5_robot.urdf")
        .display()
        .to_string()
}

/// `R = exp([w])` (Rodrigues), row-major.
fn rotation(w: [f64; 3]) -> [[f64; 3]; 3] {
    let t = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    let k = [w[0] / t, w[1] / t, w[2] / t];
    let (s, c) = t.sin_cos();
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let kk = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]];
            let k2: f64 = (0..3).map(|m| kk[i][m] * kk[m][j]).sum();
            r[i][j] = f64::from(u8::from(i == j)) + s * kk[i][j] + (1.0 - c) * k2;
        }
    }
    r
}

#[test]
fn a_full_pose_of_the_ur5_is_reached() {
    let out = rigid(&[
        "ik",
        &ur5(),
        "--frame",
        "tool0",
        "--target",
        "0.3,-0.2,0.4,0.5,-2.0,0.3",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["converged"], true);
    assert!(v["angular_error"].as_f64().unwrap() <= 1e-9);
    assert!(v["linear_error"].as_f64().unwrap() <= 1e-9);
    let p: Vec<f64> = serde_json::from_value(v["pose"]["translation"].clone()).unwrap();
    let r: Vec<Vec<f64>> = serde_json::from_value(v["pose"]["rotation"].clone()).unwrap();
    let want = rotation([0.5, -2.0, 0.3]);
    for i in 0..3 {
        assert!((p[i] - [0.3, -0.2, 0.4][i]).abs() < 1e-9);
        for j in 0..3 {
            assert!((r[i][j] - want[i][j]).abs() < 1e-9, "R[{i}][{j}]");
        }
    }
    assert_eq!(v["joints"].as_array().unwrap().len(), 6);
    assert_eq!(v["q"].as_array().unwrap().len(), 6);
}

#[test]
fn a_position_target_then_the_same_pose_in_roll_pitch_yaw() {
    let out = rigid(&[
        "ik",
        "puma560",
        "--frame",
        "link6",
        "--target",
        "0.4,0.2,0.3",
    ]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.starts_with("link6: converged"), "{text}");
    assert!(text.contains("joint6"));
    let out = rigid(&[
        "ik",
        "puma560",
        "--frame",
        "link6",
        "--target",
        "0.4,0.2,0.3",
        "--json",
    ]);
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    let r: Vec<Vec<f64>> = serde_json::from_value(v["pose"]["rotation"].clone()).unwrap();
    // URDF rpy: R = Rz(yaw) Ry(pitch) Rx(roll)
    let (roll, pitch, yaw) = (
        r[2][1].atan2(r[2][2]),
        (-r[2][0]).asin(),
        r[1][0].atan2(r[0][0]),
    );
    let t = format!("0.4,0.2,0.3,{roll},{pitch},{yaw}");
    let out = rigid(&[
        "ik", "puma560", "--frame", "link6", "--target", &t, "--rpy", "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    let w: Value = serde_json::from_slice(&out.stdout).unwrap();
    let r2: Vec<Vec<f64>> = serde_json::from_value(w["pose"]["rotation"].clone()).unwrap();
    for i in 0..3 {
        for j in 0..3 {
            assert!((r[i][j] - r2[i][j]).abs() < 1e-9);
        }
    }
}

#[test]
fn an_unreachable_target_exits_1_with_the_best_attempt() {
    let out = rigid(&[
        "ik",
        "puma560",
        "--frame",
        "link6",
        "--target",
        "5,0,0",
        "--restarts",
        "2",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["converged"], false);
    assert_eq!(v["attempts"], 3);
    assert!(v["position_error"].as_f64().unwrap() > 3.0);
}

#[test]
fn bad_flags_exit_2_naming_the_flag() {
    for (args, needle) in [
        (vec!["--frame", "nope", "--target", "0,0,0"], "--frame"),
        (vec!["--frame", "link6", "--target", "0,0"], "--target"),
        (
            vec!["--frame", "link6", "--target", "0,0,0", "--q0", "1,2"],
            "--q0",
        ),
        (
            vec!["--frame", "link6", "--target", "0,0,0", "--tolerance", "-1"],
            "--tolerance",
        ),
        (
            vec!["--frame", "link6", "--target", "0,0,0", "--rpy"],
            "--rpy",
        ),
    ] {
        let mut a = vec!["ik", "puma560"];
        a.extend(args);
        let out = rigid(&a);
        assert_eq!(out.status.code(), Some(2), "{a:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{a:?}: {err}");
    }
}
