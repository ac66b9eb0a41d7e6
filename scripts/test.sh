#!/usr/bin/env bash
# Runs every test of rigid, the live cross-checks included.
#
# `cargo test --workspace` alone needs nothing but Rust: the cross-checks against Pinocchio,
# SciPy and the robot-description packages read checked-in fixtures. This script also turns on
# the live checks (RIGID_CROSSCHECK=1): it creates a virtual environment (target/test-venv, on
# its first run; `python3 -m venv`) with the Python packages they need
# (scripts/requirements-test.txt: Pinocchio, MuJoCo, example-robot-data, SciPy, pytest, the
# description packages; scripts/requirements-mjcf.txt, without their dependencies: the packages
# whose MJCF files MuJoCo's cross-check loads), points RIGID_PYTHON at it, runs the Rust tests, then builds and installs the Python
# module into the same environment (`pip install ./crates/rigid-py`, the README's command) and
# runs its tests against Pinocchio. Nothing is installed into the system's Python. The live
# checks also use a C compiler, rustfmt, a browser (`chromium`) and OpenBLAS: scripts/setup.sh,
# run first, installs the system packages that are missing (apt-get, as root) or says which
# ones to install and stops.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export PIP_DISABLE_PIP_VERSION_CHECK=1
venv=target/test-venv
requirements=scripts/requirements-test.txt
mjcf_packages=scripts/requirements-mjcf.txt
if [ ! -x "$venv/bin/python" ]; then
    echo "creating the test environment $venv (python3 -m venv)"
    rm -rf "$venv"
    mkdir -p target
    python3 -m venv "$venv" || {
        echo "error: python3 -m venv failed: install Python 3 with venv (Debian:" \
            "apt-get install python3-venv)" >&2
        exit 1
    }
fi
python="$PWD/$venv/bin/python"
# (re)install the pinned packages when the requirements changed since the last install
stamp="$venv/requirements.sha256"
if ! sha256sum --status -c "$stamp" 2>/dev/null; then
    "$python" -m pip install --quiet -r "$requirements"
    "$python" -m pip install --quiet --no-deps -r "$mjcf_packages"
    sha256sum "$requirements" "$mjcf_packages" > "$stamp"
fi
export RIGID_PYTHON="$python" RIGID_CROSSCHECK=1
# the physically consistent identification (crate feature `sdp`) links OpenBLAS from the system
# (scripts/setup.sh installed it)
export MATURIN_PEP517_ARGS="--features sdp"
cargo test --workspace --features rigid/sdp,rigid-cli/sdp,rigid-py/sdp
start=$(date +%s)
"$python" -m pip install --quiet ./crates/rigid-py
echo "pip install ./crates/rigid-py: $(($(date +%s) - start)) s"
# from the tests' folder, so that `import rigid` is the installed module
(cd crates/rigid-py/tests && "$python" -m pytest -q -p no:cacheprovider .)
