//! `rigid eval ... --constraints K.json` (docs/conventions.md): the fixture cases of the library's
//! Pinocchio cross-check (`crates/rigid/tests/fixtures/constraints/pinocchio.json`, Pinocchio
//! 4.1's `constraintDynamics` and `impulseDynamics`) run through the command line in Pinocchio's
//! layout give Pinocchio's numbers; in rigid's layout a wrench is moment first; bad files are
//! named errors.

use serde_json::Value;
use std::path::PathBuf;
use std::process::Command;

fn fixtures() -> PathBuf {
    crate::common::rigid_tests("fixtures/constraints")
}

fn temp_file(tag: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("rigid-cli-constraints-{}", std::process::id()));
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

/// `max |x − y| / max(1, ‖y‖∞)`.
fn rel_err(x: &[f64], y: &[f64]) -> f64 {
    assert_eq!(x.len(), y.len());
    let scale = y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    x.iter()
        .zip(y)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale
}

/// Runs one fixture case through `rigid eval --layout pinocchio --constraints` and returns the
/// output beside the case.
fn run_case(name: &str, layout: &str) -> (Value, Value) {
    let text = std::fs::read_to_string(fixtures().join("pinocchio.json")).unwrap();
    let doc: Value = serde_json::from_str(&text).unwrap();
    let case = doc["cases"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == name)
        .unwrap()
        .clone();
    let urdf = fixtures().join(case["urdf"].as_str().unwrap());
    let states: Vec<Value> = case["states"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            // Pinocchio's free-flyer velocity is linear first, rigid's angular first
            let swap = |x: &Value| {
                let mut x = numbers(x);
                if layout == "rigid" && case["floating"].as_bool().unwrap() {
                    x[..6].rotate_left(3);
                }
                x
            };
            serde_json::json!({"q": s["q"], "v": swap(&s["v"]), "tau": swap(&s["tau"])})
        })
        .collect();
    let cases = temp_file(
        &format!("{name}-cases.json"),
        &serde_json::json!({ "cases": states }).to_string(),
    );
    let k = temp_file(&format!("{name}-k.json"), &case.to_string());
    let mut args = vec![
        "eval",
        urdf.to_str().unwrap(),
        "--cases",
        &cases,
        "--constraints",
        &k,
        "--json",
        "--layout",
        layout,
    ];
    if case["floating"].as_bool().unwrap() {
        args.push("--floating");
    }
    let out = rigid(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (serde_json::from_slice(&out.stdout).unwrap(), case)
}

#[test]
fn eval_constraints_gives_pinocchio_numbers_in_its_layout() {
    for name in [
        "solo12_4_points_local_baumgarte",
        "talos_2_frames_world_aligned",
        "anymal_2_points_local",
    ] {
        let (out, case) = run_case(name, "pinocchio");
        for (r, s) in out["results"]
            .as_array()
            .unwrap()
            .iter()
            .zip(case["states"].as_array().unwrap())
        {
            let cd = &r["constraint_dynamics"];
            let id = &r["impulse_dynamics"];
            for (got, want) in [
                (&cd["ddq"], &s["ddq"]),
                (&cd["lambda"], &s["lambda"]),
                (&id["dq_plus"], &s["dq_plus"]),
                (&id["impulse"], &s["impulse"]),
            ] {
                let e = rel_err(&numbers(got), &numbers(want));
                assert!(e < 1e-9, "{name}: {e:e}");
            }
            assert!(
                r["aba"].is_array() && r["rnea"].is_array(),
                "the other keys stay"
            );
        }
    }
}

/// In rigid's layout the free-flyer velocity is angular first and a wrench moment first (models
/// whose sibling joints are in name order in the file, so that both layouts have one joint order).
#[test]
fn eval_constraints_in_rigid_layout_is_angular_first() {
    let (pin, _) = run_case("closed_chain_frame_world_aligned_baumgarte", "pinocchio");
    let (own, _) = run_case("closed_chain_frame_world_aligned_baumgarte", "rigid");
    let (p, o) = (&pin["results"][0], &own["results"][0]);
    let lambda = |r: &Value| numbers(&r["constraint_dynamics"]["lambda"]);
    let (lp, lo) = (lambda(p), lambda(o));
    assert_eq!((&lo[..3], &lo[3..]), (&lp[3..], &lp[..3]));
    assert_eq!(
        p["constraint_dynamics"]["ddq"],
        o["constraint_dynamics"]["ddq"]
    );
    let (pin, _) = run_case("solo12_4_points_local_baumgarte", "pinocchio");
    let (own, _) = run_case("solo12_4_points_local_baumgarte", "rigid");
    let (p, o) = (&pin["results"][0], &own["results"][0]);
    let ddq = |r: &Value| numbers(&r["constraint_dynamics"]["ddq"]);
    let (dp, dd) = (ddq(p), ddq(o));
    assert_eq!(
        (&dd[..3], &dd[3..6], &dd[6..]),
        (&dp[3..6], &dp[..3], &dp[6..])
    );
    assert_eq!(lambda(p), lambda(o));
}

