//! Replays the fuzzers' committed corpora (`fuzz/seeds/TARGET/`: the seeds, and what fuzzing kept
//! as covering new code, minimised), every crash found so far (`fuzz/regressions/TARGET/`) and,
//! when present, the working corpus of a local fuzzing run (`fuzz/corpus/TARGET/`, not
//! committed) through the same entry points the fuzz targets call (`rigid::fuzzing`), without
//! fuzzing: no input may panic.
//! How the fuzzing is run and what it found: RELIABILITY.md.

use std::path::PathBuf;

type Target = fn(&[u8]);

const TARGETS: [(&str, Target); 8] = [
    ("urdf", rigid::fuzzing::urdf),
    ("spec", rigid::fuzzing::spec),
    ("stl", rigid::fuzzing::stl),
    ("obj", rigid::fuzzing::obj),
    ("dae", rigid::fuzzing::dae),
    ("cases", rigid::fuzzing::cases),
    ("mjcf", rigid::fuzzing::mjcf),
    ("sdf", rigid::fuzzing::sdf),
];

#[test]
fn every_fuzz_corpus_and_regression_file_runs_without_a_panic() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fuzz");
    let mut failures = Vec::new();
    let mut count = 0;
    for (name, target) in TARGETS {
        let mut files = 0;
        for dir in ["seeds", "regressions", "corpus"] {
            let Ok(entries) = std::fs::read_dir(root.join(dir).join(name)) else {
                continue;
            };
            for entry in entries.flatten() {
                let path = entry.path();
                let Ok(data) = std::fs::read(&path) else {
                    continue; // removed by a running fuzzer
                };
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
