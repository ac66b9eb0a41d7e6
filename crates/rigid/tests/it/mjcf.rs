//! MJCF import against MuJoCo: the checked-in fixtures (`tests/mujoco/fixtures`, written by
//! `tests/mujoco/reference.py fixtures` from the models in `tests/mujoco/models`) in every run,
//! and, with `RIGID_CROSSCHECK=1`, every MJCF file of the description packages installed next to
//! the `mujoco` Python package of `RIGID_PYTHON` (`reference.py live`).
//!
//! Each state is compared in MuJoCo's coordinates ([`MujocoLayout`]): the mass matrix with
//! `mj_fullM` (armature included), the bias with `qfrc_bias`, the gravity forces with the bias at
//! `qvel = 0`, inverse dynamics with `M qacc + qfrc_bias`, forward dynamics with
//! `M⁻¹ (qfrc - qfrc_bias)`. Tolerance: `1e-9` relative to the largest entry of the reference (to
//! the mass matrix's largest entry times 1 m/s² for a force whose reference is smaller), `1e-6`
//! where a mesh carries inertia (MuJoCo keeps mesh vertices in float32).

use rigid::interop::MujocoLayout;
use rigid::io::mjcf::{load_mjcf, MjcfModel};
use rigid::multibody::Data;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn here() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/mujoco")
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

fn matrix(v: &Value) -> Vec<Vec<f64>> {
    v.as_array().expect("rows").iter().map(numbers).collect()
}

/// The largest `|a - b|` over the largest `|b|` (at least `floor`).
fn relative(a: &[f64], b: &[f64], floor: f64) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(floor, |m, x| m.max(x.abs()));
    let d = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    if d == 0.0 {
        0.0
    } else {
        d / scale
    }
}

/// The worst relative error of rigid against MuJoCo's references at every state of `reference`
/// (the JSON of `reference.py`), and what it was on.
fn compare(m: &MjcfModel, reference: &Value) -> (f64, String) {
    let model = &m.model;
    let layout: MujocoLayout = m.layout();
    let mut data = Data::new(model);
    let mut worst = (0.0, String::new());
    for (i, s) in reference["states"].as_array().unwrap().iter().enumerate() {
        let qpos = numbers(&s["qpos"]);
        let (u, a, f) = (
            numbers(&s["qvel"]),
            numbers(&s["qacc"]),
            numbers(&s["qfrc"]),
        );
        let mut q = vec![0.0; model.nq()];
        layout.q_from_mujoco(&qpos, &mut q).unwrap();
        let mm = layout.mass_matrix(model, &mut data, &q).unwrap();
        let m_ref: Vec<f64> = matrix(&s["mass_matrix"]).concat();
        let m_rig: Vec<f64> = (0..model.nv())
            .flat_map(|r| (0..model.nv()).map(move |c| (r, c)))
            .map(|(r, c)| mm[(r, c)])
            .collect();
        let floor = m_ref.iter().fold(0.0f64, |x, y| x.max(y.abs()));
        let bias = layout.nonlinear_effects(model, &mut data, &q, &u).unwrap();
        let g = layout.gravity_torques(model, &mut data, &q).unwrap();
        let tau = layout.rnea(model, &mut data, &q, &u, &a).unwrap();
        let aba = match s["aba"].is_null() {
            true => 0.0, // M singular: MuJoCo has no forward dynamics either
            false => {
                let acc = layout.aba(model, &mut data, &q, &u, &f).unwrap();
                relative(acc.as_slice(), &numbers(&s["aba"]), 1.0)
            }
        };
        let errors = [
            ("mass_matrix", relative(&m_rig, &m_ref, 0.0)),
            (
                "bias",
                relative(bias.as_slice(), &numbers(&s["bias"]), floor),
            ),
            (
                "gravity",
                relative(g.as_slice(), &numbers(&s["gravity"]), floor),
            ),
            (
                "rnea",
                relative(tau.as_slice(), &numbers(&s["rnea"]), floor),
            ),
            ("aba", aba),
        ];
        for (what, e) in errors {
            if e > worst.0 || e.is_nan() {
                worst = (e, format!("{what} at state {i}"));
            }
        }
    }
    worst
}

/// Two MuJoCo configurations equal to 1e-12, a quaternion and its negative being one orientation.
fn same_qpos(m: &MjcfModel, a: &[f64], b: &[f64]) -> bool {
    use rigid::io::mjcf::MjcfJointKind;
    m.joints.iter().all(|j| {
        let joint = &m.model.joints()[j.id.0];
        let (x, y) = (&a[joint.coordinates()], &b[joint.coordinates()]);
        let close = |x: &[f64], y: &[f64]| x.iter().zip(y).all(|(p, q)| (p - q).abs() < 1e-12);
        match j.kind {
            MjcfJointKind::Free => {
                let neg: Vec<f64> = y[3..].iter().map(|v| -v).collect();
                close(&x[..3], &y[..3]) && (close(&x[3..], &y[3..]) || close(&x[3..], &neg))
            }
            MjcfJointKind::Ball => {
                let neg: Vec<f64> = y.iter().map(|v| -v).collect();
                close(x, y) || close(x, &neg)
            }
            MjcfJointKind::Hinge | MjcfJointKind::Slide => close(x, y),
        }
    })
}

/// 1e-9, or 1e-6 where meshes carry inertia.
fn tolerance(reference: &Value) -> f64 {
    if reference["mesh_inertia"].as_bool().unwrap_or(false) {
        1e-6
    } else {
        1e-9
    }
}