#[test]
fn eval_constraints_errors_name_the_file_and_the_constraint() {
    let urdf = fixtures().join("fourbar.urdf");
    let cases = temp_file("fb-cases.json", r#"{"cases": [{"q": [0.1, 0.2, 0.3]}]}"#);
    let bad = temp_file(
        "fb-bad.json",
        r#"{"constraints": [{"type": "point", "joint1": "elbow"}]}"#,
    );
    let out = rigid(&[
        "eval",
        urdf.to_str().unwrap(),
        "--cases",
        &cases,
        "--constraints",
        &bad,
        "--json",
    ]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("fb-bad.json: constraint 0: \"joint1\": no joint named \"elbow\""),
        "{err}"
    );
    // the planar loop closed by a 3D point is redundant: with mu = 0 it is refused, with mu > 0 solved
    let k = r#"{"constraints": [{"type": "point", "joint1": "coupler_joint", "placement1": {"translation": [0.8, 0, 0]}, "joint2": "rocker_joint", "placement2": {"translation": [0.6, 0, 0]}}], "mu": MU}"#;
    let exact = temp_file("fb-exact.json", &k.replace("MU", "0"));
    let out = rigid(&[
        "eval",
        urdf.to_str().unwrap(),
        "--cases",
        &cases,
        "--constraints",
        &exact,
        "--json",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success()
            && err.contains("case 0: constraint_dynamics: the constraints are redundant"),
        "{err}"
    );
    let prox = temp_file("fb-prox.json", &k.replace("MU", "1e-4"));
    let out = rigid(&[
        "eval",
        urdf.to_str().unwrap(),
        "--cases",
        &cases,
        "--constraints",
        &prox,
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// `--constraints MODEL.xml`: the MJCF file's own `<connect>` closes fourbar.xml's loop, and the
/// accelerations and pin force equal those of fourbar.urdf closed by a constraint file (its `q`
/// shifted by the assembly angles of fourbar.xml); in MuJoCo's layout too (hinges: the same
/// numbers). Another file than the model's is refused.
#[test]
fn mjcf_equalities_close_the_loop() {
    let xml = fixtures().join("fourbar.xml");
    let xml = xml.to_str().unwrap();
    let urdf = fixtures().join("fourbar.urdf");
    let (q, v, tau) = ([0.1, -0.2, 0.05], [0.5, -1.0, 0.3], [0.2, 0.0, -0.1]);
    let assembly = [0.5, 0.02116623166979137, 1.1280269456729848];
    let q_urdf: Vec<f64> = q.iter().zip(assembly).map(|(a, b)| a + b).collect();
    let case = |q: &[f64]| {
        format!(r#"{{"cases": [{{"q": {q:?}, "v": {v:?}, "a": [0, 0, 0], "tau": {tau:?}}}]}}"#)
    };
    let closure = r#"{"constraints": [{"type": "point", "joint1": "coupler_joint",
        "placement1": {"translation": [0.8, 0, 0]}, "joint2": "rocker_joint",
        "placement2": {"translation": [0.6, 0, 0]}, "reference_frame": "local_world_aligned"}],
        "mu": 1e-6, "max_iter": 1000}"#;
    let result = |args: &[&str]| -> Value {
        let out = rigid(args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let doc: Value = serde_json::from_slice(&out.stdout).unwrap();
        doc["results"][0]["constraint_dynamics"].clone()
    };
    let (cases_x, cases_u) = (
        temp_file("fb_x.json", &case(&q)),
        temp_file("fb_u.json", &case(&q_urdf)),
    );
    let by_file = temp_file("fb_k.json", closure);
    let reference = result(&[
        "eval",
        urdf.to_str().unwrap(),
        "--cases",
        &cases_u,
        "--constraints",
        &by_file,
        "--json",
    ]);
    for layout in ["rigid", "mujoco"] {
        let got = result(&[
            "eval",
            xml,
            "--cases",
            &cases_x,
            "--constraints",
            xml,
            "--layout",
            layout,
            "--json",
        ]);
        let lambda = numbers(&reference["lambda"]); // a point: three numbers in either layout
        assert!(
            rel_err(&numbers(&got["ddq"]), &numbers(&reference["ddq"])) < 1e-9,
            "{layout}: {got}"
        );
        assert!(
            rel_err(&numbers(&got["lambda"]), &lambda) < 1e-9,
            "{layout}: {got}"
        );
    }
    let out = rigid(&[
        "eval",
        urdf.to_str().unwrap(),
        "--cases",
        &cases_u,
        "--constraints",
        xml,
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("the <equality> constraints of an MJCF file apply to the model read from it"),
        "{err}"
    );
}

/// `rigid simulate fourbar.xml --constraints fourbar.xml`: the MJCF four-bar turns 2 s on its
/// `<connect>`, the loop held (violation ≤ 1e-9 in every CSV row) and the energy kept (change
/// ≤ 1e-6 of its scale); the flags that do not apply are refused by name.
#[test]
fn simulate_closes_the_loop() {
    let xml = fixtures().join("fourbar.xml");
    let xml = xml.to_str().unwrap();
    let csv = temp_file("fb_sim.csv", "");
    let out = rigid(&[
        "simulate",
        xml,
        "--constraints",
        xml,
        "--duration",
        "2",
        "--v0",
        "2,0,0",
        "--csv",
        &csv,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (e, p, v) = (
        col("energy"),
        col("violation_position"),
        col("violation_velocity"),
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 2001);
    let e0 = rows[0][e];
    for r in &rows {
        assert!(
            r[p] <= 1e-9 && r[v] <= 1e-9,
            "t = {}: {} {}",
            r[0],
            r[p],
            r[v]
        );
        assert!(
            (r[e] - e0).abs() <= 1e-6 * e0.abs().max(1.0),
            "t = {}: energy {}",
            r[0],
            r[e]
        );
    }
    // the crank turns: the loop is in motion, not stuck
    let crank = col("q_crank_joint");
    assert!((rows[2000][crank] - rows[0][crank]).abs() > 0.1);
    // the file's own <equality> is held without the flag: the same run, the same numbers
    let again = temp_file("fb_sim_own.csv", "");
    let out = rigid(&[
        "simulate",
        xml,
        "--duration",
        "2",
        "--v0",
        "2,0,0",
        "--csv",
        &again,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(std::fs::read_to_string(&again).unwrap(), text);
    // a controller acts on the closed loop too: gravity compensation holds it still
    let held = temp_file("fb_sim_held.csv", "");
    let out = rigid(&[
        "simulate",
        xml,
        "--controller",
        "gravity",
        "--duration",
        "1",
        "--csv",
        &held,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&held).unwrap();
    let last: Vec<f64> = text
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    let first: Vec<f64> = text
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    assert!(
        (last[crank] - first[crank]).abs() < 1e-6,
        "{} -> {}",
        first[crank],
        last[crank]
    );
    // a body spec has no loops to close
    let spec = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/compound.toml");
    let out = rigid(&["simulate", spec.to_str().unwrap(), "--constraints", xml]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--constraints applies to a robot"));
}

/// `--derivatives` with `--constraints` in Pinocchio's layout: TALOS's two 6D soles (local frame,
/// Baumgarte gains) of `pinocchio_derivatives.json` give Pinocchio 4.1's
/// `computeConstraintDynamicsDerivatives` and `computeImpulseDynamicsDerivatives` (its `ddq_dv`
/// plus the identity) to 1e-9.
#[test]
fn derivatives_with_constraints_equal_pinocchio() {
    let text = std::fs::read_to_string(fixtures().join("pinocchio_derivatives.json")).unwrap();
    let doc: Value = serde_json::from_str(&text).unwrap();
    let case = doc["cases"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["name"] == "talos_2_frames_local_baumgarte")
        .unwrap();
    let urdf = fixtures().join(case["urdf"].as_str().unwrap());
    let cases = temp_file(
        "derivatives-cases.json",
        &serde_json::json!({"cases": [{"q": case["q"], "v": case["v"], "tau": case["tau"]}]})
            .to_string(),
    );
    let file = temp_file("derivatives-constraints.json", &case.to_string());
    let out = rigid(&[
        "eval",
        urdf.to_str().unwrap(),
        "--floating",
        "--cases",
        &cases,
        "--constraints",
        &file,
        "--derivatives",
        "--layout",
        "pinocchio",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let r: Value = serde_json::from_slice(&out.stdout).unwrap();
    let r = &r["results"][0];
    let flat = |v: &Value| -> Vec<f64> { v.as_array().unwrap().iter().flat_map(numbers).collect() };
    for (group, keys) in [
        (
            "constraint_dynamics_derivatives",
            &[
                "ddq_dq",
                "ddq_dv",
                "ddq_dtau",
                "dlambda_dq",
                "dlambda_dv",
                "dlambda_dtau",
            ][..],
        ),
        (
            "impulse_dynamics_derivatives",
            &["dvplus_dq", "dvplus_dv", "dimpulse_dq", "dimpulse_dv"][..],
        ),
    ] {
        for k in keys {
            let e = rel_err(&flat(&r[group][k]), &flat(&case["pinocchio"][k]));
            assert!(e < 1e-9, "{group}.{k}: {e:.1e}");
        }
    }
}
