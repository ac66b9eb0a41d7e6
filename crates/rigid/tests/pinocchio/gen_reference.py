#!/usr/bin/env python3
"""Generate reference.json: Pinocchio's results on the robots of reference.py, the fixture of the
default (hermetic) run of crates/rigid/tests/it/pinocchio.rs and of rigid-cli's
tests/it/eval_pinocchio.rs.

    python3 -m venv /tmp/v && /tmp/v/bin/pip install -r scripts/requirements-test.txt
    /tmp/v/bin/python crates/rigid/tests/pinocchio/gen_reference.py

writes crates/rigid/tests/pinocchio/reference.json (`--check` instead compares a fresh
generation with the committed file, to CHECK_TOLERANCE, prints what differs and exits 1 if
anything does).

For every robot of reference.py's ROBOTS: `reference(robot, STATES, SEED, derivatives=True)`,
the object `python3 reference.py ROBOT --states STATES --seed SEED --derivatives` prints (in
rigid's conventions, see reference.py), with its "urdf" made portable: the robot's path under
example-robot-data's robots/ folder (the tests read the copy under
tests/fixtures/robots/example-robot-data/robots/, gen_robots.py), or "local:all_joints.urdf"
(beside this script). One robot per line. The live run (RIGID_CROSSCHECK=1) draws more states
(8) from Pinocchio itself; this fixture keeps a few per robot, to stay small: STATES states, the
first of which carries the derivatives; TALOS (nv = 50, whose derivative matrices alone would be
0.5 MB) one state without derivatives (its derivatives are checked against finite differences by
tests/it/multibody_derivatives.rs, and against Pinocchio by the live run).

The numbers come from Pinocchio and numpy: the tests compare rigid with them to a relative
tolerance (1e-9, as the live check), and `--check` (run by the live tests) compares a fresh
generation with the committed file to CHECK_TOLERANCE relative to each quantity's largest entry
(at least 1), never bit for bit: another machine's compiler, CPU or library versions may round
differently, and ill-conditioned quantities (M⁻¹, ABA) amplify that.
"""

import json
import os
import sys
from importlib import metadata

import numpy as np
import pinocchio as pin

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from reference import ROBOTS, reference  # noqa: E402

STATES = 2
SEED = 7
# robot: number of states kept, without derivatives
LEAN = {"talos": 1}
OUT = os.path.join(HERE, "reference.json")
# --check: the tests' own tolerance against rigid
CHECK_TOLERANCE = 1e-9


def generate():
    robots = {}
    for name in sorted(ROBOTS):
        r = reference(name, STATES, SEED, derivatives=name not in LEAN)
        r["urdf"] = ROBOTS[name][0]
        if name in LEAN:
            r["states"] = r["states"][: LEAN[name]]
        for st in r["states"][1:]:
            st.pop("derivatives", None)
        robots[name] = r
    head = dict(
        generator="crates/rigid/tests/pinocchio/gen_reference.py",
        pinocchio_version=pin.__version__,
        example_robot_data_version=metadata.version("example-robot-data"),
        numpy_version=np.__version__,
        states=STATES,
        seed=SEED,
    )
    return head, robots


def dump(head, robots):
    lines = [json.dumps(head)[:-1] + ', "robots": {']
    items = [f"{json.dumps(k)}: {json.dumps(v)}" for k, v in robots.items()]
    lines.append(",\n".join(items))
    lines.append("}}")
    return "\n".join(lines) + "\n"


def differences(a, b, path="", tol=CHECK_TOLERANCE):
    """Where `a` and `b` differ: structure, strings and integers exactly, arrays of floats to
    `tol` relative to the larger of their largest entries (at least 1)."""
    out = []
    if isinstance(a, dict) and isinstance(b, dict):
        if sorted(a) != sorted(b):
            return [f"{path}: keys {sorted(a)} vs {sorted(b)}"]
        for k in a:
            out += differences(a[k], b[k], f"{path}/{k}", tol)
        return out
    num = (int, float)
    flat = lambda x: np.asarray(x, dtype=float).ravel()  # noqa: E731
    numeric = lambda x: isinstance(x, num) and not isinstance(x, bool) or (  # noqa: E731
        isinstance(x, list) and all(numeric(y) for y in x))
    if numeric(a) and numeric(b) and not (isinstance(a, int) and isinstance(b, int)):
        fa, fb = flat(a), flat(b)
        if fa.shape != fb.shape:
            return [f"{path}: shapes {fa.shape} vs {fb.shape}"]
        scale = max(1.0, float(np.max(np.abs(fb), initial=0.0)), float(np.max(np.abs(fa), initial=0.0)))
        err = float(np.max(np.abs(fa - fb), initial=0.0)) / scale
        return [f"{path}: {err:.2e} relative"] if not err <= tol else []
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f"{path}: lengths {len(a)} vs {len(b)}"]
        for i, (x, y) in enumerate(zip(a, b)):
            out += differences(x, y, f"{path}/{i}", tol)
        return out
    return [] if a == b else [f"{path}: {a!r} vs {b!r}"]


def main():
    head, robots = generate()
    if "--check" in sys.argv[1:]:
        with open(OUT) as f:
            committed = json.load(f)
        diff = differences(json.loads(dump(head, robots))["robots"], committed["robots"])
        for d in diff:
            print(d)
        sys.exit(1 if diff else 0)
    with open(OUT, "w") as f:
        f.write(dump(head, robots))
    print(f"wrote {OUT} ({os.path.getsize(OUT)} bytes)", file=sys.stderr)


if __name__ == "__main__":
    main()
