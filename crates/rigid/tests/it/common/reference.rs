//! Running the Python reference scripts (`tests/pinocchio/*.py`: Pinocchio and the PyPI
//! description packages, installed by `scripts/test.sh`) and comparing with their output.

use rigid::multibody::Model;
use serde_json::Value;
use std::path::PathBuf;
use std::process::Command;

/// The interpreter: `RIGID_PYTHON`, or `python3`.
pub fn python() -> String {
    std::env::var("RIGID_PYTHON").unwrap_or_else(|_| "python3".into())
}

/// `true` (and a note on stderr) when `RIGID_SKIP_PINOCCHIO=1` asks to skip `what`.
pub fn skip(what: &str) -> bool {
    let skip = std::env::var("RIGID_SKIP_PINOCCHIO").is_ok_and(|v| v == "1");
    if skip {
        eprintln!("RIGID_SKIP_PINOCCHIO=1: skipping {what}");
    }
    skip
}

/// The standard output of `python3 tests/SCRIPT ARGS`, with a message that says what to install
/// when it fails.
pub fn run_script(script: &str, args: &[&str]) -> Vec<u8> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join(script);
    let out = Command::new(python())
        .arg(&path)
        .args(args)
        .output()
        .unwrap_or_else(|e| {
            panic!(
                "cannot run {} ({e}): install Python 3 and run `bash scripts/test.sh`, which \
                 pip-installs Pinocchio and the description packages (or set \
                 RIGID_SKIP_PINOCCHIO=1)",
                python()
            )
        });
    if !out.status.success() {
        let stderr = String::from_utf8_lossy(&out.stderr);
        let hint = if stderr.contains("No module named") || stderr.contains("not installed") {
            "\nRun `bash scripts/test.sh` (it pip-installs scripts/requirements-test.txt), or set \
             RIGID_SKIP_PINOCCHIO=1 to skip the comparisons."
        } else {
            ""
        };
        panic!("{} {args:?} failed:\n{stderr}{hint}", path.display());
    }
    out.stdout
}

/// The folders of the description packages (`packages.py roots`), by package name.
pub fn package_roots() -> std::collections::HashMap<String, PathBuf> {
    let out = run_script("pinocchio/packages.py", &["roots"]);
    let v: Value = serde_json::from_slice(&out).expect("packages.py roots: JSON");
    v.as_object()
        .unwrap()
        .iter()
        .filter_map(|(k, p)| Some((k.clone(), PathBuf::from(p.as_str()?))))
        .collect()
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

/// One JSON record a line of `python3 tests/SCRIPT ARGS`, or `None` (skipped) when
/// `RIGID_SKIP_PINOCCHIO=1`.
pub fn json_lines(script: &str, args: &[&str]) -> Option<Vec<Value>> {
    if skip(script) {
        return None;
    }
    let text = String::from_utf8(run_script(script, args)).expect("UTF-8");
    Some(
        text.lines()
            .map(|l| serde_json::from_str(l).expect("the script printed invalid JSON"))
            .collect(),
    )
}
