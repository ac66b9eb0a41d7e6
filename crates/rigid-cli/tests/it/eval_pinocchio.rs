//! `rigid eval --json` end to end against Pinocchio: the states of
//! `crates/rigid/tests/pinocchio/reference.py` are written as a CASES.json, run through the
//! binary, and every output compared with Pinocchio's (the same 1e-9 norm-relative tolerance,
//! `‖Δ‖∞ / max(‖ref‖∞, 1e-6)`, as `crates/rigid/tests/it/pinocchio.rs`).
//!
//! Every run uses the checked-in fixture `crates/rigid/tests/pinocchio/reference.json` (written by
//! `gen_reference.py` beside it) and the URDF files checked in under
//! `crates/rigid/tests/fixtures/robots/`; `RIGID_CROSSCHECK=1` adds the live check, `reference.py`
//! run with `RIGID_PYTHON` (or `python3`) with Pinocchio installed (`bash scripts/test.sh`
//! installs it).

use crate::common::{example_robot_data, live, python, rigid_tests};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::process::Command;

fn floats(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(a) => a.iter().flat_map(floats).collect(),
        Value::Number(n) => vec![n.as_f64().unwrap()],
        other => panic!("not a number or array: {other}"),
    }
}

fn rel(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let diff = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    diff / b.iter().map(|y| y.abs()).fold(1e-6, f64::max)
}

/// Pinocchio's references for `robot`: the checked-in fixture's and, with `RIGID_CROSSCHECK=1`,
/// the live one; each with where it comes from.
fn references(robot: &str) -> Vec<(&'static str, Value)> {
    let path = rigid_tests("pinocchio/reference.json");
    let text = std::fs::read_to_string(&path).unwrap();
    let fixture: Value = serde_json::from_str(&text).unwrap();
    let r = fixture["robots"][robot].clone();
    assert!(r.is_object(), "{} has no {robot}", path.display());
    let mut out = vec![("fixture", r)];
    if live(&format!("rigid eval {robot} against Pinocchio live")) {
        let out_ = Command::new(python())
            .arg(rigid_tests("pinocchio/reference.py"))
            .args([robot, "--states", "4", "--seed", "3"])
            .output()
            .unwrap_or_else(|e| {
                panic!(
                    "cannot run {} ({e}): RIGID_CROSSCHECK=1 needs Python with Pinocchio (run \
                     `bash scripts/test.sh`, or set RIGID_PYTHON)",
                    python()
                )
            });
        assert!(
            out_.status.success(),
            "reference.py failed (RIGID_CROSSCHECK=1 needs Python with Pinocchio: run `bash \
             scripts/test.sh`, or set RIGID_PYTHON):\n{}",
            String::from_utf8_lossy(&out_.stderr)
        );
        out.push(("live", serde_json::from_slice(&out_.stdout).unwrap()));
    }
    out
}

/// The URDF file of a reference: the checked-in copy for the fixture's (relative, or `local:`
/// beside the reference scripts), the installed package's for a live one (absolute).
fn urdf_of(r: &Value) -> PathBuf {
    let file = r["urdf"].as_str().unwrap();
    if let Some(local) = file.strip_prefix("local:") {
        rigid_tests("pinocchio").join(local)
    } else if Path::new(file).is_absolute() {
        PathBuf::from(file)
    } else {
        example_robot_data().join(file)
    }
}

fn check(robot: &str) {
    for (source, r) in references(robot) {
        check_with(robot, source, &r);
    }
}

