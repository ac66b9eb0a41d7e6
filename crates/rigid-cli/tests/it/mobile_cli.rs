//! `rigid mobile`: `h` prints the book's H(φ) (eq. 13.10 typed here), `odometry` follows a
//! differential drive along an arc to the closed form of a circle, `capstone` writes the course's
//! scene CSV, X_err, a plot and a replay with the end effector on the reference, and bad input
//! exits 2 naming the flag, the wheel or the line.

use serde_json::Value;
use std::process::{Command, Output};

fn rigid(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(args)
        .output()
        .expect("run rigid")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn h_is_the_books_mecanum_matrix() {
    let (r, l, w, phi) = (0.05, 0.3, 0.2, 0.7f64);
    let o = rigid(&[
        "mobile",
        "h",
        "--base",
        "mecanum",
        "--radius",
        "0.05",
        "--half-length",
        "0.3",
        "--half-width",
        "0.2",
        "--phi",
        "0.7",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let h0 = [
        [-l - w, 1.0, -1.0],
        [l + w, 1.0, 1.0],
        [l + w, 1.0, -1.0],
        [-l - w, 1.0, 1.0],
    ];
    let (s, c) = phi.sin_cos();
    for (i, row) in h0.iter().enumerate() {
        // H(φ) = H(0) [[1, 0, 0], [0, cos φ, sin φ], [0, -sin φ, cos φ]]
        let want = [
            row[0] / r,
            (row[1] * c - row[2] * s) / r,
            (row[1] * s + row[2] * c) / r,
        ];
        for (j, x) in want.iter().enumerate() {
            let got = v["H"][i][j].as_f64().unwrap();
            assert!((got - x).abs() < 1e-12, "H[{i}][{j}] = {got}, book {x}");
        }
    }
    assert!(v["constraint"].is_null());
    let o = rigid(&[
        "mobile",
        "h",
        "--base",
        "diff-drive",
        "--radius",
        "0.1",
        "--track",
        "0.5",
    ]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success() && text.contains("nonholonomic"),
        "{text}"
    );
}

#[test]
fn odometry_follows_an_arc() {
    // a differential drive (r = 0.1, track 0.5) at ω = 0.5 rad/s, v = 0.4 m/s for 2 s in 20 rows
    let (r, d, w, v) = (0.1, 0.25, 0.5, 0.4);
    let (ul, ur) = ((v - d * w) / r, (v + d * w) / r);
    let mut csv = String::from("t,left,right\n");
    for k in 0..=20 {
        let t = 0.1 * f64::from(k);
        csv.push_str(&format!("{t},{},{}\n", ul * t, ur * t));
    }
    let dir = std::env::temp_dir().join(format!("rigid-mobile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("wheels.csv");
    std::fs::write(&path, csv).unwrap();
    let o = rigid(&[
        "mobile",
        "odometry",
        "--base",
        "diff-drive",
        "--radius",
        "0.1",
        "--track",
        "0.5",
        "--start",
        "0.3,1,2",
        path.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    let last: Vec<f64> = out
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(out.lines().next(), Some("t,phi,x,y"));
    // the circle of radius v/ω from (1, 2) heading 0.3
    let (rho, phi0, phi1) = (v / w, 0.3f64, 0.3 + w * 2.0);
    let x = 1.0 + rho * (phi1.sin() - phi0.sin());
    let y = 2.0 - rho * (phi1.cos() - phi0.cos());
    assert!((last[0] - 2.0).abs() < 1e-12 && (last[1] - phi1).abs() < 1e-12);
    assert!(
        (last[2] - x).abs() < 1e-12 && (last[3] - y).abs() < 1e-12,
        "{last:?} vs ({x}, {y})"
    );
    // a first row that is not numbers and not a header of the right width is refused, and a
    // row with the wrong number of wheels is named by its line
    for (text, line) in [("0,x\n1,1\n", "line 1"), ("0,0\n1,1,1\n", "line 2")] {
        std::fs::write(&path, text).unwrap();
        let o = rigid(&[
            "mobile",
            "odometry",
            "--base",
            "diff-drive",
            "--radius",
            "0.1",
            "--track",
            "0.5",
            path.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(2));
        assert!(stderr(&o).contains(line), "{}", stderr(&o));
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_capstone_writes_the_scene_csv_and_converges() {
    let dir = std::env::temp_dir().join(format!("rigid-capstone-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (csv, err, svg, html) = (
        dir.join("c.csv"),
        dir.join("e.csv"),
        dir.join("e.svg"),
        dir.join("r.html"),
    );
    let o = rigid(&[
        "mobile",
        "capstone",
        "--csv",
        csv.to_str().unwrap(),
        "--errors",
        err.to_str().unwrap(),
        "--plot",
        svg.to_str().unwrap(),
        "--html",
        html.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows: Vec<Vec<f64>> = std::fs::read_to_string(&csv)
        .unwrap()
        .lines()
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert!(rows.len() > 1000 && rows.iter().all(|r| r.len() == 13));
    assert!(
        rows.iter().any(|r| r[12] == 1.0) && rows[0][12] == 0.0,
        "the gripper closes"
    );
    let errors: Vec<Vec<f64>> = std::fs::read_to_string(&err)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    let norm = |r: &Vec<f64>| r[1..].iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(norm(&errors[0]) > 0.3);
    let late = errors
        .iter()
        .filter(|r| r[0] >= 5.0)
        .map(norm)
        .fold(0.0, f64::max);
    assert!(late < 1e-3, "X_err after 5 s: {late}");
    let page = std::fs::read_to_string(&html).unwrap();
    assert!(page.contains("youBot") && std::fs::metadata(&svg).unwrap().len() > 1000);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn bad_bases_are_refused_by_name() {
    let o = rigid(&["mobile", "h", "--base", "mecanum", "--radius", "0.05"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--half-length"), "{}", stderr(&o));
    let o = rigid(&[
        "mobile",
        "h",
        "--base",
        "mecanum",
        "--radius",
        "-0.05",
        "--half-length",
        "0.3",
        "--half-width",
        "0.2",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("wheel 0") && stderr(&o).contains("radius"),
        "{}",
        stderr(&o)
    );
    let o = rigid(&[
        "mobile",
        "h",
        "--base",
        "mecanum",
        "--radius",
        "0.05",
        "--half-length",
        "0",
        "--half-width",
        "0",
    ]);
    assert!(stderr(&o).contains("rank 2"), "{}", stderr(&o));
    let o = rigid(&["mobile", "h", "--base", "tank", "--radius", "0.05"]);
    assert!(stderr(&o).contains("unknown base"), "{}", stderr(&o));
}

/// `rigid mobile drive`: the differential drive of examples/diff_drive.urdf, its wheels under
/// velocity control, moves as its kinematic model on a curve and turning in place: from its CSV,
/// after 0.5 s, the forward speed and yaw rate equal `r (u_L + u_R)/2` and `r (u_R - u_L)/track`
/// of the simulated wheel speeds within 2 % of the motion's speed (computed here, not read from
/// the command's summary); a wheel that is not a joint is named.
#[test]
fn drive_rolls_as_the_kinematic_model_says() {
    let urdf = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/diff_drive.urdf"
    );
    let dir = std::env::temp_dir().join(format!("rigid-drive-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("drive.csv");
    let (r, track) = (0.08, 0.36);
    for speeds in ["5,7", "-3,3"] {
        let o = rigid(&[
            "mobile",
            "drive",
            urdf,
            "--wheels",
            "left_wheel_joint,right_wheel_joint",
            "--speeds",
            speeds,
            "--time",
            "2",
            "--csv",
            csv.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let text = std::fs::read_to_string(&csv).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next(),
            Some("t,x,y,yaw,v,omega,left_wheel_joint,right_wheel_joint")
        );
        let (mut worst_v, mut worst_w) = (0.0f64, 0.0f64);
        for line in lines {
            let c: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
            if c[0] < 0.5 {
                continue;
            }
            let (ul, ur) = (c[6], c[7]);
            let rim = r * (ul.abs() + ur.abs()) / 2.0;
            let (v, w) = (r * (ul + ur) / 2.0, r * (ur - ul) / track);
            worst_v = worst_v.max((c[4] - v).abs() / v.abs().max(rim));
            worst_w = worst_w.max((c[5] - w).abs() / w.abs().max(rim / (track / 2.0)));
        }
        assert!(
            worst_v < 0.02 && worst_w < 0.02,
            "{speeds}: v {worst_v}, ω {worst_w}"
        );
    }
    let o = rigid(&[
        "mobile",
        "drive",
        urdf,
        "--wheels",
        "left_wheel,right_wheel_joint",
        "--speeds",
        "1,1",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("wheel joint \"left_wheel\""),
        "{}",
        stderr(&o)
    );
    std::fs::remove_dir_all(&dir).ok();
}
