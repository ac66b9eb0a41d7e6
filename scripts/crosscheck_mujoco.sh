#!/usr/bin/env bash
# MuJoCo's live cross-check of the MJCF importer (crates/rigid/tests/mjcf.rs with
# RIGID_CROSSCHECK=1): installs MuJoCo and the description packages that ship MJCF files
# (gymnasium, dm-control, robosuite, brax, mujoco-mjx, metaworld, gymnasium-robotics; --no-deps,
# only their model files are read) into the Python of RIGID_PYTHON (default python3), then loads
# every .xml file of them with MuJoCo and with rigid and compares M, qfrc_bias and the gravity
# forces at random states, printing the counts per package and every file that fails.
set -euo pipefail
cd "$(dirname "$0")/.."
python=${RIGID_PYTHON:-python3}
export PIP_ROOT_USER_ACTION=ignore PIP_DISABLE_PIP_VERSION_CHECK=1
"$python" -m pip install --quiet mujoco==4.0.0 numpy
"$python" -m pip install --quiet --no-deps gymnasium==1.4.0 dm-control==1.0.50 robosuite==1.5.2 \
    brax==0.14.2 mujoco-mjx==3.17.0 metaworld==3.1.1 gymnasium-robotics==1.4.2
RIGID_CROSSCHECK=1 RIGID_PYTHON="$python" cargo test -p rigid --test mjcf -- --nocapture
