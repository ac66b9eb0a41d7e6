#!/usr/bin/env bash
# Runs every test of rigid. Installs the Python packages the cross-checks need (Pinocchio,
# example-robot-data and pytest from PyPI) if they are missing, runs the Rust test suite, then
# builds and installs the Python module (`pip install ./crates/rigid-py`, the README's command)
# and runs its tests against Pinocchio.
set -euo pipefail
cd "$(dirname "$0")/.."
export PIP_ROOT_USER_ACTION=ignore PIP_DISABLE_PIP_VERSION_CHECK=1
pip() { python3 -m pip --quiet "$@"; }
pip install -r scripts/requirements-test.txt
cargo test --workspace
start=$(date +%s)
pip install ./crates/rigid-py
echo "pip install ./crates/rigid-py: $(($(date +%s) - start)) s"
# from the tests' folder, so that `import rigid` is the installed module
(cd crates/rigid-py/tests && python3 -m pytest -q -p no:cacheprovider .)
