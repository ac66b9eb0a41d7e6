//! `rigid bench`: the JSON contract (keys never renamed), the table, and clean failures.

use std::process::{Command, Output};

fn rigid(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(args)
        .output()
        .unwrap()
}

/// `rigid bench puma560 --batch --json` on one thread, one pass over 9 states (a partial last
/// pack for any width), then `extra`.
fn quick_batch(extra: &[&str]) -> Output {
    quick_batch_command(extra).output().unwrap()
}

/// The command of [`quick_batch`], to run with more (an environment).
fn quick_batch_command(extra: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_rigid"));
    c.args([
        "bench",
        "puma560",
        "--batch",
        "--json",
        "--threads",
        "1",
        "--repetitions",
        "1",
        "--states",
        "9",
    ])
    .args(extra);
    c
}

#[test]
fn bench_json_has_the_contract_keys() {
    let out = rigid(&[
        "bench",
        "puma560",
        "--json",
        "--repetitions",
        "1",
        "--states",
        "10",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["model"], "puma560");
    assert_eq!(v["nq"], 6);
    assert_eq!(v["nv"], 6);
    let t = v["ns_per_call"].as_object().unwrap();
    for key in [
        "forward_kinematics",
        "jacobians",
        "rnea",
        "gravity",
        "nonlinear_effects",
        "crba",
        "aba",
        "minverse",
    ] {
        let x = t[key].as_f64().unwrap_or_else(|| panic!("{key} missing"));
        assert!(x > 0.0 && x.is_finite(), "{key} = {x}");
    }
}

#[test]
fn bench_table_names_every_algorithm() {
    let out = rigid(&[
        "bench",
        "double_pendulum",
        "--repetitions",
        "1",
        "--states",
        "5",
    ]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    for key in ["rnea", "crba", "aba", "minverse", "jacobians"] {
        assert!(text.contains(key), "{text}");
    }
}

#[test]
fn bench_unknown_model_fails_cleanly() {
    let out = rigid(&["bench", "no_such_robot", "--json"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no_such_robot"));
}

/// `rigid bench --batch --json`: the lanes the batch uses (2, 4 or 8, a power of two), and per
/// algorithm the states per second of the loop of single calls and of each thread count, with
/// the speed-ups (positive, finite).
#[test]
fn bench_batch_json_reports_lanes_and_rates() {
    let out = quick_batch(&[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let lanes = v["lanes"].as_u64().unwrap();
    assert!([2, 4, 8].contains(&lanes), "lanes {lanes}");
    for algo in ["rnea", "aba", "crba", "crba_lower"] {
        let row = &v["states_per_second"][algo];
        for key in ["loop", "threads_1", "threads_1_vs_loop"] {
            let x = row[key].as_f64().unwrap_or_else(|| panic!("{algo}.{key}"));
            assert!(x > 0.0 && x.is_finite(), "{algo}.{key} = {x}");
        }
    }
}

/// `rigid bench --batch --lanes W`: the batch computes `W` states side by side whatever the
/// CPU's width, and says so; a width other than 2, 4 or 8 is refused with its value.
#[test]
fn bench_batch_lanes_forces_the_width() {
    let args = |w| ["--only", "rnea", "--lanes", w];
    for w in ["2", "4", "8"] {
        let out = quick_batch(&args(w));
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["lanes"].to_string(), w);
        assert!(
            v["states_per_second"]["rnea"]["threads_1"]
                .as_f64()
                .unwrap()
                > 0.0
        );
    }
    let out = quick_batch(&args("3"));
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--lanes must be 2, 4 or 8, not 3"), "{err}");
}

/// `rigid bench --batch --only`: only the named batch entry points are timed, and a name that is
/// not one of them is refused with its name.
#[test]
fn bench_batch_only_times_the_named_entry_points() {
    let out = quick_batch(&["--only", "rnea,crba_lower"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let keys: Vec<&String> = v["states_per_second"].as_object().unwrap().keys().collect();
    assert_eq!(keys, ["crba_lower", "rnea"]);
    let out = quick_batch(&["--only", "minverse"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("minverse"), "{err}");
}

/// `RIGID_LANES=W` sets the width the batch takes when `--lanes` is not given (the JSON's
/// `lanes`); a value other than 2, 4 or 8 is named on stderr and the CPU's width is used.
#[test]
fn rigid_lanes_sets_the_default_width() {
    let run = |lanes: &str| {
        quick_batch_command(&["--only", "rnea"])
            .env("RIGID_LANES", lanes)
            .output()
            .unwrap()
    };
    for w in ["2", "4", "8"] {
        let out = run(w);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(v["lanes"].to_string(), w);
    }
    let out = run("3");
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("RIGID_LANES=\"3\" is not 2, 4 or 8"), "{err}");
}
