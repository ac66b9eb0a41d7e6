//! The cross-checks against references computed outside rigid (Pinocchio, SciPy, the PyPI
//! description packages).
//!
//! Every run compares rigid with checked-in fixtures (`tests/pinocchio/*.json`,
//! `tests/simulation/double_pendulum.json`, each written by the generator script beside it, and
//! the robot files under `tests/fixtures/robots/`): no Python is needed. `RIGID_CROSSCHECK=1`
//! turns on the live checks as well: the reference scripts (`tests/pinocchio/*.py`, ...) run
//! under `RIGID_PYTHON` (else `python3`) with the packages of `scripts/requirements-test.txt`
//! (`bash scripts/test.sh` installs them in a virtual environment and sets both variables), and
//! the generators are re-run to check that the fixtures are still what they write.

use rigid::multibody::Model;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The environment variable that turns the live cross-checks on.
pub const SWITCH: &str = "RIGID_CROSSCHECK";

/// `true` when `RIGID_CROSSCHECK=1`: the tests that need Python (and its packages), a browser,
/// a C compiler, `rustc` or `rustfmt` at test time run too. Unset (or `0`) they do not.
///
/// # Panics
/// On any other value (`true`, `yes`, ...), so that a typo does not turn the checks off quietly.
pub fn crosscheck() -> bool {
    match std::env::var(SWITCH).as_deref() {
        Err(_) | Ok("" | "0") => false,
        Ok("1") => true,
        Ok(other) => panic!("{SWITCH}={other}: set it to 1 to turn the live cross-checks on"),
    }
}

/// [`crosscheck`], saying on stderr that the live check `what` is not run when it is off.
pub fn live(what: &str) -> bool {
    let on = crosscheck();
    if !on {
        eprintln!("{what}: not run ({SWITCH}=1 turns the live cross-checks on)");
    }
    on
}

/// The interpreter of the live checks: `RIGID_PYTHON`, or `python3`.
pub fn python() -> String {
    std::env::var("RIGID_PYTHON").unwrap_or_else(|_| "python3".into())
}

/// What to do when a live check cannot run its reference.
const INSTALL: &str = "RIGID_CROSSCHECK=1 runs the references in Python with the packages of \
     scripts/requirements-test.txt: run `bash scripts/test.sh` (it creates a virtual environment \
     with them and sets RIGID_PYTHON), or point RIGID_PYTHON at an interpreter that has them; \
     without RIGID_CROSSCHECK the tests compare with the checked-in fixtures only";

/// The standard output of `RIGID_PYTHON tests/SCRIPT ARGS`, with a message that says what to
/// install when it fails.
pub fn run_script(script: &str, args: &[&str]) -> Vec<u8> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join(script);
    let out = Command::new(python())
        .arg(&path)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {} ({e}).\n{INSTALL}.", python()));
    if !out.status.success() {
        let stderr = String::from_utf8_lossy(&out.stderr);
        panic!(
            "{} {} {args:?} failed:\n{stderr}\n{INSTALL}.",
            python(),
            path.display()
        );
    }
    out.stdout
}

/// Runs the generator `tests/SCRIPT --check`, which regenerates its fixture in memory and
/// compares it with the committed one to a tolerance; panics with what differs.
pub fn check_generator(script: &str) {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join(script);
    let out = Command::new(python())
        .arg(&path)
        .arg("--check")
        .output()
        .unwrap_or_else(|e| panic!("cannot run {} ({e}).\n{INSTALL}.", python()));
    assert!(
        out.status.success(),
        "{script} --check: the committed fixture is not what the generator writes now \
         (regenerate it: {} {}):\n{}{}",
        python(),
        path.display(),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The folders of the installed description packages (`packages.py roots`), by package name
/// (live checks only).
pub fn package_roots() -> std::collections::HashMap<String, PathBuf> {
    let out = run_script("pinocchio/packages.py", &["roots"]);
    let v: Value = serde_json::from_slice(&out).expect("packages.py roots: JSON");
    v.as_object()
        .unwrap()
        .iter()
        .filter_map(|(k, p)| Some((k.clone(), PathBuf::from(p.as_str()?))))
        .collect()
}

/// The checked-in JSON fixture `tests/REL`.
pub fn fixture(rel: &str) -> Value {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join(rel);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read the fixture {}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The checked-in fixture `tests/REL` of one JSON record a line.
pub fn fixture_lines(rel: &str) -> Vec<Value> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join(rel);
    std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read the fixture {}: {e}", path.display()))
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{}: {e}", path.display())))
        .collect()
}

/// The file a reference record names: an absolute path (a live record, in the installed
/// package), `local:NAME` (beside `tests/pinocchio/`), or a path under `package`'s checked-in
/// folder (a fixture record, [`super::robots`]).
pub fn record_file(package: &str, file: &str) -> PathBuf {
    if let Some(local) = file.strip_prefix("local:") {
        return PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("tests/pinocchio")
            .join(local);
    }
    if Path::new(file).is_absolute() {
        return PathBuf::from(file);
    }
    super::robots(package).join(file)
}

/// `‖a - b‖∞ / max(‖b‖∞, floor)`, infinite for NaN.
pub fn rel(a: &[f64], b: &[f64], floor: f64) -> f64 {
    assert_eq!(a.len(), b.len());
    let diff = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    let e = diff / b.iter().map(|y| y.abs()).fold(floor, f64::max);
    if e.is_nan() {
        f64::INFINITY
    } else {
        e
    }
}

/// `(pq, pv)`: the index in rigid's layout of each coordinate of the reference's layout
/// (Pinocchio's joint order; `joints` lists each joint's name and slices), joints by name.
///
/// # Errors
/// A joint count, a name or a size that differs.
pub fn index_maps(model: &Model, joints: &[Value]) -> Result<(Vec<usize>, Vec<usize>), String> {
    if model.joints().len() != joints.len() {
        return Err(format!(
            "{} moving joints in rigid, {} in the reference",
            model.joints().len(),
            joints.len()
        ));
    }
    let (mut pq, mut pv) = (vec![0; model.nq()], vec![0; model.nv()]);
    for rj in joints {
        let name = rj["name"].as_str().unwrap();
        let field = |k: &str| rj[k].as_u64().unwrap() as usize;
        let id = model
            .joint_id(name)
            .ok_or_else(|| format!("rigid has no joint {name}"))?;
        let j = &model.joints()[id.0];
        if (j.nq, j.nv) != (field("nq"), field("nv")) {
            return Err(format!("joint {name}: nq/nv differ"));
        }
        for t in 0..j.nq {
            pq[field("idx_q") + t] = j.idx_q + t;
        }
        for t in 0..j.nv {
            pv[field("idx_v") + t] = j.idx_v + t;
        }
    }
    Ok((pq, pv))
}

/// `x` in rigid's layout from the reference's.
pub fn to_rigid(x: &[f64], map: &[usize]) -> Vec<f64> {
    let mut out = vec![0.0; x.len()];
    for (k, &r) in map.iter().enumerate() {
        out[r] = x[k];
    }
    out
}

/// One JSON record a line of `RIGID_PYTHON tests/SCRIPT ARGS` (live checks only).
pub fn json_lines(script: &str, args: &[&str]) -> Vec<Value> {
    let text = String::from_utf8(run_script(script, args)).expect("UTF-8");
    text.lines()
        .map(|l| serde_json::from_str(l).expect("the script printed invalid JSON"))
        .collect()
}
