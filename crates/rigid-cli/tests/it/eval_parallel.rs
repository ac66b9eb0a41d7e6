//! `rigid eval` on a large case file (evaluated on every core) gives, in order, exactly the
//! results of evaluating each case alone.

use std::process::Command;

fn eval(dir: &std::path::Path, name: &str, cases: &[serde_json::Value]) -> serde_json::Value {
    let file = dir.join(name);
    std::fs::write(&file, serde_json::json!({ "cases": cases }).to_string()).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rigid"))
        .args(["eval", "puma560", "--json", "--cases"])
        .arg(&file)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn large_case_files_keep_order_and_equal_single_cases() {
    let dir = std::env::temp_dir().join(format!("rigid-eval-parallel-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases: Vec<_> = (0..100)
        .map(|k| {
            let x = k as f64 * 0.037;
            let q: Vec<f64> = (0..6).map(|i| (x + i as f64).sin()).collect();
            let v: Vec<f64> = (0..6).map(|i| (2.0 * x - i as f64).cos()).collect();
            serde_json::json!({ "q": q, "v": v, "a": q, "tau": v })
        })
        .collect();
    let all = eval(&dir, "all.json", &cases);
    let results = all["results"].as_array().unwrap();
    assert_eq!(results.len(), 100);
    for k in [0, 1, 50, 63, 64, 99] {
        let one = eval(&dir, &format!("one{k}.json"), &cases[k..k + 1]);
        assert_eq!(results[k], one["results"][0], "case {k}");
    }
}
