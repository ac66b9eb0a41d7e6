//! The malformed-input corpus (`tests/corpus/`, written by `tests/corpus/make_corpus.py`): every
//! file through the library (no panic; an error where the CLI must fail) and through the CLI
//! (exit code 2 and exactly one `error:` line naming the thing and what is wrong, or the
//! expected warning; never `panicked`; no output file left behind), plus inputs too large to keep
//! as files (a 10 MB attribute, a 10 000-joint chain, 100 000 nested elements), made here.

use rigid::io::mesh_file::read_mesh;
use rigid::io::spec::read_spec;
use rigid::io::urdf::{load_urdf_with, UrdfOptions};
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn corpus_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/corpus")
}

/// Runs `rigid` with `args`, killing it after 60 s (a hang is a failure too). The output is read
/// by `wait_with_output` on another thread, so that a large output cannot block the child.
fn rigid(args: &[String]) -> Output {
    let child = Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run rigid");
    let id = child.id();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(child.wait_with_output());
    });
    match rx.recv_timeout(Duration::from_secs(60)) {
        Ok(out) => out.expect("output"),
        Err(_) => {
            let _ = Command::new("kill").arg("-9").arg(id.to_string()).status();
            panic!("rigid {args:?} did not finish in 60 s");
        }
    }
}

struct Case {
    file: PathBuf,
    args: Vec<String>,
    status: String,
    contains: Vec<String>,
    out: PathBuf,
}

fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    let tmp = std::env::temp_dir().join(format!("rigid-corpus-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    for kind in [
        "urdf", "spec", "mesh", "cases", "samples", "cli", "mjcf", "sdf",
    ] {
        let dir = corpus_dir().join(kind);
        let mut entries: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|e| e == "expect"))
            .collect();
        entries.sort();
        for expect in entries {
            let stem = expect.file_stem().unwrap().to_string_lossy().to_string();
            let text = std::fs::read_to_string(&expect).unwrap();
            let field = |k: &str| {
                text.lines()
                    .find_map(|l| l.strip_prefix(k))
                    .unwrap_or_default()
                    .trim()
                    .to_string()
            };
            let file = std::fs::read_dir(&dir)
                .unwrap()
                .flatten()
                .map(|e| e.path())
                .find(|p| {
                    p.file_stem().is_some_and(|s| s.to_string_lossy() == stem)
                        && p.extension().is_some_and(|e| e != "expect" && e != "toml")
                        || (kind == "spec"
                            && p.file_stem().is_some_and(|s| s.to_string_lossy() == stem)
                            && p.extension().is_some_and(|e| e == "toml"))
                })
                .unwrap_or_else(|| panic!("no file for {}", expect.display()));
            let out_path = tmp.join(format!("{kind}-{stem}.out"));
            let args = field("args:")
                .split_whitespace()
                .map(|a| {
                    a.replace("{file}", file.to_str().unwrap())
                        .replace("{dir}", dir.to_str().unwrap())
                        .replace("{out}", out_path.to_str().unwrap())
                })
                .collect();
            let contains = field("contains:")
                .split(" | ")
                .map(str::to_string)
                .filter(|s| !s.is_empty())
                .collect();
            out.push(Case {
                file,
                args,
                status: field("status:"),
                contains,
                out: out_path,
            });
        }
    }
    out
}

/// Checks one CLI run against its expectation; `Err` says what is wrong.
fn check(c: &Case, o: &Output) -> Result<(), String> {
    let stdout = String::from_utf8_lossy(&o.stdout);
    let stderr = String::from_utf8_lossy(&o.stderr);
    if stdout.contains("panicked") || stderr.contains("panicked") {
        return Err(format!("panicked:\n{stderr}"));
    }
    let has_all = |line: &str| c.contains.iter().all(|s| line.contains(s.as_str()));
    match c.status.as_str() {
        "error" => {
            if o.status.code() != Some(2) {
                return Err(format!(
                    "exit code {:?}, expected 2:\n{stderr}",
                    o.status.code()
                ));
            }
            let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
            if errors.len() != 1 {
                return Err(format!(
                    "{} `error:` lines, expected 1:\n{stderr}",
                    errors.len()
                ));
            }
            if !has_all(errors[0]) {
                return Err(format!("error line lacks {:?}: {}", c.contains, errors[0]));
            }
            if c.out.exists() {
                return Err(format!("output {} left behind", c.out.display()));
            }
        }
        "warning" => {
            if !o.status.success() {
                return Err(format!("failed, expected a warning:\n{stderr}"));
            }
            let found = stdout
                .lines()
                .chain(stderr.lines())
                .any(|l| l.contains("warning") && has_all(l));
            if !found {
                return Err(format!(
                    "no warning with {:?}:\n{stdout}\n{stderr}",
                    c.contains
                ));
            }
        }
        "ok" => {
            if !o.status.success() {
                return Err(format!("failed, expected success:\n{stderr}"));
            }
        }
        s => return Err(format!("unknown status {s}")),
    }
    Ok(())
}

