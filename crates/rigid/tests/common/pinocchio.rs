//! Running the Pinocchio reference scripts of `tests/pinocchio/` and matching their joint layout
//! with rigid's.

use rigid::multibody::Model;
use serde_json::Value;
use std::path::PathBuf;
use std::process::Command;

/// Floor of the relative errors: `‖x − y‖∞ / max(‖y‖∞, FLOOR)`.
pub const FLOOR: f64 = 1e-6;

/// The Python interpreter: `RIGID_PYTHON`, else `python3`.
pub fn python() -> String {
    std::env::var("RIGID_PYTHON").unwrap_or_else(|_| "python3".into())
}

/// Runs `tests/pinocchio/SCRIPT PACKAGE ARGS…` and reads one JSON record a line, or `None`
/// when `RIGID_SKIP_PINOCCHIO=1`.
pub fn run_script(script: &str, package: &str, args: &[&str]) -> Option<Vec<Value>> {
    if std::env::var("RIGID_SKIP_PINOCCHIO").is_ok_and(|v| v == "1") {
        eprintln!("RIGID_SKIP_PINOCCHIO=1: not comparing {package} with Pinocchio");
        return None;
    }
    let script = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/pinocchio")
        .join(script);
    let out = Command::new(python())
        .arg(&script)
        .arg(package)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run {} ({e}); run `bash scripts/test.sh`", python()));
    assert!(
        out.status.success(),
        "{} {package} failed (run `bash scripts/test.sh`, which pip-installs the packages):\n{}",
        script.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).expect("UTF-8");
    Some(
        text.lines()
            .map(|l| serde_json::from_str(l).expect("the script printed invalid JSON"))
            .collect(),
    )
}

/// `‖a − b‖∞ / max(‖b‖∞, FLOOR)` (infinite when NaN).
pub fn rel(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let diff = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    let e = diff / b.iter().map(|y| y.abs()).fold(FLOOR, f64::max);
    if e.is_nan() {
        f64::INFINITY
    } else {
        e
    }
}

/// `(pq, pv)`: index of each reference-layout coordinate in rigid's layout, joints by name.
pub fn index_maps(model: &Model, joints: &[Value]) -> Result<(Vec<usize>, Vec<usize>), String> {
    if model.joints().len() != joints.len() {
        return Err(format!(
            "{} moving joints in rigid, {} in Pinocchio",
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

pub fn to_rigid(x: &[f64], map: &[usize]) -> Vec<f64> {
    let mut out = vec![0.0; x.len()];
    for (k, &r) in map.iter().enumerate() {
        out[r] = x[k];
    }
    out
}