fn check_with(robot: &str, source: &str, r: &Value) {
    // Pinocchio's joint order → rigid's, by name, from `rigid eval`'s own joint list.
    let states = r["states"].as_array().unwrap();
    let urdf = urdf_of(r);
    let urdf = urdf.to_str().unwrap();
    let floating = r["floating"].as_bool().unwrap();
    let probe = std::env::temp_dir().join(format!(
        "rigid-eval-pin-{robot}-{source}-{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&probe).unwrap();
    let run = |cases: &Value| -> Value {
        let path = probe.join("cases.json");
        std::fs::write(&path, cases.to_string()).unwrap();
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_rigid"));
        cmd.args(["eval", urdf, "--cases", path.to_str().unwrap(), "--json"]);
        if floating {
            cmd.arg("--floating");
        }
        let out = cmd.output().unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let nq = r["nq"].as_u64().unwrap() as usize;
    // No case: just the model's joint list.
    let first = run(&json!({ "cases": [] }));
    let ours = first["model"]["joints"].as_array().unwrap();
    let (mut pq, mut pv) = (vec![0; nq], vec![0; r["nv"].as_u64().unwrap() as usize]);
    for rj in r["joints"].as_array().unwrap() {
        let j = ours
            .iter()
            .find(|j| j["name"] == rj["name"])
            .expect("same joints");
        let f = |v: &Value, k: &str| v[k].as_u64().unwrap() as usize;
        assert_eq!((f(j, "nq"), f(j, "nv")), (f(rj, "nq"), f(rj, "nv")));
        for t in 0..f(j, "nq") {
            pq[f(rj, "idx_q") + t] = f(j, "idx_q") + t;
        }
        for t in 0..f(j, "nv") {
            pv[f(rj, "idx_v") + t] = f(j, "idx_v") + t;
        }
    }
    let place = |x: &Value, map: &[usize]| {
        let x = floats(x);
        let mut out = vec![0.0; x.len()];
        for (k, &m) in map.iter().enumerate() {
            out[m] = x[k];
        }
        out
    };
    let cases: Vec<Value> = states
        .iter()
        .map(|s| {
            json!({"q": place(&s["q"], &pq), "v": place(&s["v"], &pv),
                   "a": place(&s["a"], &pv), "tau": place(&s["tau"], &pv)})
        })
        .collect();
    let out = run(&json!({ "cases": cases }));
    let results = out["results"].as_array().unwrap();
    assert_eq!(results.len(), states.len());
    let mut worst = 0.0f64;
    for (res, s) in results.iter().zip(states) {
        let back = |x: &Value| -> Vec<f64> {
            let x = floats(x);
            pv.iter().map(|&m| x[m]).collect()
        };
        for key in ["rnea", "aba", "nonlinear_effects", "gravity_torques"] {
            let e = rel(&back(&res[key]), &floats(&s[key]));
            assert!(e < 1e-9, "{robot} {key}: {e:e}");
            worst = worst.max(e);
        }
        let m = &res["mass_matrix"];
        let m_ours: Vec<f64> = (0..pv.len())
            .flat_map(|i| (0..pv.len()).map(move |j| (i, j)))
            .map(|(i, j)| m[pv[i]][pv[j]].as_f64().unwrap())
            .collect();
        let e = rel(&m_ours, &floats(&s["mass_matrix"]));
        assert!(e < 1e-9, "{robot} mass_matrix: {e:e}");
        worst = worst.max(e);
        for key in ["kinetic_energy", "potential_energy", "com"] {
            let e = rel(&floats(&res[key]), &floats(&s[key]));
            assert!(e < 1e-9, "{robot} {key}: {e:e}");
            worst = worst.max(e);
        }
        let e = rel(&floats(&res["total_mass"]), &floats(&r["total_mass"]));
        assert!(e < 1e-9, "{robot} total_mass: {e:e}");
        for (name, p) in s["placements"].as_object().unwrap() {
            let ours = &res["placements"][name];
            let e = rel(&floats(&ours["translation"]), &floats(&p["translation"]))
                .max(rel(&floats(&ours["rotation"]), &floats(&p["rotation"])));
            assert!(e < 1e-9, "{robot} placement of {name}: {e:e}");
            worst = worst.max(e);
        }
    }
    eprintln!("rigid eval {robot} ({source}): max relative error vs Pinocchio {worst:.1e}");
}

#[test]
fn eval_json_agrees_with_pinocchio_on_every_joint_type() {
    check("all_joints_floating");
}

#[test]
fn eval_json_agrees_with_pinocchio_on_talos() {
    check("talos");
}