/// The library entry point for the file, when there is one: `Some(is_err)`; panics are caught
/// and reported.
fn library(c: &Case) -> Result<Option<bool>, String> {
    let path = c.file.clone();
    let kind = path
        .parent()
        .unwrap()
        .file_name()
        .unwrap()
        .to_string_lossy()
        .to_string();
    let default_model = c.args.len() == 2 && c.args[0] == "model";
    let result = std::panic::catch_unwind(move || match kind.as_str() {
        "urdf" if default_model => Some(load_urdf_with(&path, &UrdfOptions::default()).is_err()),
        "mjcf" if default_model => Some(rigid::io::mjcf::load_mjcf(&path).is_err()),
        "sdf" if default_model => Some(rigid::io::sdf::load_sdf(&path).is_err()),
        "spec" => Some(read_spec(&path).is_err()),
        "mesh" if path.extension().is_some_and(|e| e != "toml") => Some(
            read_mesh(&path)
                .map_err(|e| e.to_string())
                .and_then(|m| m.mass_properties().map_err(|e| e.to_string()))
                .is_err(),
        ),
        _ => None,
    });
    result.map_err(|_| "the library panicked".to_string())
}

#[test]
fn every_corpus_file_gives_its_named_error_and_never_a_panic() {
    let cases = cases();
    let files = cases.len();
    assert!(files >= 150, "only {files} corpus cases");
    let mut failures = Vec::new();
    for c in &cases {
        let tag = c
            .file
            .strip_prefix(corpus_dir())
            .unwrap_or(&c.file)
            .display()
            .to_string();
        let o = rigid(&c.args);
        if let Err(e) = check(c, &o) {
            failures.push(format!("{tag}: {e}"));
        }
        match library(c) {
            Err(e) => failures.push(format!("{tag}: {e}")),
            Ok(Some(is_err)) if c.status == "error" && !is_err => {
                failures.push(format!("{tag}: the library accepts what the CLI refuses"));
            }
            _ => {}
        }
    }
    eprintln!("{files} corpus cases, {} failures", failures.len());
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

fn write_tmp(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigid-corpus-big-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

fn run(args: &[&str]) -> Output {
    rigid(&args.iter().map(|s| (*s).to_string()).collect::<Vec<_>>())
}

fn assert_clean(o: &Output, ok: bool, what: &str) {
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!stderr.contains("panicked"), "{what}: {stderr}");
    assert_eq!(o.status.success(), ok, "{what}: {stderr}");
    if !ok {
        assert_eq!(o.status.code(), Some(2), "{what}: {stderr}");
        assert_eq!(
            stderr.lines().filter(|l| l.starts_with("error:")).count(),
            1,
            "{what}: {stderr}"
        );
    }
}

#[test]
fn a_ten_megabyte_attribute_is_refused_quickly() {
    let big = "9".repeat(10 << 20);
    let text = format!(
        "<robot name=\"r\"><link name=\"a\"/><link name=\"b\"/><joint name=\"j\" \
         type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/><origin xyz=\"{big} 0 0\"/>\
         </joint></robot>"
    );
    let p = write_tmp("big_attribute.urdf", &text);
    let start = Instant::now();
    let o = run(&["model", p.to_str().unwrap()]);
    assert_clean(&o, false, "10 MB attribute");
    assert!(String::from_utf8_lossy(&o.stderr).contains("non-finite"));
    assert!(start.elapsed() < Duration::from_secs(20));
}

#[test]
fn a_ten_thousand_joint_chain_loads_and_evaluates() {
    let n = 10_000;
    let mut text = String::from("<robot name=\"chain\">\n<link name=\"l0\"/>\n");
    for i in 1..=n {
        text.push_str(&format!(
            "<link name=\"l{i}\"><inertial><origin xyz=\"0 0 0.01\"/><mass value=\"0.01\"/>\
             <inertia ixx=\"1e-6\" iyy=\"1e-6\" izz=\"1e-6\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>\
             </inertial></link>\n<joint name=\"j{i}\" type=\"continuous\"><parent \
             link=\"l{}\"/><child link=\"l{i}\"/><origin xyz=\"0 0 0.02\"/><axis xyz=\"0 1 \
             0\"/></joint>\n",
            i - 1
        ));
    }
    text.push_str("</robot>\n");
    let p = write_tmp("chain.urdf", &text);
    let o = run(&["model", p.to_str().unwrap()]);
    assert_clean(&o, true, "10 000-joint chain");
    assert!(String::from_utf8_lossy(&o.stdout).contains("nq = 10000, nv = 10000"));
    // the recursions are loops, not calls: no stack overflow at depth 10 000
    let model = rigid::io::urdf::load_urdf(&p, false).unwrap();
    let mut data = rigid::multibody::Data::new(&model);
    let q = vec![0.001; model.nq()];
    let v = vec![0.01; model.nv()];
    let tau = rigid::multibody::rnea(&model, &mut data, &q, &v, &v)
        .unwrap()
        .clone();
    assert!(tau.iter().all(|x| x.is_finite()));
    let a = rigid::multibody::aba(&model, &mut data, &q, &v, tau.as_slice())
        .unwrap()
        .clone();
    assert!(a.iter().all(|x| x.is_finite()));
    // ABA's answer satisfies the equations of motion: rnea(q, v, aba(τ)) = τ (the backward error;
    // the forward error |aba(rnea(a)) - a| is as large as the condition number of this 10 000-
    // body chain's mass matrix, ~1e12 between its largest and smallest diagonal entries, allows)
    let back = rigid::multibody::rnea(&model, &mut data, &q, &v, a.as_slice()).unwrap();
    let scale = tau.amax();
    let err = (back - &tau).amax() / scale;
    assert!(err < 1e-9, "rnea(aba(tau)) - tau = {err:e} relative");
}

#[test]
fn deeply_nested_xml_is_refused_not_a_stack_overflow() {
    let depth = 100_000;
    let text = format!(
        "<robot name=\"r\"><link name=\"a\">{}{}</link></robot>",
        "<x>".repeat(depth),
        "</x>".repeat(depth)
    );
    let p = write_tmp("nested.urdf", &text);
    let o = run(&["model", p.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        !stderr.contains("panicked") && !stderr.contains("overflow"),
        "{stderr}"
    );
    assert!(o.status.code().is_some(), "killed by a signal: {stderr}");
}

#[test]
fn the_corpus_is_what_its_generator_writes() {
    // the generator is the corpus's documentation: it must still write these files, byte for
    // byte but for the numbers it computes with libm (the swinging pendulum's samples/*.csv:
    // `math.sin`, `math.cos`), which another machine may round differently ([`same_file`]).
    // It runs in Python: a live check.
    if !crate::common::live("tests/corpus/make_corpus.py") {
        return;
    }
    let out = std::env::temp_dir().join(format!("rigid-corpus-gen-{}", std::process::id()));
    let py = crate::common::python();
    let status = Command::new(&py)
        .arg(corpus_dir().join("make_corpus.py"))
        .arg(&out)
        .stdout(Stdio::null())
        .status()
        .unwrap_or_else(|e| panic!("cannot run {py} ({e}): RIGID_CROSSCHECK=1 needs Python 3"));
    assert!(status.success());
    let mut n = 0;
    for kind in [
        "urdf", "spec", "mesh", "cases", "samples", "cli", "mjcf", "sdf",
    ] {
        let mut made: Vec<_> = std::fs::read_dir(out.join(kind))
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        let mut kept: Vec<_> = std::fs::read_dir(corpus_dir().join(kind))
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        made.sort();
        kept.sort();
        assert_eq!(made, kept, "{kind}: run tests/corpus/make_corpus.py");
        for name in made {
            let a = std::fs::read(out.join(kind).join(&name)).unwrap();
            let b = std::fs::read(corpus_dir().join(kind).join(&name)).unwrap();
            assert!(
                same_file(&a, &b),
                "{kind}/{name:?} differs: run tests/corpus/make_corpus.py"
            );
            n += 1;
        }
    }
    assert!(n >= 300, "{n} files");
}

/// `a` and `b` are the same file: the same bytes, or the same text but for numbers that agree to
/// 1e-12 relative (the last digits of a `repr` of a libm result).
fn same_file(a: &[u8], b: &[u8]) -> bool {
    if a == b {
        return true;
    }
    let (Ok(a), Ok(b)) = (std::str::from_utf8(a), std::str::from_utf8(b)) else {
        return false;
    };
    let split = |s: &str| -> Vec<String> {
        s.split(|c: char| c == ',' || c.is_whitespace())
            .map(str::to_string)
            .collect()
    };
    let (ta, tb) = (split(a), split(b));
    // the delimiters themselves must agree
    let delimiters = |s: &str| -> String {
        s.chars()
            .filter(|&c| c == ',' || c.is_whitespace())
            .collect()
    };
    ta.len() == tb.len()
        && delimiters(a) == delimiters(b)
        && ta.iter().zip(&tb).all(|(x, y)| {
            x == y
                || match (x.parse::<f64>(), y.parse::<f64>()) {
                    (Ok(p), Ok(q)) => (p - q).abs() <= 1e-12 * p.abs().max(q.abs()).max(1.0),
                    _ => false,
                }
        })
}