#[test]
fn checked_in_models_match_mujocos_dynamics() {
    let dir = here();
    let mut seen = 0;
    for entry in std::fs::read_dir(dir.join("fixtures")).unwrap() {
        let path = entry.unwrap().path();
        let reference: Value =
            serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let file = dir.join(reference["file"].as_str().unwrap());
        let m = load_mjcf(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        assert_eq!(m.model.nq() as u64, reference["nq"].as_u64().unwrap());
        assert_eq!(m.model.nv() as u64, reference["nv"].as_u64().unwrap());
        // MuJoCo's joint order and names (unnamed joints get rigid's names)
        for (j, name) in m.joints.iter().zip(reference["joints"].as_array().unwrap()) {
            if let Some(n) = name.as_str() {
                assert_eq!(j.name, n, "{}", path.display());
            }
        }
        let q0 = numbers(&reference["qpos0"]);
        assert!(
            same_qpos(&m, &m.qpos0, &q0),
            "{}: qpos0 {:?}",
            path.display(),
            m.qpos0
        );
        let total: f64 = m.bodies.iter().map(|b| b.mass).sum();
        let want = reference["total_mass"].as_f64().unwrap();
        assert!(
            (total - want).abs() <= 1e-12 * want,
            "{}: {total} vs {want}",
            path.display()
        );
        let (err, what) = compare(&m, &reference);
        let tol = tolerance(&reference);
        assert!(
            err <= tol,
            "{}: {what}: relative error {err:e} > {tol:e}",
            path.display()
        );
        seen += 1;
    }
    assert!(seen >= 9, "only {seen} fixtures");
}

/// Per package: files, compiled by MuJoCo, loaded by rigid, matching.
#[derive(Default)]
struct Counts {
    files: usize,
    compiled: usize,
    loaded: usize,
    matching: usize,
}

/// Every MJCF file of the installed description packages (`RIGID_CROSSCHECK=1`): each file that
/// MuJoCo compiles must load and match, except where rigid says why not (a tendon armature,
/// which rigid does not model), and its `<equality>` elements convert to constraint models.
#[test]
fn every_package_model_that_mujoco_compiles_matches() {
    if std::env::var("RIGID_CROSSCHECK").as_deref() != Ok("1") {
        eprintln!("skipped: set RIGID_CROSSCHECK=1 (and RIGID_PYTHON) to run MuJoCo's loop");
        return;
    }
    let python = std::env::var("RIGID_PYTHON").unwrap_or_else(|_| "python3".into());
    // MuJoCo writes MUJOCO_LOG.TXT into the working folder on a warning: not into the crate
    let out = std::process::Command::new(&python)
        .current_dir(std::env::temp_dir())
        .arg(here().join("reference.py"))
        .arg("live")
        .output()
        .unwrap_or_else(|e| panic!("cannot run {python}: {e}"));
    assert!(
        out.status.success(),
        "reference.py live failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let mut counts: BTreeMap<String, Counts> = BTreeMap::new();
    let (mut failures, mut explained) = (Vec::new(), Vec::new());
    // files with <equality>, constraints made from them, equalities left out
    let mut equalities = [0usize; 3];
    // the largest relative error among the matching files: without and with mesh inertia
    let mut worst = [(0.0f64, String::new()), (0.0f64, String::new())];
    for line in String::from_utf8(out.stdout).unwrap().lines() {
        let row: Value = serde_json::from_str(line).unwrap();
        let package = row["package"].as_str().unwrap().to_string();
        let file = row["file"].as_str().unwrap().to_string();
        let c = counts.entry(package).or_default();
        c.files += 1;
        if row.get("error").is_some() {
            continue;
        }
        c.compiled += 1;
        let m = match load_mjcf(&file) {
            Ok(m) => m,
            Err(e) => {
                failures.push(format!("{file}: not loaded: {e}"));
                continue;
            }
        };
        c.loaded += 1;
        // the <equality> constraints convert (or are left out with a warning)
        match m.constraint_models() {
            Ok((cs, skipped)) if !m.equalities.is_empty() => {
                equalities[0] += 1;
                equalities[1] += cs.len();
                equalities[2] += skipped.len();
            }
            Ok(_) => {}
            Err(e) => failures.push(format!("{file}: equality constraints: {e}")),
        }
        let (err, what) = compare(&m, &row);
        let tol = tolerance(&row);
        if err <= tol {
            c.matching += 1;
            let w = &mut worst[usize::from(tol > 1e-9)];
            if err > w.0 {
                *w = (err, format!("{file}: {what}"));
            }
        } else if let Some(w) = m
            .warnings
            .iter()
            .find(|w| w.message.contains("tendon armature"))
        {
            explained.push(format!("{file}: {what} differs by {err:.1e}: {w}"));
        } else {
            failures.push(format!(
                "{file}: {what}: relative error {err:.2e} > {tol:e}"
            ));
        }
    }
    println!("package              files  compiled  loaded  matching");
    for (p, c) in &counts {
        println!(
            "{p:<20} {:>5} {:>9} {:>7} {:>9}",
            c.files, c.compiled, c.loaded, c.matching
        );
    }
    println!(
        "largest relative error where they match: {:.1e} ({}); with mesh inertia {:.1e} ({})",
        worst[0].0, worst[0].1, worst[1].0, worst[1].1
    );
    println!(
        "<equality>: {} files, {} constraints made, {} left out (each with a warning)",
        equalities[0], equalities[1], equalities[2]
    );
    for e in &explained {
        println!("explained: {e}");
    }
    for f in &failures {
        println!("FAILED: {f}");
    }
    assert!(
        counts.values().map(|c| c.compiled).sum::<usize>() > 0,
        "no MJCF file found"
    );
    assert!(failures.is_empty(), "{} files fail", failures.len());
}
