#!/usr/bin/env bash
# MuJoCo's live cross-check of the MJCF importer alone (crates/rigid/tests/it/mjcf.rs with
# RIGID_CROSSCHECK=1): loads every .xml file of the description packages that ship MJCF files
# (scripts/requirements-mjcf.txt) with MuJoCo and with rigid and compares M, qfrc_bias and the
# gravity forces at random states, printing the counts per package and every file that fails.
# It uses the test environment of scripts/test.sh (target/test-venv; run that once first), or the
# Python of RIGID_PYTHON. `bash scripts/test.sh` runs this check among all the others.
set -euo pipefail
cd "$(dirname "$0")/.."
python=${RIGID_PYTHON:-$PWD/target/test-venv/bin/python}
if [ ! -x "$python" ]; then
    echo "error: no test environment: run bash scripts/test.sh once (or set RIGID_PYTHON)" >&2
    exit 1
fi
RIGID_CROSSCHECK=1 RIGID_PYTHON="$python" cargo test -p rigid --test it mjcf -- --nocapture
