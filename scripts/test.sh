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
# the physically consistent identification (crate feature `sdp`) links OpenBLAS from the system:
# tested when it is there (.ci/run installs it)
features=()
if pkg-config --exists openblas 2>/dev/null; then
    features=(--features rigid/sdp,rigid-cli/sdp,rigid-py/sdp)
    export MATURIN_PEP517_ARGS="--features sdp"
else
    echo "note: no OpenBLAS (pkg-config openblas): the physically consistent identification is" \
        "not built nor tested; apt-get install libopenblas-dev libgfortran-12-dev pkg-config"
fi
cargo test --workspace ${features[@]+"${features[@]}"}
start=$(date +%s)
pip install ./crates/rigid-py
echo "pip install ./crates/rigid-py: $(($(date +%s) - start)) s"
# from the tests' folder, so that `import rigid` is the installed module
(cd crates/rigid-py/tests && python3 -m pytest -q -p no:cacheprovider .)
