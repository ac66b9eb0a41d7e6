#!/usr/bin/env bash
# Coverage-guided fuzzing of rigid's readers with cargo fuzz (libFuzzer), on the stable toolchain:
#
#   bash scripts/fuzz.sh [SECONDS] [TARGET...]     (default: 60 s each, every target)
#   bash scripts/fuzz.sh merge [TARGET...]         (the working corpus into the committed seeds)
#
# Built optimised with debug assertions (overflow checks). Targets (fuzz/fuzz_targets/, entry points in crates/rigid/src/fuzzing.rs): urdf, spec, stl, obj,
# dae, cases, mjcf, sdf. Needs `cargo install cargo-fuzz` (a C++ compiler builds libFuzzer). The corpus grows
# in fuzz/corpus/TARGET/ (not committed); `merge` adds to fuzz/seeds/TARGET/ (committed) the
# inputs of the working corpus that reach code the seeds do not (edge coverage, libFuzzer's
# `-merge=1 -use_counters=0`: a few hundred files per target instead of thousands); a crash is saved
# in fuzz/artifacts/TARGET/: copy it to fuzz/regressions/TARGET/, fix the bug, and the test suite
# replays it from then on (crates/rigid/tests/it/fuzz_replay.rs). The executions of each run are
# appended to fuzz/runs.log (target, seconds, executions, crashes), which RELIABILITY.md sums up.
set -euo pipefail
cd "$(dirname "$0")/../fuzz"
seconds=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(urdf spec stl obj dae cases mjcf sdf)
export RUSTC_BOOTSTRAP=1   # cargo fuzz passes -Z flags; stable rustc accepts them with this
if [ "$seconds" = merge ]; then
    for t in "${targets[@]}"; do
        before=$(find "seeds/$t" -type f | wc -l)
        cargo fuzz run --sanitizer none -O --debug-assertions "$t" "seeds/$t" "corpus/$t" -- \
            -merge=1 -use_counters=0 -timeout=10 -rss_limit_mb=4096 -max_len=65536 >/dev/null 2>&1
        echo "$t: seeds $before -> $(find "seeds/$t" -type f | wc -l) files"
    done
    exit 0
fi
for t in "${targets[@]}"; do
    mkdir -p "corpus/$t" "artifacts/$t"
    log=$(mktemp)
    status=0
    cargo fuzz run --sanitizer none -O --debug-assertions "$t" "corpus/$t" -- \
        -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -max_len=65536 \
        -print_final_stats=1 >"$log" 2>&1 || status=$?
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -1)
    crashes=$(find "artifacts/$t" -type f | wc -l)
    echo "$(date -u +%FT%TZ) $t ${seconds}s executions=${execs:-?} exit=$status artifacts=$crashes" | tee -a runs.log
    if [ "$status" -ne 0 ]; then
        tail -40 "$log"
    fi
    rm -f "$log"
done
