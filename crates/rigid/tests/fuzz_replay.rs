//! Replays the fuzzers' corpora (`fuzz/corpus/TARGET/`: the seeds and what `cargo fuzz` kept as
//! covering new code) and every crash found so far (`fuzz/regressions/TARGET/`) through the same
//! entry points the fuzz targets call (`rigid::fuzzing`), without fuzzing: no input may panic.
//! How the fuzzing is run and what it found: RELIABILITY.md.

use std::path::PathBuf;

type Target = fn(&[u8]);

const TARGETS: [(&str, Target); 6] = [
    ("urdf", rigid::fuzzing::urdf),
    ("spec", rigid::fuzzing::spec),
    ("stl", rigid::fuzzing::stl),
    ("obj", rigid::fuzzing::obj),
    ("dae", rigid::fuzzing::dae),
    ("cases", rigid::fuzzing::cases),
];

#[test]
fn every_fuzz_corpus_and_regression_file_runs_without_a_panic() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fuzz");
    let mut failures = Vec::new();
    let mut count = 0;
    for (name, target) in TARGETS {
        let mut files = 0;
        for dir in ["corpus", "regressions"] {
            let Ok(entries) = std::fs::read_dir(root.join(dir).join(name)) else {
                continue;
            };
            for entry in entries.flatten() {
                let path = entry.path();
                let data = std::fs::read(&path).unwrap();
                if std::panic::catch_unwind(|| target(&data)).is_err() {
                    failures.push(path.display().to_string());
                }
                files += 1;
            }
        }
        assert!(files > 0, "no corpus for fuzz target {name}");
        count += files;
    }
    eprintln!("{count} fuzz inputs replayed");
    assert!(failures.is_empty(), "panics on: {failures:#?}");
}
