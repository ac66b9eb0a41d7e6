#!/usr/bin/env python3
"""Generate packages.json and regressor.json: Pinocchio's rnea, crba, aba (packages.py) and its
joint-torque regressor (regressor.py) on the URDF files checked in under
crates/rigid/tests/fixtures/robots/, the fixtures of the default (hermetic) run of
crates/rigid/tests/it/pinocchio_packages.rs and identification_packages.rs.

    python3 -m venv /tmp/v && /tmp/v/bin/pip install -r scripts/requirements-test.txt
    /tmp/v/bin/python crates/rigid/tests/pinocchio/gen_packages.py

writes crates/rigid/tests/pinocchio/packages.json and regressor.json (`--check` instead compares
a fresh generation with the committed files, to gen_reference.py's CHECK_TOLERANCE relative to
each quantity's largest entry, prints what differs and exits 1 if anything does).

Each file is one JSON record a line, as `packages.py PACKAGE` (resp. `regressor.py PACKAGE`)
prints, for the files of FILES only, fixed and floating, with "file" relative to the package's
folder (the tests read the copy under tests/fixtures/robots/<package>/, gen_robots.py). The
seeds are the live run's (packages.py 11, regressor.py 3), with one random state per file and
base (the first state of the live run's) to keep the fixtures small. The live run
(RIGID_CROSSCHECK=1) walks every URDF file of the installed packages, with 3 (resp. 2) states;
these are a few files per package (the copyleft packages icub-models and gym-ignition-models are
not copied, so they are checked live only).
"""

import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import packages  # noqa: E402
import regressor  # noqa: E402
from gen_reference import differences  # noqa: E402

# package: files under its folder (a subset of tests/fixtures/robots/gen_robots.py's FILES)
FILES = {
    "example-robot-data": [
        "ur_description/urdf/ur5_robot.urdf",
        "panda_description/urdf/panda.urdf",
        "solo_description/robots/solo12.urdf",
        "double_pendulum_description/urdf/double_pendulum.urdf",
    ],
    "upkie-description": ["urdf/upkie.urdf"],
    "jvrc-description": ["urdf/jvrc1.urdf"],
    "airo-models": ["arms/ur5e/ur5e.urdf", "grippers/robotiq_2f_85/urdf/robotiq_2f_85.urdf"],
    "cookie-description": ["urdf/cookie.urdf"],
}
# the regressor on example-robot-data only, as identification_packages.rs (the free-flyer rows
# are covered by the floating UR5 and Panda)
REGRESSOR_FILES = {
    "example-robot-data": [
        "ur_description/urdf/ur5_robot.urdf",
        "panda_description/urdf/panda.urdf",
        "double_pendulum_description/urdf/double_pendulum.urdf",
    ],
}

OUTPUTS = {
    "packages.json": (packages.one, 1, 11, FILES),
    "regressor.json": (regressor.one, 1, 3, REGRESSOR_FILES),
}


def records(one, states, seed, files):
    out = []
    for package, rels in files.items():
        root = packages.PACKAGES[package]()
        if root is None:
            sys.exit(f"{package} is not installed: pip install -r scripts/requirements-test.txt")
        for rel in rels:
            for floating in (False, True):
                rec = dict(package=package, file=rel, floating=floating)
                rec.update(one(os.path.join(root, rel), floating, states, seed))
                out.append(packages.plain(rec))
    return out


def main():
    check = "--check" in sys.argv[1:]
    failed = False
    for name, (one, states, seed, files) in OUTPUTS.items():
        recs = records(one, states, seed, files)
        text = "".join(json.dumps(r) + "\n" for r in recs)
        path = os.path.join(HERE, name)
        if check:
            with open(path) as f:
                committed = [json.loads(line) for line in f]
            diff = differences([json.loads(line) for line in text.splitlines()], committed,
                               name)
            for d in diff:
                print(d)
            failed |= bool(diff)
            continue
        with open(path, "w") as f:
            f.write(text)
        print(f"wrote {path} ({len(recs)} records, {os.path.getsize(path)} bytes)",
              file=sys.stderr)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
