//! `rigid simulate`: the CSV contract, the plot, the summary, and clean failures on bad input.

use std::path::PathBuf;
use std::process::{Command, Output};

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigid-simulate-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn rigid(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(args)
        .output()
        .unwrap()
}

/// A box 0.3 x 0.2 x 0.05 m of 1 kg whose centre is at (0, 0, 0.5) of the spec frame.
const BOX: &str = r#"
[[part]]
shape = "box"
size = [0.3, 0.2, 0.05]
mass = 1.0
position = [0.0, 0.0, 0.5]
"#;

fn spec(dir: &std::path::Path, text: &str) -> String {
    let p = dir.join("body.toml");
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_owned()
}

fn rows(csv: &str) -> Vec<Vec<f64>> {
    csv.lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect()
}

#[test]
fn writes_the_csv_with_the_exact_header_and_one_row_per_step() {
    let dir = scratch("csv");
    let body = spec(&dir, BOX);
    let csv = dir.join("out.csv");
    let out = rigid(&[
        "simulate",
        &body,
        "--omega",
        "0.01,3,0.01",
        "--velocity",
        "1,0,0",
        "--duration",
        "0.5",
        "--dt",
        "0.01",
        "--integrator",
        "rk4",
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(
        text.lines().next().unwrap(),
        "t,px,py,pz,qx,qy,qz,qw,wx,wy,wz,vx,vy,vz"
    );
    let r = rows(&text);
    assert_eq!(r.len(), 51);
    // Starts aligned with the world, CoM at the origin, with the given twist.
    assert_eq!(
        r[0],
        vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.01, 3.0, 0.01, 1.0, 0.0, 0.0]
    );
    let last = r.last().unwrap();
    assert!((last[0] - 0.5).abs() < 1e-12);
    assert!(last.iter().all(|x| x.is_finite()));
    // Unit quaternion; the CoM moves with the world velocity (no force), which is R v_b.
    let q = &last[4..8];
    assert!((q.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-12);
    assert!(
        (last[1] - 0.5).abs() < 1e-6 && last[2].abs() < 1e-6,
        "{last:?}"
    );
    let summary = String::from_utf8_lossy(&out.stdout);
    for key in [
        "steps: 50",
        "relative energy error",
        "relative angular momentum error",
        "wall time",
    ] {
        assert!(summary.contains(key), "{summary}");
    }
}

#[test]
fn pivot_puts_the_pivot_at_the_world_origin_and_plots_an_svg() {
    let dir = scratch("pivot");
    let body = spec(&dir, BOX);
    let (csv, svg) = (dir.join("p.csv"), dir.join("p.svg"));
    let out = rigid(&[
        "simulate",
        &body,
        "--pivot",
        "0,0,0",
        "--omega",
        "1,0,0",
        "--gravity",
        "0,0,-9.81",
        "--duration",
        "1",
        "--dt",
        "0.01",
        "--csv",
        csv.to_str().unwrap(),
        "--plot",
        svg.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let r = rows(&std::fs::read_to_string(&csv).unwrap());
    // The CoM frame starts 0.5 m above the pivot, and stays 0.5 m away from it.
    assert_eq!(&r[0][1..4], &[0.0, 0.0, 0.5]);
    for row in &r {
        let d = (row[1] * row[1] + row[2] * row[2] + row[3] * row[3]).sqrt();
        assert!((d - 0.5).abs() < 1e-12, "{row:?}");
    }
    // The CoM velocity is ω × r in CoM-frame axes: (1,0,0) × (0,0,0.5) = (0,-0.5,0) at t = 0.
    assert_eq!(&r[0][11..14], &[0.0, -0.5, 0.0]);
    let svg = std::fs::read_to_string(&svg).unwrap();
    assert!(
        svg.starts_with("<svg") && svg.contains("polyline"),
        "{}",
        &svg[..200.min(svg.len())]
    );
}

/// Runs a bad command: non-zero exit, an `error:` line, no panic, no output file with NaN.
fn fails_cleanly(args: &[&str], expect: &str) {
    let out = rigid(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{args:?} succeeded");
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        err.to_lowercase().contains(expect),
        "{args:?}: expected {expect:?} in {err}"
    );
}

#[test]
fn bad_inputs_fail_cleanly() {
    let dir = scratch("bad");
    let body = spec(&dir, BOX);
    let b = body.as_str();
    fails_cleanly(&["simulate", b, "--dt", "0"], "dt");
    fails_cleanly(&["simulate", b, "--dt", "-0.1"], "dt");
    fails_cleanly(&["simulate", b, "--dt", "nan"], "dt");
    fails_cleanly(&["simulate", b, "--duration", "inf"], "duration");
    fails_cleanly(&["simulate", b, "--omega", "nan,0,0"], "finite");
    fails_cleanly(&["simulate", b, "--omega", "1,2"], "three numbers");
    fails_cleanly(&["simulate", b, "--gravity", "0,0,inf"], "finite");
    fails_cleanly(&["simulate", b, "--integrator", "euler"], "integrator");
    fails_cleanly(
        &["simulate", b, "--pivot", "0,0,0", "--velocity", "1,0,0"],
        "pivot",
    );
    fails_cleanly(
        &["simulate", &dir.join("missing.toml").to_string_lossy()],
        "cannot read",
    );
    let massless = spec(
        &scratch("massless"),
        "[[part]]\nshape = \"sphere\"\nradius = 0.1\nmass = 0.0\n",
    );
    fails_cleanly(
        &["simulate", &massless, "--pivot", "0,0,1"],
        "field `mass`: must be positive",
    );
    fails_cleanly(&["simulate", &massless], "mass");
    let negative = spec(
        &scratch("negative"),
        "[[part]]\nshape = \"box\"\nsize = [1, -1, 1]\nmass = 1.0\n",
    );
    fails_cleanly(&["simulate", &negative], "positive");
    // A point-like body on its own centre: the inertia about the pivot is singular.
    let rod = spec(
        &scratch("rod"),
        "[[part]]\nshape = \"cylinder\"\nradius = 1e-12\nlength = 1\nmass = 1.0\n",
    );
    fails_cleanly(&["simulate", &rod], "singular");
    let garbage = spec(
        &scratch("garbage"),
        "[[part]]\nshape = \"box\"\nsize = \"big\"\n",
    );
    fails_cleanly(&["simulate", &garbage], "error");
}

#[test]
fn robot_csv_has_joint_named_columns_and_one_row_per_step() {
    let dir = scratch("robot-csv");
    let csv = dir.join("dp.csv");
    let svg = dir.join("dp.svg");
    let out = rigid(&[
        "simulate",
        "double_pendulum",
        "--q0",
        "0.5,-0.2",
        "--duration",
        "0.01",
        "--controller",
        "gravity",
        "--csv",
        csv.to_str().unwrap(),
        "--plot",
        svg.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(
        text.lines().next().unwrap(),
        "t,q_joint1,q_joint2,v_joint1,v_joint2,tau_joint1,tau_joint2,energy"
    );
    let r = rows(&text);
    assert_eq!(r.len(), 11, "t = 0 and 10 steps");
    // gravity compensation holds the arm: q stays, τ = g(q) ≠ 0
    for row in &r {
        assert!((row[1] - 0.5).abs() < 1e-12 && (row[2] + 0.2).abs() < 1e-12);
        assert!(row[5].abs() > 1.0);
    }
    let svg = std::fs::read_to_string(&svg).unwrap();
    assert!(svg.contains("joint velocities") && svg.contains("total energy"));
    let stdout = String::from_utf8_lossy(&out.stdout);
    for key in [
        "relative drift",
        "max joint speed",
        "final q: joint1=0.500000",
    ] {
        assert!(stdout.contains(key), "{key} missing from:\n{stdout}");
    }
    // no temporary file left behind
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left.len(), 2, "{left:?}");
}

#[test]
fn robot_bad_inputs_fail_cleanly() {
    for (args, expected) in [
        (
            &["simulate", "double_pendulum", "--q0", "1,2,3"][..],
            "--q0 has 3 numbers",
        ),
        (
            &["simulate", "double_pendulum", "--controller", "pd"][..],
            "needs --target",
        ),
        (
            &["simulate", "double_pendulum", "--controller", "fly"][..],
            "expected none, gravity, pd or track",
        ),
        (
            &["simulate", "double_pendulum", "--integrator", "leapfrog"][..],
            "unknown integrator",
        ),
        (&["simulate", "no_such_robot"][..], "unknown model"),
        (
            &["view", "pendulum", "--q", "1,2", "--html", "x.html"][..],
            "--q has 2 numbers",
        ),
    ] {
        let out = rigid(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(expected), "{args:?}: {err}");
    }
}

#[test]
fn view_writes_a_self_contained_page() {
    let dir = scratch("view");
    let html = dir.join("p.html");
    let out = rigid(&[
        "view",
        "puma560",
        "--q",
        "0,0.5,-0.5,0,0.3,0",
        "--html",
        html.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let page = std::fs::read_to_string(&html).unwrap();
    assert!(page.contains("<canvas") && page.contains("Content-Security-Policy"));
    // nothing to fetch: no external URL in a src or href
    assert!(!page.contains("src=\"http") && !page.contains("href=\"http"));
}

/// A chain of `n` hinges named `hinge_a`, `hinge_b`, … (axis y, 0.1 m apart, 1 kg links).
fn chain_urdf(dir: &std::path::Path, n: usize) -> PathBuf {
    let name = |k: usize| format!("hinge_{}", (b'a' + k as u8) as char);
    let mut urdf = String::from(r#"<robot name="chain"><link name="base"/>"#);
    for k in 0..n {
        let parent = if k == 0 {
            "base".to_string()
        } else {
            format!("link{}", k - 1)
        };
        urdf += &format!(
            r#"<link name="link{k}"><inertial><origin xyz="0 0 -0.05"/><mass value="1"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
<joint name="{}" type="continuous"><parent link="{parent}"/><child link="link{k}"/><origin xyz="0 0 -0.1"/><axis xyz="0 1 0"/></joint>"#,
            name(k)
        );
    }
    urdf += "</robot>";
    let path = dir.join(format!("chain{n}.urdf"));
    std::fs::write(&path, urdf).unwrap();
    path
}

/// The texts of the SVG plot's joint-position panel of the chain of `n` hinges held (gravity
/// compensation) at `q_k = 0.05 (k + 1)`: from its caption to the next panel's.
fn chain_position_panel(n: usize) -> Vec<String> {
    let dir = scratch(&format!("legend{n}"));
    let urdf = chain_urdf(&dir, n);
    let svg = dir.join("chain.svg");
    let q0: Vec<String> = (0..n)
        .map(|k| format!("{}", 0.05 * (k + 1) as f64))
        .collect();
    let out = rigid(&[
        "simulate",
        urdf.to_str().unwrap(),
        "--q0",
        &q0.join(","),
        "--controller",
        "gravity",
        "--duration",
        "0.01",
        "--plot",
        svg.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    let start = text.find("joint positions").unwrap();
    let end = start + text[start..].find("joint velocities").unwrap();
    text[start..end]
        .split("<text")
        .skip(1)
        .filter_map(|t| Some(t.split_once('>')?.1.split_once('<')?.0.trim().to_string()))
        .collect()
}

#[test]
fn a_plot_of_many_joints_names_the_six_largest_and_counts_the_others() {
    // 14 hinges: the legend names the six that reach the largest |q| (the last six), and says
    // how many others are drawn unnamed
    let panel = chain_position_panel(14);
    for c in 'a'..='n' {
        let name = format!("hinge_{c}");
        assert_eq!(panel.contains(&name), c >= 'i', "{name} in {panel:?}");
    }
    assert!(
        panel
            .iter()
            .any(|t| t.starts_with("8 others in grey, unnamed")),
        "{panel:?}"
    );
    // 12 hinges: every one named, no note
    let panel = chain_position_panel(12);
    for c in 'a'..='l' {
        assert!(panel.contains(&format!("hinge_{c}")), "{panel:?}");
    }
    assert!(!panel.iter().any(|t| t.contains("others in grey")));
}
