#!/usr/bin/env bash
# Runs every test of rigid. Installs the Python packages the cross-checks need (Pinocchio and
# example-robot-data from PyPI) if they are missing, then runs the Rust test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -m pip install --quiet --disable-pip-version-check -r scripts/requirements-test.txt
cargo test --workspace
